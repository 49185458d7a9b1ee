// SPDX-License-Identifier: GPL-3.0-or-later
#include "view/encode_base64.h"

#include <cstring>

namespace subfab::detail {

std::string encode_base64(const std::uint8_t* data, std::size_t size) {
  static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t v = (std::uint32_t(data[i]) << 16) | (std::uint32_t(data[i + 1]) << 8) | data[i + 2];
    for (int s = 18; s >= 0; s -= 6) out.push_back(kAlphabet[(v >> s) & 63]);
  }
  if (i < size) {
    const bool two = i + 1 < size;
    const std::uint32_t v = (std::uint32_t(data[i]) << 16) | (two ? std::uint32_t(data[i + 1]) << 8 : 0u);
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(two ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

namespace {

//! The values' bytes in little-endian order, whatever the host's order.
template <typename T>
std::vector<std::uint8_t> little_endian_bytes(const std::vector<T>& values) {
  static_assert(sizeof(T) == 4);
  std::vector<std::uint8_t> bytes(values.size() * 4);
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::uint32_t u;
    std::memcpy(&u, &values[i], 4);
    for (int k = 0; k < 4; ++k) bytes[4 * i + k] = static_cast<std::uint8_t>(u >> (8 * k));
  }
  return bytes;
}

}  // namespace

std::string base64_float32(const std::vector<float>& values) {
  const auto bytes = little_endian_bytes(values);
  return encode_base64(bytes.data(), bytes.size());
}

std::string base64_uint32(const std::vector<std::uint32_t>& values) {
  const auto bytes = little_endian_bytes(values);
  return encode_base64(bytes.data(), bytes.size());
}

}  // namespace subfab::detail
