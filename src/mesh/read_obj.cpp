// SPDX-License-Identifier: GPL-3.0-or-later
//! Wavefront OBJ reader: `v x y z [w | r g b]`, faces `f` with corners
//! `v`, `v/vt`, `v//vn`, `v/vt/vn` (1-based, negative = relative to the last
//! vertex read), polygons fan-triangulated, `\` line continuation, CRLF.
//! Texture coordinates, normals, materials, groups and smoothing groups are
//! ignored; other records are skipped and counted in the notes.
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh_readers.h"

namespace subfab::detail {
namespace {

class ObjParser : TextParser {
 public:
  using TextParser::TextParser;

  void parse() {
    mesh_.vertices.reserve(static_cast<std::size_t>(end_ - p_) / 64);
    mesh_.faces.reserve(static_cast<std::size_t>(end_ - p_) / 32);
    while (p_ < end_) {
      skip_inline();
      if (p_ == end_) break;
      if (*p_ == '\n') {
        ++p_;
        ++line_;
        continue;
      }
      const char* key_begin = p_;
      while (p_ < end_ && !is_space_or_newline(*p_)) ++p_;
      const std::string_view key(key_begin, static_cast<std::size_t>(p_ - key_begin));
      if (key == "v")
        parse_vertex();
      else if (key == "f")
        parse_face();
      else if (key[0] == '#' || key == "vt" || key == "vn" || key == "vp" || key == "mtllib" || key == "usemtl" ||
               key == "o" || key == "g" || key == "s")
        ;  // ignored on purpose
      else if (key == "l" || key == "p")
        ++num_polylines_;
      else
        note_unknown(key);
      skip_line();
    }
    finish();
  }

 private:
  //! Skips blanks within the line, and a `\` line continuation.
  void skip_inline() {
    while (p_ < end_) {
      if (is_space(*p_)) {
        ++p_;
      } else if (*p_ == '\\' && continuation_at(p_)) {
        p_ = (p_[1] == '\r') ? p_ + 3 : p_ + 2;
        ++line_;
      } else {
        break;
      }
    }
  }

  //! True when q points at a `\` that ends the line ("\\\n" or "\\\r\n").
  bool continuation_at(const char* q) const {
    return q + 1 < end_ && (q[1] == '\n' || (q[1] == '\r' && q + 2 < end_ && q[2] == '\n'));
  }

  //! Moves past the end of the current (logical) line, not past the '\n'.
  void skip_line() {
    while (p_ < end_ && *p_ != '\n') {
      if (*p_ == '\\' && continuation_at(p_)) {
        p_ = (p_[1] == '\r') ? p_ + 3 : p_ + 2;
        ++line_;
      } else {
        ++p_;
      }
    }
  }

  bool at_line_end() const { return p_ == end_ || *p_ == '\n' || *p_ == '#'; }

  //! True at whitespace, the end of the line or file, or a line continuation.
  bool at_token_end() const {
    return p_ == end_ || is_space_or_newline(*p_) || (*p_ == '\\' && continuation_at(p_));
  }

  void parse_vertex() {
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      skip_inline();
      if (at_line_end())
        fail_io("expected 3 coordinates after 'v', found " + std::to_string(k));
      double value;
      const char* start = p_;
      if (!parse_double(p_, end_, value) || !at_token_end()) {
        p_ = start;
        fail_io("expected a number after 'v', got '" + token_here() + "'");
      }
      p[k] = value;
    }
    check_finite(p, mesh_.vertices.size(), name_, Location::line(line_));
    mesh_.vertices.push_back(p);
  }

  void parse_face() {
    corners_.clear();
    const std::int64_t num_vertices = static_cast<std::int64_t>(mesh_.vertices.size());
    while (true) {
      skip_inline();
      if (at_line_end()) break;
      std::int64_t index;
      const char* start = p_;
      if (!parse_int(p_, end_, index)) fail_io("expected a vertex index in 'f', got '" + token_here() + "'");
      // The rest of the corner: /vt, //vn or /vt/vn (ignored, but must look like it).
      while (!at_token_end()) {
        const char c = *p_;
        if (!(c == '/' || c == '-' || (c >= '0' && c <= '9'))) {
          p_ = start;
          fail_io("expected a face corner like 7, 7/3, 7//2 or 7/3/2 in 'f', got '" + token_here() + "'");
        }
        ++p_;
      }
      std::int64_t resolved;
      if (index > 0) {
        resolved = index - 1;  // may refer to a vertex defined further down: checked in finish()
        if (resolved > max_index_) {
          max_index_ = resolved;
          max_index_line_ = line_;
        }
      } else if (index < 0) {
        resolved = num_vertices + index;
        if (resolved < 0)
          throw_invalid(name_, Location::line(line_),
                        "face index " + std::to_string(index) + " out of range (relative index, only " +
                            std::to_string(num_vertices) + " vertices read so far)");
      } else {
        throw_invalid(name_, Location::line(line_), "face index 0 out of range (OBJ indices start at 1)");
      }
      if (resolved >= INT32_MAX)
        throw_invalid(name_, Location::line(line_), "face index " + std::to_string(index) + " out of range");
      corners_.push_back(static_cast<int>(resolved));
    }
    if (corners_.size() < 3)
      throw_invalid(name_, Location::line(line_),
                    "face with " + std::to_string(corners_.size()) + " corners (a face needs at least 3)");
    add_polygon();
  }

  void note_unknown(std::string_view key) {
    if (num_unknown_++ == 0) {
      first_unknown_ = printable(key.substr(0, 24));  // (built by appends: GCC 12 -Wrestrict false positive)
      first_unknown_.insert(first_unknown_.begin(), '\'');
      first_unknown_.append("' at line ").append(std::to_string(line_));
    }
  }

  void finish() {
    const std::size_t num_vertices = mesh_.vertices.size();
    if (num_vertices == 0 && info_.polygons_in_file == 0 && num_unknown_ > 0)
      throw_io(name_, {},
               "not an OBJ file: no vertex ('v') or face ('f') records; first unrecognised line: " + first_unknown_);
    if (max_index_ >= 0 && static_cast<std::size_t>(max_index_) >= num_vertices)
      throw_invalid(name_, Location::line(max_index_line_),
                    "face index " + std::to_string(max_index_ + 1) + " out of range (file has " +
                        std::to_string(num_vertices) + " vertices)");
    info_.vertices_in_file = num_vertices;
    if (num_polylines_ > 0)
      info_.notes.push_back("ignored " + std::to_string(num_polylines_) + " line/point records ('l', 'p')");
    if (num_unknown_ > 0)
      info_.notes.push_back("ignored " + std::to_string(num_unknown_) + " lines with unknown keywords (first: " +
                            first_unknown_ + ")");
  }

  std::int64_t max_index_ = -1;
  std::size_t max_index_line_ = 0;
  std::size_t num_polylines_ = 0;
  std::size_t num_unknown_ = 0;
  std::string first_unknown_;
};

}  // namespace

void read_obj(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info) {
  ObjParser(data, name, mesh, info).parse();
}

}  // namespace subfab::detail
