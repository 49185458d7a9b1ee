// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/core/write_png.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

namespace subfab {
namespace {

std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 | std::uint32_t(b[at + 2]) << 8 | b[at + 3];
}

//! Decodes what encode_png writes (8-bit RGB, filter 0 rows), checking every
//! chunk's CRC; fails the test on anything else.
RgbImage decode(const std::vector<std::uint8_t>& png) {
  const std::vector<std::uint8_t> signature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(std::equal(signature.begin(), signature.end(), png.begin()));
  int width = 0, height = 0;
  std::vector<std::uint8_t> idat;
  bool end = false;
  for (std::size_t at = 8; at + 12 <= png.size() && !end;) {
    const std::uint32_t length = be32(png, at);
    const std::string type(png.begin() + std::ptrdiff_t(at + 4), png.begin() + std::ptrdiff_t(at + 8));
    const std::uint8_t* body = png.data() + at + 4;
    EXPECT_EQ(be32(png, at + 8 + length), crc32(0L, body, 4 + length)) << type;
    const std::uint8_t* data = body + 4;
    if (type == "IHDR") {
      width = int(be32(png, at + 8));
      height = int(be32(png, at + 12));
      EXPECT_EQ(data[8], 8);  // bit depth
      EXPECT_EQ(data[9], 2);  // RGB
    } else if (type == "IDAT") {
      idat.insert(idat.end(), data, data + length);
    } else if (type == "IEND") {
      end = true;
    }
    at += 12 + length;
  }
  EXPECT_TRUE(end);
  std::vector<std::uint8_t> rows((std::size_t(width) * 3 + 1) * height);
  uLongf size = rows.size();
  EXPECT_EQ(uncompress(rows.data(), &size, idat.data(), idat.size()), Z_OK);
  EXPECT_EQ(size, rows.size());
  RgbImage image(width, height);
  for (int y = 0; y < height; ++y) {
    const std::size_t row = std::size_t(y) * (std::size_t(width) * 3 + 1);
    EXPECT_EQ(rows[row], 0);  // filter: none
    std::copy_n(rows.begin() + std::ptrdiff_t(row + 1), std::size_t(width) * 3,
                image.pixels.begin() + std::ptrdiff_t(std::size_t(y) * width * 3));
  }
  return image;
}

TEST(WritePng, DecodesToTheSamePixels) {
  RgbImage img(3, 2);
  img.set(1, 1, 255, 0, 0);
  img.set(0, 0, 1, 2, 3);
  img.set(5, 5, 0, 0, 0);  // outside: ignored
  const RgbImage back = decode(encode_png(img));
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(WritePng, CompressesALargeImageLosslessly) {
  RgbImage img(400, 300);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if ((x / 20 + y / 20) % 2) img.set(x, y, 215, 48, std::uint8_t(y / 20));
  const auto png = encode_png(img);
  EXPECT_LT(png.size(), img.pixels.size() / 4);  // a checkerboard compresses well
  const RgbImage back = decode(png);
  EXPECT_EQ(back.width, 400);
  EXPECT_EQ(back.height, 300);
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(WritePng, EncodesAnEmptyImage) {
  const RgbImage back = decode(encode_png(RgbImage(0, 0)));
  EXPECT_EQ(back.width, 0);
  EXPECT_TRUE(back.pixels.empty());
}

}  // namespace
}  // namespace subfab
