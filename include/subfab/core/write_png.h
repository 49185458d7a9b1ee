// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_png.h
//! The one PNG writer (8-bit RGB, zlib-compressed), enough for previews
//! (unfold's nets, mill's block maps, view's assembly pictures) without an
//! image library.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace subfab {

//! An RGB image, rows top to bottom, 3 bytes per pixel.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;
  RgbImage(int w, int h, std::uint8_t fill = 255) : width(w), height(h), pixels(std::size_t(w) * h * 3, fill) {}
  void set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::uint8_t* p = &pixels[(std::size_t(y) * width + x) * 3];
    p[0] = r;
    p[1] = g;
    p[2] = b;
  }
};

//! Encodes `image` as PNG bytes (8-bit RGB, zlib level 9, no row filter).
//! \throw AlgorithmError when zlib fails.
std::vector<std::uint8_t> encode_png(const RgbImage& image);

//! Writes `image` as a PNG file. \throw IoError when the file cannot be written.
void write_png(const RgbImage& image, const std::filesystem::path& path);

}  // namespace subfab
