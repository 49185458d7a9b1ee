// SPDX-License-Identifier: GPL-3.0-or-later
//! OFF reader (text). Header keyword `[ST][C][N][4][n]OFF` (OFF, COFF, NOFF,
//! STOFF, ...; optional, as in old files that start with the counts), then
//! `#vertices #faces [#edges]` on the same line or the next (the edge count is
//! ignored), one vertex per line (`x y z` then per-vertex extras such as
//! normals, colours or texture coordinates, ignored), one polygon per line
//! (`n i1 .. in` then an optional face colour, ignored), fan-triangulated.
//! `#` starts a comment anywhere.
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh_readers.h"

namespace subfab::detail {
namespace {

class OffParser : TextParser {
 public:
  using TextParser::TextParser;

  void parse() {
    parse_header();
    mesh_.vertices.reserve(static_cast<std::size_t>(num_vertices_));
    for (std::int64_t v = 0; v < num_vertices_; ++v) parse_vertex(v);
    mesh_.faces.reserve(static_cast<std::size_t>(num_faces_));
    for (std::int64_t f = 0; f < num_faces_; ++f) parse_face(f);
    info_.vertices_in_file = static_cast<std::size_t>(num_vertices_);
  }

 private:
  //! Skips blanks and comments, not newlines.
  void skip_inline() {
    while (p_ < end_ && is_space(*p_)) ++p_;
    if (p_ < end_ && *p_ == '#')
      while (p_ < end_ && *p_ != '\n') ++p_;
  }

  //! Skips blanks, comments and newlines.
  void skip_all() {
    while (true) {
      skip_inline();
      if (p_ < end_ && *p_ == '\n') {
        ++p_;
        ++line_;
      } else {
        return;
      }
    }
  }

  //! Moves past the end of the current line.
  void next_line() {
    while (p_ < end_ && *p_ != '\n') ++p_;
    if (p_ < end_) {
      ++p_;
      ++line_;
    }
  }

  bool at_line_end() const { return p_ == end_ || *p_ == '\n'; }
  bool at_token_end() const { return p_ == end_ || is_space_or_newline(*p_) || *p_ == '#'; }

  std::int64_t read_count(const char* what) {
    skip_all();
    std::int64_t value;
    if (p_ == end_) fail_io(std::string("file ends before the ") + what + " in the header");
    const char* start = p_;
    if (!parse_int(p_, end_, value) || !at_token_end() || value < 0) {
      p_ = start;
      fail_io(std::string("expected the ") + what + " in the header, got '" + token_here() + "'");
    }
    return value;
  }

  void parse_header() {
    skip_all();
    const char* start = p_;
    while (p_ < end_ && !is_space_or_newline(*p_) && *p_ != '#') ++p_;
    const std::string_view keyword(start, static_cast<std::size_t>(p_ - start));
    bool has_dimension = false;
    if (keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF") {
      for (char c : keyword.substr(0, keyword.size() - 3)) {
        if (c == '4') fail_io("4-dimensional OFF ('" + std::string(keyword) + "') is not supported");
        if (c == 'n') has_dimension = true;
        else if (c != 'S' && c != 'T' && c != 'C' && c != 'N') {
          p_ = start;
          fail_io("expected an OFF header (OFF, COFF, NOFF, STOFF, ...), got '" + token_here() + "'");
        }
      }
    } else if (keyword.empty() || !((keyword[0] >= '0' && keyword[0] <= '9'))) {
      p_ = start;
      fail_io("expected an OFF header (OFF, COFF, NOFF, STOFF, ...), got '" + token_here() + "'");
    } else {
      p_ = start;  // no keyword: the file starts with the counts
      info_.notes.push_back("OFF file without the 'OFF' keyword");
    }
    if (has_dimension) {
      const std::int64_t dimension = read_count("dimension");
      if (dimension != 3) fail_io("only 3-dimensional OFF is supported, this file has dimension " +
                                  std::to_string(dimension));
    }
    skip_all();
    if (static_cast<std::size_t>(end_ - p_) >= 6 && std::string_view(p_, 6) == "BINARY")
      fail_io("binary OFF is not supported; convert the file to text OFF, PLY or STL");
    num_vertices_ = read_count("vertex count");
    num_faces_ = read_count("face count");
    // The edge count, if present on this line, is ignored.
    skip_inline();
    if (!at_line_end()) {
      std::int64_t edges;
      const char* before = p_;
      if (!parse_int(p_, end_, edges) || !at_token_end()) {
        p_ = before;
        fail_io("expected the edge count or the end of the header line, got '" + token_here() + "'");
      }
    }
    next_line();
    // Every vertex record takes at least 6 bytes ("0 0 0\n"), every face at
    // least 8 ("3 0 1 2\n"): refuse impossible counts before reserving memory.
    const auto remaining = static_cast<std::uint64_t>(end_ - p_);
    const auto nv = static_cast<std::uint64_t>(num_vertices_), nf = static_cast<std::uint64_t>(num_faces_);
    if (nv > remaining / 6 + 1 || nf > remaining / 8 + 1 || nv * 6 + nf * 8 > remaining + 16)
      fail_io("the header announces " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
              " faces, but only " + std::to_string(remaining) + " bytes follow (truncated or corrupt file)");
    if (nv >= INT32_MAX) fail_io("too many vertices (" + std::to_string(nv) + ")");
  }

