// SPDX-License-Identifier: GPL-3.0-or-later
//! read_mesh(): reads the whole file into memory, picks the format (extension,
//! then content), runs the format reader (read_obj.cpp, read_off.cpp,
//! read_ply.cpp, read_stl.cpp, read_3mf.cpp), then checks and cleans the result.
#include "subfab/mesh/read_mesh.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <system_error>

#include "mesh/mesh_readers.h"

namespace subfab {

std::string format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj: return "obj";
    case MeshFormat::Off: return "off";
    case MeshFormat::Ply: return "ply";
    case MeshFormat::Stl: return "stl";
    case MeshFormat::ThreeMf: return "3mf";
  }
  return "unknown";
}

namespace detail {

std::string located_message(const std::string& name, Location where, const std::string& what) {
  switch (where.kind) {
    case Location::Kind::Line: return name + ":" + std::to_string(where.value) + ": " + what;
    case Location::Kind::Byte: return name + ": at byte " + std::to_string(where.value) + ": " + what;
    case Location::Kind::None: break;
  }
  return name + ": " + what;
}

void throw_io(const std::string& name, Location where, const std::string& what) {
  throw IoError(located_message(name, where, what));
}

void throw_invalid(const std::string& name, Location where, const std::string& what) {
  throw InvalidMeshError(located_message(name, where, what));
}

bool parse_double(const char*& p, const char* end, double& value) {
  const char* q = p;
  if (q < end && *q == '+') ++q;  // from_chars does not take a leading '+'
  if (q < end && (*q == '+' || (*q == '-' && q != p))) return false;  // "++1", "+-1"
  double v = 0;
  const auto [ptr, ec] = std::from_chars(q, end, v, std::chars_format::general);
  if (ec == std::errc::invalid_argument || ptr == q) return false;
  if (ec == std::errc::result_out_of_range) {
    // Overflow or underflow: let strtod pick +-HUGE_VAL (then rejected as
    // infinite by the caller) or the nearest denormal/zero.
    const std::string text(q, ptr);
    v = std::strtod(text.c_str(), nullptr);
  }
  value = v;
  p = ptr;
  return true;
}

bool parse_int(const char*& p, const char* end, std::int64_t& value) {
  const char* q = p;
  bool negative = false;
  if (q < end && (*q == '+' || *q == '-')) negative = (*q++ == '-');
  const char* digits = q;
  constexpr std::int64_t kSaturate = std::int64_t{1} << 62;
  std::int64_t v = 0;
  while (q < end && *q >= '0' && *q <= '9') {
    if (v < kSaturate) v = v * 10 + (*q - '0');
    ++q;
  }
  if (q == digits) return false;
  if (v > kSaturate) v = kSaturate;
  value = negative ? -v : v;
  p = q;
  return true;
}

std::string printable(std::string_view s) {
  std::string out(s.substr(0, 40));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return out;
}

std::string token_at(const char* p, const char* end) {
  const char* q = p;
  while (q < end && !is_space_or_newline(*q) && q - p < 24) ++q;
  return printable(std::string_view(p, static_cast<std::size_t>(q - p)));
}

std::string number_text(double v) {
  char buffer[64];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return ec == std::errc() ? std::string(buffer, ptr) : std::string("?");
}

int checked_index(std::int64_t index, std::size_t num_vertices, const std::string& name, Location where) {
  if (index < 0 || static_cast<std::uint64_t>(index) >= num_vertices)
    throw_invalid(name, where,
                  "face index " + std::to_string(index) + " out of range (file has " + std::to_string(num_vertices) +
                      " vertices, indices 0.." + std::to_string(static_cast<std::int64_t>(num_vertices) - 1) + ")");
  return static_cast<int>(index);
}

void check_finite(const Vec3& p, std::size_t vertex, const std::string& name, Location where) {
  if (p.allFinite()) return;
  throw_invalid(name, where,
                "vertex " + std::to_string(vertex) + " has a non-finite coordinate (" + number_text(p.x()) + " " +
                    number_text(p.y()) + " " + number_text(p.z()) + "); fix or remove it");
}

}  // namespace detail

namespace {

using detail::Location;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

std::string read_whole_file(const std::filesystem::path& path, const std::string& name) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw IoError(name + ": cannot open: no such file");
  if (std::filesystem::is_directory(status)) throw IoError(name + ": cannot read: it is a folder, not a mesh file");
  if (!std::filesystem::is_regular_file(status)) throw IoError(name + ": cannot read: not a regular file");
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw IoError(name + ": cannot open: " + std::strerror(errno));
  std::string data;
  const auto size_hint = std::filesystem::file_size(path, ec);
  if (!ec) data.reserve(static_cast<std::size_t>(size_hint));
  char buffer[1 << 16];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) data.append(buffer, n);
  if (std::ferror(file.get())) throw IoError(name + ": read error: " + std::strerror(errno));
  return data;
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool starts_with_word(std::string_view data, std::string_view word) {
  std::size_t i = 0;
  while (i < data.size() && detail::is_space_or_newline(data[i])) ++i;
  return data.substr(i, word.size()) == word;
}

