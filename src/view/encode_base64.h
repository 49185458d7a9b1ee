// SPDX-License-Identifier: GPL-3.0-or-later
//! \file encode_base64.h
//! Private: base64 (RFC 4648, with padding) of raw bytes and of little-endian
//! float32 / uint32 arrays, the compact form geometry and pictures take in
//! the HTML pages.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace subfab::detail {

//! Base64 of `size` bytes at `data`.
std::string encode_base64(const std::uint8_t* data, std::size_t size);

//! Base64 of the values as little-endian IEEE float32.
std::string base64_float32(const std::vector<float>& values);

//! Base64 of the values as little-endian uint32.
std::string base64_uint32(const std::vector<std::uint32_t>& values);

}  // namespace subfab::detail
