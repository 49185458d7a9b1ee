// SPDX-License-Identifier: GPL-3.0-or-later
//! PLY reader: ascii, binary_little_endian and binary_big_endian.
//! - `vertex`: x, y, z of any numeric type (char/int8, uchar/uint8, short/int16,
//!   ushort/uint16, int/int32, uint/uint32, float/float32, double/float64);
//!   other vertex properties (normals, colours, lists) are skipped.
//! - `face`: the list property `vertex_indices` or `vertex_index` (any count
//!   and index types), polygons fan-triangulated; other properties skipped.
//! - `tristrips`: a list of indices where -1 restarts the strip; triangles
//!   alternate winding; degenerate joining triangles are dropped.
//! - every other element is skipped, its lists included.
//! Counts in the header are checked against the bytes that follow before
//! anything is reserved, and every read is bounds-checked.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "mesh/mesh_readers.h"

namespace subfab::detail {
namespace {

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::size_t type_size(ScalarType t) {
  switch (t) {
    case ScalarType::Int8:
    case ScalarType::UInt8: return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16: return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32: return 4;
    case ScalarType::Float64: return 8;
  }
  return 1;
}

bool is_float(ScalarType t) { return t == ScalarType::Float32 || t == ScalarType::Float64; }

bool parse_type(std::string_view s, ScalarType& t) {
  static const std::array<std::pair<std::string_view, ScalarType>, 16> names = {{
      {"char", ScalarType::Int8},       {"int8", ScalarType::Int8},       {"uchar", ScalarType::UInt8},
      {"uint8", ScalarType::UInt8},     {"short", ScalarType::Int16},     {"int16", ScalarType::Int16},
      {"ushort", ScalarType::UInt16},   {"uint16", ScalarType::UInt16},   {"int", ScalarType::Int32},
      {"int32", ScalarType::Int32},     {"uint", ScalarType::UInt32},     {"uint32", ScalarType::UInt32},
      {"float", ScalarType::Float32},   {"float32", ScalarType::Float32}, {"double", ScalarType::Float64},
      {"float64", ScalarType::Float64},
  }};
  for (const auto& [n, type] : names)
    if (n == s) {
      t = type;
      return true;
    }
  return false;
}

struct Property {
  std::string name;
  bool is_list = false;
  ScalarType count_type = ScalarType::UInt8;  // lists only
  ScalarType type = ScalarType::Float32;      // the value, or the list items
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  std::size_t header_line = 0;
};

enum class Encoding { Ascii, BinaryLittle, BinaryBig };

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

//! Reads scalar values from the body, ascii or binary, never past its end.
class BodyCursor {
 public:
  BodyCursor(std::string_view data, std::size_t body_offset, std::size_t body_line, Encoding encoding,
             const std::string& name)
      : begin_(data.data()), p_(data.data() + body_offset), end_(data.data() + data.size()),
        encoding_(encoding), name_(name), line_(body_line),
        swap_((encoding == Encoding::BinaryLittle && std::endian::native == std::endian::big) ||
              (encoding == Encoding::BinaryBig && std::endian::native == std::endian::little)) {}

  bool ascii() const { return encoding_ == Encoding::Ascii; }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }

  //! Where the current record started (line or byte offset).
  Location record_location() const { return record_; }
  void start_record(const Element& element, std::uint64_t index) {
    element_ = &element;
    index_ = index;
    if (ascii()) {
      skip_blanks();
      record_ = Location::line(line_);
    } else {
      record_ = Location::byte(static_cast<std::size_t>(p_ - begin_));
    }
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw_io(name_, ascii() ? Location::line(line_) : Location::byte(static_cast<std::size_t>(p_ - begin_)),
             what + " (element '" + printable(element_->name) + "', record " + std::to_string(index_) + " of " +
                 std::to_string(element_->count) + ")");
  }

  double read_double(ScalarType t) {
    if (ascii()) {
      const char* start = ascii_token();
      double value;
      if (!parse_double(p_, end_, value) || !token_ended()) {
        p_ = start;
        fail("expected a number, got '" + token_text() + "'");
      }
      return value;
    }
    return binary_value(t);
  }