//! First whitespace-delimited token of the data (comments not skipped).
std::string_view first_token(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && detail::is_space_or_newline(data[i])) ++i;
  std::size_t j = i;
  while (j < data.size() && j - i < 16 && !detail::is_space_or_newline(data[j])) ++j;
  return data.substr(i, j - i);
}

bool looks_like_off_keyword(std::string_view t) {
  if (t.size() < 3 || t.substr(t.size() - 3) != "OFF") return false;
  for (char c : t.substr(0, t.size() - 3))
    if (std::string_view("STCN4n").find(c) == std::string_view::npos) return false;
  return true;
}

bool looks_like_binary_stl(std::string_view data) {
  if (data.size() < 84) return false;
  std::uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);  // little-endian on every machine we build for
  if constexpr (std::endian::native == std::endian::big) n = __builtin_bswap32(n);
  return 84 + 50 * static_cast<std::uint64_t>(n) == data.size();
}

bool looks_like_obj(std::string_view data) {
  // A line starting with "v " or "f " within the first 64 kB.
  const std::string_view head = data.substr(0, 1 << 16);
  std::size_t pos = 0;
  while (pos < head.size()) {
    std::size_t i = pos;
    while (i < head.size() && detail::is_space(head[i])) ++i;
    if (i + 1 < head.size() && (head[i] == 'v' || head[i] == 'f') && (head[i + 1] == ' ' || head[i + 1] == '\t'))
      return true;
    const std::size_t nl = head.find('\n', pos);
    if (nl == std::string_view::npos) break;
    pos = nl + 1;
  }
  return false;
}

MeshFormat choose_format(const std::filesystem::path& path, std::string_view data, const std::string& name) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".stl") return MeshFormat::Stl;
  if (ext == ".3mf") return MeshFormat::ThreeMf;
  // Unknown extension: look at the content.
  if (data.substr(0, 4) == std::string_view("PK\x03\x04", 4)) return MeshFormat::ThreeMf;  // a zip
  if (data.substr(0, 3) == "ply" && data.size() > 3 && (data[3] == '\n' || data[3] == '\r')) return MeshFormat::Ply;
  if (looks_like_off_keyword(first_token(data))) return MeshFormat::Off;
  if (looks_like_binary_stl(data) || starts_with_word(data, "solid")) return MeshFormat::Stl;
  if (looks_like_obj(data)) return MeshFormat::Obj;
  throw IoError(name + ": unknown mesh format: the extension '" + ext +
                "' is not .obj, .off, .ply, .stl or .3mf and the content looks like none of them");
}

}  // namespace

Mesh read_mesh(const std::filesystem::path& path, ReadInfo* info_out) {
  const std::string name = path.string();
  const std::string data = read_whole_file(path, name);
  if (data.empty()) throw IoError(name + ": the file is empty");
  ReadInfo info;
  info.format = choose_format(path, data, name);
  Mesh mesh;
  switch (info.format) {
    case MeshFormat::Obj: detail::read_obj(data, name, mesh, info); break;
    case MeshFormat::Off: detail::read_off(data, name, mesh, info); break;
    case MeshFormat::Ply: detail::read_ply(data, name, mesh, info); break;
    case MeshFormat::Stl: detail::read_stl(data, name, mesh, info); break;
    case MeshFormat::ThreeMf: detail::read_3mf(data, name, mesh, info); break;
  }
  if (mesh.faces.empty())
    detail::throw_invalid(name, {},
                          "the file has no faces (" + std::to_string(mesh.num_vertices()) +
                              " vertices): subfab needs a triangle mesh, not a point cloud");
  if (mesh.num_vertices() > static_cast<std::size_t>(INT_MAX))
    detail::throw_invalid(name, {}, "too many vertices (" + std::to_string(mesh.num_vertices()) + ")");
  // The readers check every index and coordinate where they read it (with the
  // line or byte offset); this is a cheap last guard for the invariant.
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) detail::check_finite(mesh.vertices[v], v, name, {});
  for (const auto& t : mesh.faces)
    for (int v : t) detail::checked_index(v, mesh.num_vertices(), name, {});
  info.unreferenced_removed = remove_unreferenced_vertices(mesh);
  if (info.unreferenced_removed > 0)
    info.notes.push_back("dropped " + std::to_string(info.unreferenced_removed) +
                         " vertices that no face uses");
  if (info_out) *info_out = std::move(info);
  return mesh;
}

}  // namespace subfab