  //! Positions p_ at the next record (skips blank and comment lines).
  void next_record(const char* what, std::int64_t index, std::int64_t count) {
    skip_all();
    if (p_ == end_)
      fail_io("file ends at " + std::string(what) + " " + std::to_string(index) + " of " + std::to_string(count) +
              " (truncated file?)");
  }

  void parse_vertex(std::int64_t v) {
    next_record("vertex", v, num_vertices_);
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      skip_inline();
      const char* start = p_;
      if (at_line_end())
        fail_io("expected 3 coordinates for vertex " + std::to_string(v) + ", found " + std::to_string(k));
      if (!parse_double(p_, end_, p[k]) || !at_token_end()) {
        p_ = start;
        fail_io("expected a coordinate of vertex " + std::to_string(v) + ", got '" + token_here() + "'");
      }
    }
    check_finite(p, static_cast<std::size_t>(v), name_, Location::line(line_));
    mesh_.vertices.push_back(p);
    next_line();  // per-vertex normals, colours, texture coordinates
  }

  void parse_face(std::int64_t f) {
    next_record("face", f, num_faces_);
    std::int64_t n;
    const char* start = p_;
    if (!parse_int(p_, end_, n) || !at_token_end() || n < 0) {
      p_ = start;
      fail_io("expected the corner count of face " + std::to_string(f) + ", got '" + token_here() + "'");
    }
    if (n < 3)
      throw_invalid(name_, Location::line(line_),
                    "face " + std::to_string(f) + " has " + std::to_string(n) + " corners (a face needs at least 3)");
    if (static_cast<std::uint64_t>(n) > static_cast<std::uint64_t>(end_ - p_) / 2)
      fail_io("face " + std::to_string(f) + " announces " + std::to_string(n) +
              " corners, more than the rest of the file can hold");
    corners_.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      skip_inline();
      std::int64_t index;
      const char* corner = p_;
      if (at_line_end())
        fail_io("face " + std::to_string(f) + " announces " + std::to_string(n) + " corners but lists " +
                std::to_string(k));
      if (!parse_int(p_, end_, index) || !at_token_end()) {
        p_ = corner;
        fail_io("expected a vertex index in face " + std::to_string(f) + ", got '" + token_here() + "'");
      }
      corners_.push_back(
          checked_index(index, static_cast<std::size_t>(num_vertices_), name_, Location::line(line_)));
    }
    add_polygon();
    next_line();  // optional face colour
  }

  std::int64_t num_vertices_ = 0;
  std::int64_t num_faces_ = 0;
};

}  // namespace

void read_off(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info) {
  OffParser(data, name, mesh, info).parse();
}

}  // namespace subfab::detail