  //! An integer value (list counts, indices). Float-typed values must be integral.
  std::int64_t read_integer(ScalarType t) {
    if (ascii()) {
      const char* start = ascii_token();
      if (is_float(t)) {
        double value;
        if (!parse_double(p_, end_, value) || !token_ended() || !(std::abs(value) < 4e18) ||
            value != std::floor(value)) {
          p_ = start;
          fail("expected an integer, got '" + token_text() + "'");
        }
        return static_cast<std::int64_t>(value);
      }
      std::int64_t value;
      if (!parse_int(p_, end_, value) || !token_ended()) {
        p_ = start;
        fail("expected an integer, got '" + token_text() + "'");
      }
      return value;
    }
    const double value = binary_value(t);
    if (!is_float(t)) return static_cast<std::int64_t>(value);  // exact: at most 32 bits
    if (!(std::abs(value) < 4e18) || value != std::floor(value)) fail("non-integral index " + number_text(value));
    return static_cast<std::int64_t>(value);
  }

  void skip_value(ScalarType t) {
    if (ascii()) {
      read_double(t);
      return;
    }
    if (remaining() < type_size(t)) fail("file ends inside a value (truncated file?)");
    p_ += type_size(t);
  }

  //! A list count, checked against what the rest of the file can hold.
  std::uint64_t read_list_count(ScalarType count_type, ScalarType item_type) {
    const std::int64_t n = read_integer(count_type);
    if (n < 0) fail("negative list length " + std::to_string(n));
    const std::size_t min_item = ascii() ? 2 : type_size(item_type);
    if (static_cast<std::uint64_t>(n) > remaining() / min_item + 1)
      fail("list of " + std::to_string(n) + " values does not fit in the rest of the file (truncated file?)");
    return static_cast<std::uint64_t>(n);
  }

 private:
  void skip_blanks() {
    while (p_ < end_ && is_space_or_newline(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
  }
  const char* ascii_token() {
    skip_blanks();
    if (p_ == end_) fail("file ends before all values are read (truncated file?)");
    return p_;
  }
  bool token_ended() const { return p_ == end_ || is_space_or_newline(*p_); }
  std::string token_text() const { return token_at(p_, end_); }

  template <class T>
  T load() {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, p_, sizeof(T));
    if (swap_)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    p_ += sizeof(T);
    return value;
  }

  double binary_value(ScalarType t) {
    if (remaining() < type_size(t)) fail("file ends inside a value (truncated file?)");
    switch (t) {
      case ScalarType::Int8: return load<std::int8_t>();
      case ScalarType::UInt8: return load<std::uint8_t>();
      case ScalarType::Int16: return load<std::int16_t>();
      case ScalarType::UInt16: return load<std::uint16_t>();
      case ScalarType::Int32: return load<std::int32_t>();
      case ScalarType::UInt32: return load<std::uint32_t>();
      case ScalarType::Float32: return static_cast<double>(load<float>());
      case ScalarType::Float64: return load<double>();
    }
    return 0;
  }

  const char* begin_;
  const char* p_;
  const char* end_;
  Encoding encoding_;
  const std::string& name_;
  std::size_t line_;
  bool swap_;
  const Element* element_ = nullptr;
  std::uint64_t index_ = 0;
  Location record_;
};

class PlyParser {
 public:
  PlyParser(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info)
      : data_(data), name_(name), mesh_(mesh), info_(info) {}

  void parse() {
    parse_header();
    check_sizes();
    BodyCursor cursor(data_, body_offset_, body_line_, encoding_, name_);
    for (const Element& element : elements_) {
      if (element.properties.empty()) continue;  // no data at all
      if (element.name == "vertex")
        read_vertices(cursor, element);
      else if (element.name == "face")
        read_faces(cursor, element);
      else if (element.name == "tristrips")
        read_tristrips(cursor, element);
      else
        skip_element(cursor, element);
    }
    info_.vertices_in_file = static_cast<std::size_t>(num_vertices_);
    if (num_strip_degenerate_ > 0)
      info_.notes.push_back("dropped " + std::to_string(num_strip_degenerate_) +
                            " degenerate triangles joining triangle strips");
  }

 private:
  [[noreturn]] void fail_header(std::size_t line, const std::string& what) const {
    throw_io(name_, Location::line(line), what);
  }

