// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/core/write_png.h"

#include <zlib.h>

#include <fstream>

#include "subfab/core/error.h"

namespace subfab {

namespace {

void append_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.insert(out.end(), {std::uint8_t(v >> 24), std::uint8_t(v >> 16), std::uint8_t(v >> 8), std::uint8_t(v)});
}

//! Appends a PNG chunk: length, type, data, CRC of type and data (zlib's crc32).
void append_chunk(std::vector<std::uint8_t>& png, const char (&type)[5], const std::vector<std::uint8_t>& data) {
  append_be32(png, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data.begin(), data.end());
  append_be32(png, static_cast<std::uint32_t>(crc32(0L, png.data() + start, static_cast<uInt>(png.size() - start))));
}

}  // namespace

std::vector<std::uint8_t> encode_png(const RgbImage& image) {
  const std::size_t row_bytes = std::size_t(image.width) * 3;
  std::vector<std::uint8_t> rows;
  rows.reserve((row_bytes + 1) * image.height);
  for (int y = 0; y < image.height; ++y) {
    rows.push_back(0);  // no filter
    const auto row = image.pixels.begin() + static_cast<std::ptrdiff_t>(std::size_t(y) * row_bytes);
    rows.insert(rows.end(), row, row + static_cast<std::ptrdiff_t>(row_bytes));
  }
  uLongf size = compressBound(static_cast<uLong>(rows.size()));
  std::vector<std::uint8_t> packed(size);
  if (compress2(packed.data(), &size, rows.data(), static_cast<uLong>(rows.size()), 9) != Z_OK)
    throw AlgorithmError("PNG encoding failed (zlib)");
  packed.resize(size);
  std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  append_be32(header, static_cast<std::uint32_t>(image.width));
  append_be32(header, static_cast<std::uint32_t>(image.height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, no filter choice, no interlace
  append_chunk(png, "IHDR", header);
  append_chunk(png, "IDAT", packed);
  append_chunk(png, "IEND", {});
  return png;
}

void write_png(const RgbImage& image, const std::filesystem::path& path) {
  const auto bytes = encode_png(image);
  std::ofstream file(path, std::ios::binary);
  if (!file) throw IoError("cannot write " + path.string());
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!file) throw IoError("cannot write " + path.string());
}

}  // namespace subfab
