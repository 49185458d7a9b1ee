// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mesh_readers.h
//! Private machinery shared by the format readers (read_obj.cpp, read_off.cpp,
//! read_ply.cpp, read_stl.cpp, read_3mf.cpp) and read_mesh.cpp: error messages that name the
//! file and the line or byte offset, allocation-free number parsing, and the
//! state the text parsers share (TextParser).
//!
//! Every reader works on the whole file held in memory (`std::string_view`),
//! never reads past its end, and appends to a `Mesh` whose face indices are
//! all checked against the vertex count (InvalidMeshError otherwise).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "subfab/core/error.h"
#include "subfab/mesh/mesh.h"
#include "subfab/mesh/read_mesh.h"

namespace subfab::detail {

//! Where a problem is: a 1-based line (text formats) or a byte offset (binary).
struct Location {
  enum class Kind { None, Line, Byte } kind = Kind::None;
  std::size_t value = 0;
  static Location line(std::size_t l) { return {Kind::Line, l}; }
  static Location byte(std::size_t b) { return {Kind::Byte, b}; }
};

//! "name:12: what", "name: byte 340: what" or "name: what".
std::string located_message(const std::string& name, Location where, const std::string& what);

//! Throws IoError (the file is not a well-formed file of its format).
[[noreturn]] void throw_io(const std::string& name, Location where, const std::string& what);

//! Throws InvalidMeshError (well formed, but not a usable mesh).
[[noreturn]] void throw_invalid(const std::string& name, Location where, const std::string& what);

//! Parses a decimal floating-point number (optional sign, "inf", "nan"
//! accepted so the caller can report them) at p; on success advances p.
//! Overflow gives +-infinity, underflow a denormal or zero.
bool parse_double(const char*& p, const char* end, double& value);

//! Parses an optionally signed decimal integer at p; on success advances p.
//! Values beyond +-2^62 saturate (they are out of any index range anyway).
bool parse_int(const char*& p, const char* end, std::int64_t& value);

//! s cut to 40 characters, bytes that are not printable ASCII shown as '?'
//! (file content quoted in messages).
std::string printable(std::string_view s);

//! The whitespace-delimited token at p (at most 24 characters), printable.
std::string token_at(const char* p, const char* end);

//! Shortest readable rendering of a (possibly non-finite) double for messages.
std::string number_text(double v);

//! A face index as read from the file, checked to be a valid 0-based index
//! into `num_vertices` vertices. `what` names the record ("face 12").
int checked_index(std::int64_t index, std::size_t num_vertices, const std::string& name, Location where);

//! Throws InvalidMeshError when p has a NaN or infinite coordinate.
void check_finite(const Vec3& p, std::size_t vertex, const std::string& name, Location where);

//! Format readers. Each appends the mesh in `data` (the whole file) to `mesh`,
//! fills the counters of `info` it knows, and throws IoError/InvalidMeshError.
//! Face indices are guaranteed in range, coordinates finite.
void read_obj(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info);
void read_off(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info);
void read_ply(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info);
void read_stl(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info);
//! 3MF (a zip of XML): every build item, transformed, in millimetres (read_3mf.cpp).
void read_3mf(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info);

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
inline bool is_space_or_newline(char c) { return is_space(c) || c == '\n'; }

//! Appends the fan triangulation (c0, ci, ci+1) of a polygon given by its
//! corners [first, last) to mesh.faces; returns the number of triangles.
template <class It>
std::size_t append_fan(Mesh& mesh, It first, It last) {
  const auto n = static_cast<std::size_t>(last - first);
  for (std::size_t i = 1; i + 1 < n; ++i) mesh.faces.push_back({first[0], first[i], first[i + 1]});
  return n >= 3 ? n - 2 : 0;
}

//! What the text-format parsers (OBJ, OFF, ascii STL) keep while they read:
//! a cursor into the file, the current 1-based line, the mesh and info they
//! fill, and the corners of the polygon being read.
class TextParser {
 public:
  TextParser(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info)
      : p_(data.data()), end_(data.data() + data.size()), name_(name), mesh_(mesh), info_(info) {}

 protected:
  //! Throws IoError at the current line.
  [[noreturn]] void fail_io(const std::string& what) const {
    throw_io(name_, Location::line(line_), what);
  }

  //! The token at the cursor, for messages.
  std::string token_here() const { return token_at(p_, end_); }

  //! Counts the polygon in `corners_` in `info_` and appends its fan
  //! triangulation to `mesh_`.
  void add_polygon() {
    ++info_.polygons_in_file;
    if (corners_.size() > 3) ++info_.polygons_triangulated;
    append_fan(mesh_, corners_.begin(), corners_.end());
  }

  const char* p_;
  const char* end_;
  const std::string& name_;
  Mesh& mesh_;
  ReadInfo& info_;
  std::size_t line_ = 1;
  std::vector<int> corners_;
};

}  // namespace subfab::detail