  void parse_header() {
    std::size_t pos = 0;
    std::size_t line_number = 0;
    bool have_format = false;
    while (true) {
      if (pos >= data_.size())
        fail_header(line_number, "the PLY header has no 'end_header' line (truncated or not a PLY file)");
      std::size_t nl = data_.find('\n', pos);
      const std::size_t next = nl == std::string_view::npos ? data_.size() : nl + 1;
      std::string_view line = data_.substr(pos, (nl == std::string_view::npos ? data_.size() : nl) - pos);
      pos = next;
      ++line_number;
      if (line_number == 1) {
        while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
        if (line != "ply") fail_header(1, "expected 'ply' on the first line, got '" + printable(line) + "'");
        continue;
      }
      const auto words = split_words(line);
      if (words.empty()) continue;
      const std::string_view key = words[0];
      if (key == "comment" || key == "obj_info") continue;
      if (key == "end_header") {
        if (nl == std::string_view::npos) fail_header(line_number, "file ends right after 'end_header'");
        break;
      }
      if (key == "format") {
        if (words.size() < 2) fail_header(line_number, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
        if (words[1] == "ascii") encoding_ = Encoding::Ascii;
        else if (words[1] == "binary_little_endian") encoding_ = Encoding::BinaryLittle;
        else if (words[1] == "binary_big_endian") encoding_ = Encoding::BinaryBig;
        else fail_header(line_number, "unknown PLY format '" + printable(words[1]) + "'");
        have_format = true;
      } else if (key == "element") {
        std::int64_t count = -1;
        const char* p = words.size() == 3 ? words[2].data() : nullptr;
        if (!p || !parse_int(p, words[2].data() + words[2].size(), count) || p != words[2].data() + words[2].size() ||
            count < 0)
          fail_header(line_number, "expected 'element NAME COUNT', got '" + printable(line) + "'");
        elements_.push_back({std::string(words[1]), static_cast<std::uint64_t>(count), {}, line_number});
      } else if (key == "property") {
        if (elements_.empty()) fail_header(line_number, "'property' before any 'element'");
        Property property;
        bool ok;
        if (words.size() >= 2 && words[1] == "list") {
          property.is_list = true;
          ok = words.size() == 5 && parse_type(words[2], property.count_type) && parse_type(words[3], property.type);
          if (ok) property.name = std::string(words[4]);
        } else {
          ok = words.size() == 3 && parse_type(words[1], property.type);
          if (ok) property.name = std::string(words[2]);
        }
        if (!ok)
          fail_header(line_number, "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME' with types "
                                   "char/uchar/short/ushort/int/uint/float/double, got '" + printable(line) + "'");
        elements_.back().properties.push_back(property);
      } else {
        fail_header(line_number, "unexpected PLY header line '" + printable(line) + "'");
      }
    }
    if (!have_format) fail_header(line_number, "the PLY header has no 'format' line");
    body_offset_ = pos;
    body_line_ = line_number + 1;
    for (const Element& e : elements_) {
      if (e.name != "vertex") continue;
      if (have_vertex_element_) fail_header(e.header_line, "two 'vertex' elements");
      have_vertex_element_ = true;
      num_vertices_ = e.count;
    }
    if (!have_vertex_element_) fail_header(line_number, "the PLY header declares no 'vertex' element");
  }

  //! Refuses counts the file cannot hold, before reserving anything.
  void check_sizes() const {
    const std::uint64_t available = data_.size() - body_offset_;
    std::uint64_t needed = 0;
    for (const Element& e : elements_) {
      std::uint64_t record = 0;  // smallest possible record
      for (const Property& p : e.properties)
        record += encoding_ == Encoding::Ascii ? 2 : type_size(p.is_list ? p.count_type : p.type);
      if (record == 0) continue;
      if (e.count > (available + 1) / record + 1 || (needed += e.count * record) > available + 1)
        throw_io(name_, Location::line(e.header_line),
                 "element '" + printable(e.name) + "' declares " + std::to_string(e.count) +
                     " records, more than the " + std::to_string(available) +
                     " bytes after the header can hold (truncated or corrupt file)");
    }
    if (num_vertices_ >= INT32_MAX) throw_io(name_, {}, "too many vertices (" + std::to_string(num_vertices_) + ")");
  }

  void skip_property(BodyCursor& cursor, const Property& p) {
    if (!p.is_list) {
      cursor.skip_value(p.type);
      return;
    }
    const std::uint64_t n = cursor.read_list_count(p.count_type, p.type);
    for (std::uint64_t i = 0; i < n; ++i) cursor.skip_value(p.type);
  }

  void skip_element(BodyCursor& cursor, const Element& e) {
    for (std::uint64_t r = 0; r < e.count; ++r) {
      cursor.start_record(e, r);
      for (const Property& p : e.properties) skip_property(cursor, p);
    }
  }

  void read_vertices(BodyCursor& cursor, const Element& e) {
    std::array<int, 3> slot = {-1, -1, -1};
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      const Property& p = e.properties[i];
      const int k = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
      if (k < 0) continue;
      if (p.is_list) fail_header(e.header_line, "vertex property '" + p.name + "' is a list, expected a number");
      slot[static_cast<std::size_t>(k)] = static_cast<int>(i);
    }
    for (int k = 0; k < 3; ++k)
      if (slot[static_cast<std::size_t>(k)] < 0)
        fail_header(e.header_line, std::string("the 'vertex' element has no '") + "xyz"[k] + "' property");
    mesh_.vertices.reserve(mesh_.vertices.size() + e.count);
    for (std::uint64_t r = 0; r < e.count; ++r) {
      cursor.start_record(e, r);
      Vec3 point = Vec3::Zero();
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (static_cast<int>(i) == slot[0]) point.x() = cursor.read_double(p.type);
        else if (static_cast<int>(i) == slot[1]) point.y() = cursor.read_double(p.type);
        else if (static_cast<int>(i) == slot[2]) point.z() = cursor.read_double(p.type);
        else skip_property(cursor, p);
      }
      check_finite(point, static_cast<std::size_t>(r), name_, cursor.record_location());
      mesh_.vertices.push_back(point);
    }
  }

