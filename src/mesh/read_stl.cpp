// SPDX-License-Identifier: GPL-3.0-or-later
//! STL reader, ascii and binary. The two are told apart by content, not by
//! the first word: a file of exactly 84 + 50 n bytes, n being the triangle
//! count at byte 80, is binary even when its header starts with "solid"
//! (many exporters write that). Every triangle brings three corners of its
//! own; exactly coincident corners are then welded into shared vertices.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "mesh/mesh_readers.h"

namespace subfab::detail {
namespace {

constexpr std::size_t kBinaryHeader = 84;
constexpr std::size_t kBinaryRecord = 50;

std::uint32_t load_u32_le(const char* p) {
  unsigned char b[4];
  std::memcpy(b, p, 4);
  return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 | std::uint32_t{b[3]} << 24;
}

float load_f32_le(const char* p) {
  const std::uint32_t bits = load_u32_le(p);
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

bool starts_with_solid(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && is_space_or_newline(data[i])) ++i;
  return data.size() - i >= 5 && data.compare(i, 5, "solid") == 0;
}

//! Binary data in the first bytes (a NUL or most control characters) means
//! the file is not ascii STL even if it starts with "solid".
bool has_binary_bytes(std::string_view data) {
  for (unsigned char c : data.substr(0, 256))
    if (c == 0 || (c < 32 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v')) return true;
  return false;
}

void read_binary(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info) {
  if (data.size() < kBinaryHeader)
    throw_io(name, {},
             "not an STL file: it does not start with 'solid' (ascii STL) and is shorter than the 84-byte header "
             "of binary STL (" + std::to_string(data.size()) + " bytes)");
  const std::uint64_t n = load_u32_le(data.data() + 80);
  const std::uint64_t needed = kBinaryHeader + kBinaryRecord * n;
  if (data.size() < needed)
    throw_io(name, Location::byte(80),
             "binary STL header announces " + std::to_string(n) + " triangles (" + std::to_string(needed) +
                 " bytes) but the file has only " + std::to_string(data.size()) + " bytes (truncated file?)");
  if (3 * n >= INT32_MAX) throw_io(name, Location::byte(80), "too many triangles (" + std::to_string(n) + ")");
  if (data.size() > needed)
    info.notes.push_back("ignored " + std::to_string(data.size() - needed) +
                         " bytes after the last triangle of the binary STL");
  mesh.vertices.reserve(3 * n);
  mesh.faces.reserve(n);
  for (std::uint64_t t = 0; t < n; ++t) {
    const std::size_t record = kBinaryHeader + kBinaryRecord * t;
    const char* p = data.data() + record + 12;  // skip the normal
    for (int c = 0; c < 3; ++c) {
      const Vec3 corner(load_f32_le(p), load_f32_le(p + 4), load_f32_le(p + 8));
      check_finite(corner, mesh.vertices.size(), name, Location::byte(static_cast<std::size_t>(p - data.data())));
      mesh.vertices.push_back(corner);
      p += 12;
    }
    const int v = static_cast<int>(3 * t);
    mesh.faces.push_back({v, v + 1, v + 2});
  }
  info.polygons_in_file = n;
}

class AsciiStlParser : TextParser {
 public:
  using TextParser::TextParser;

  void parse() {
    std::size_t num_solids = 0;
    while (true) {
      const std::string_view word = next_word();
      if (word.empty()) break;
      if (!keyword_is(word, "solid")) fail_io("expected 'solid', got " + describe(word));
      ++num_solids;
      skip_rest_of_line();  // the solid's name
      parse_solid();
    }
    if (num_solids == 0) fail_io("expected 'solid'");
  }

 private:
  static bool keyword_is(std::string_view word, std::string_view keyword) {
    if (word.size() != keyword.size()) return false;
    for (std::size_t i = 0; i < word.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(word[i])) != keyword[i]) return false;
    return true;
  }

  //! "'word'" or "the end of the file" for messages.
  static std::string describe(std::string_view word) {
    if (word.empty()) return "the end of the file (truncated?)";
    std::string s = printable(word.substr(0, 24));
    s.insert(s.begin(), '\'');
    s.push_back('\'');
    return s;
  }

  std::string_view next_word() {
    while (p_ < end_ && is_space_or_newline(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    const char* start = p_;
    while (p_ < end_ && !is_space_or_newline(*p_)) ++p_;
    return std::string_view(start, static_cast<std::size_t>(p_ - start));
  }

  void skip_rest_of_line() {
    while (p_ < end_ && *p_ != '\n') ++p_;
  }

  void expect(std::string_view keyword) {
    const std::string_view word = next_word();
    if (!keyword_is(word, keyword))
      fail_io("expected '" + std::string(keyword) + "', got " + describe(word));
  }

  double number() {
    const std::string_view word = next_word();
    const char* q = word.data();
    double value;
    if (word.empty() || !parse_double(q, word.data() + word.size(), value) || q != word.data() + word.size())
      fail_io("expected a number, got " + describe(word));
    return value;
  }

  void parse_solid() {
    while (true) {
      const std::string_view word = next_word();
      if (keyword_is(word, "endsolid")) {
        skip_rest_of_line();
        return;
      }
      if (!keyword_is(word, "facet"))
        fail_io("expected 'facet' or 'endsolid', got " + describe(word));
      parse_facet();
    }
  }

  void parse_facet() {
    const char* before = p_;
    const std::size_t before_line = line_;
    if (keyword_is(next_word(), "normal")) {
      for (int k = 0; k < 3; ++k) number();
    } else {
      p_ = before;  // "facet" without a normal
      line_ = before_line;
    }
    expect("outer");
    expect("loop");
    corners_.clear();
    while (true) {
      const std::size_t word_line = line_;
      const std::string_view word = next_word();
      if (keyword_is(word, "endloop")) break;
      if (!keyword_is(word, "vertex"))
        fail_io("expected 'vertex' or 'endloop', got " + describe(word));
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = number();
      check_finite(p, mesh_.vertices.size(), name_, Location::line(word_line));
      corners_.push_back(static_cast<int>(mesh_.vertices.size()));
      mesh_.vertices.push_back(p);
    }
    if (corners_.size() < 3)
      throw_invalid(name_, Location::line(line_),
                    "facet with " + std::to_string(corners_.size()) + " vertices (a facet needs at least 3)");
    expect("endfacet");
    add_polygon();
  }
};

}  // namespace

void read_stl(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info) {
  const bool exact_binary_size =
      data.size() >= kBinaryHeader && kBinaryHeader + kBinaryRecord * std::uint64_t{load_u32_le(data.data() + 80)} ==
                                          data.size();
  if (!exact_binary_size && starts_with_solid(data) && !has_binary_bytes(data))
    AsciiStlParser(data, name, mesh, info).parse();
  else
    read_binary(data, name, mesh, info);
  info.vertices_in_file = mesh.num_vertices();
  info.vertices_welded = weld_identical_vertices(mesh);
  if (info.vertices_welded > 0)
    info.notes.push_back("welded " + std::to_string(info.vertices_welded) + " exactly coincident triangle corners");
}

}  // namespace subfab::detail