  //! Index of the list property holding the corners, or a header error.
  std::size_t index_list(const Element& e) const {
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      const Property& p = e.properties[i];
      if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) return i;
    }
    throw_io(name_, Location::line(e.header_line),
             "the '" + e.name + "' element has no list property 'vertex_indices' or 'vertex_index'");
  }

  //! Reads the list of vertex indices of property p into corners_; -1 kept
  //! when `allow_restart` (tristrips), every other index range-checked.
  void read_corner_list(BodyCursor& cursor, const Property& p, bool allow_restart) {
    const std::uint64_t n = cursor.read_list_count(p.count_type, p.type);
    corners_.clear();
    for (std::uint64_t k = 0; k < n; ++k) {
      const std::int64_t index = cursor.read_integer(p.type);
      if (allow_restart && index == -1) {
        corners_.push_back(-1);
        continue;
      }
      corners_.push_back(checked_index(index, static_cast<std::size_t>(num_vertices_), name_,
                                       cursor.record_location()));
    }
  }

  void read_faces(BodyCursor& cursor, const Element& e) {
    const std::size_t list = index_list(e);
    mesh_.faces.reserve(mesh_.faces.size() + e.count);
    for (std::uint64_t r = 0; r < e.count; ++r) {
      cursor.start_record(e, r);
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        if (i == list) read_corner_list(cursor, e.properties[i], false);
        else skip_property(cursor, e.properties[i]);
      }
      if (corners_.size() < 3)
        throw_invalid(name_, cursor.record_location(),
                      "face " + std::to_string(r) + " has " + std::to_string(corners_.size()) +
                          " corners (a face needs at least 3)");
      ++info_.polygons_in_file;
      if (corners_.size() > 3) ++info_.polygons_triangulated;
      append_fan(mesh_, corners_.begin(), corners_.end());
    }
  }

  void read_tristrips(BodyCursor& cursor, const Element& e) {
    const std::size_t list = index_list(e);
    for (std::uint64_t r = 0; r < e.count; ++r) {
      cursor.start_record(e, r);
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        if (i == list) read_corner_list(cursor, e.properties[i], true);
        else skip_property(cursor, e.properties[i]);
      }
      // Triangle k of a strip is (s[k], s[k+1], s[k+2]) for even k and
      // (s[k+1], s[k], s[k+2]) for odd k; -1 starts a new strip.
      std::size_t start = 0;
      for (std::size_t i = 0; i < corners_.size(); ++i) {
        if (corners_[i] < 0) {
          start = i + 1;
          continue;
        }
        if (i < start + 2) continue;
        const int a = corners_[i - 2], b = corners_[i - 1], c = corners_[i];
        if (a == b || b == c || a == c) {
          ++num_strip_degenerate_;
          continue;
        }
        if ((i - start) % 2 == 0) mesh_.faces.push_back({a, b, c});
        else mesh_.faces.push_back({b, a, c});
        ++info_.polygons_in_file;
      }
    }
  }

  std::string_view data_;
  const std::string& name_;
  Mesh& mesh_;
  ReadInfo& info_;
  Encoding encoding_ = Encoding::Ascii;
  std::vector<Element> elements_;
  std::size_t body_offset_ = 0;
  std::size_t body_line_ = 0;
  bool have_vertex_element_ = false;
  std::uint64_t num_vertices_ = 0;
  std::vector<int> corners_;
  std::size_t num_strip_degenerate_ = 0;
};

}  // namespace

void read_ply(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info) {
  PlyParser(data, name, mesh, info).parse();
}

}  // namespace subfab::detail
