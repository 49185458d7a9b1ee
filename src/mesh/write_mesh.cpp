// SPDX-License-Identifier: GPL-3.0-or-later
//! write_mesh(): OBJ and OFF as text with every double written in its
//! shortest exact form (std::to_chars: reads back bit for bit), binary
//! little-endian PLY with double coordinates, binary STL with float32.
//! The whole file is built in memory, then written with one call.
#include "subfab/mesh/write_mesh.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "subfab/core/error.h"

namespace subfab {
namespace {

void append_number(std::string& out, double v) {
  char buffer[32];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, ptr);
}

void append_number(std::string& out, std::int64_t v) {
  char buffer[24];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, ptr);
}

//! Appends the little-endian bytes of a trivially copyable value.
template <class T>
void append_le(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

//! "x y z" (exact shortest form of each double).
void append_point(std::string& out, const Vec3& p) {
  append_number(out, p.x());
  out += ' ';
  append_number(out, p.y());
  out += ' ';
  append_number(out, p.z());
}

std::string obj_text(const Mesh& mesh) {
  std::string out = "# written by subfab: " + std::to_string(mesh.num_vertices()) + " vertices, " +
                    std::to_string(mesh.num_faces()) + " faces\n";
  out.reserve(out.size() + mesh.num_vertices() * 64 + mesh.num_faces() * 24);
  for (const auto& p : mesh.vertices) {
    out += "v ";
    append_point(out, p);
    out += '\n';
  }
  for (const auto& t : mesh.faces) {
    out += 'f';
    for (int v : t) {
      out += ' ';
      append_number(out, std::int64_t{v} + 1);
    }
    out += '\n';
  }
  return out;
}

std::string off_text(const Mesh& mesh) {
  std::string out = "OFF\n";
  out.reserve(mesh.num_vertices() * 64 + mesh.num_faces() * 24 + 64);
  append_number(out, static_cast<std::int64_t>(mesh.num_vertices()));
  out += ' ';
  append_number(out, static_cast<std::int64_t>(mesh.num_faces()));
  out += " 0\n";
  for (const auto& p : mesh.vertices) {
    append_point(out, p);
    out += '\n';
  }
  for (const auto& t : mesh.faces) {
    out += '3';
    for (int v : t) {
      out += ' ';
      append_number(out, std::int64_t{v});
    }
    out += '\n';
  }
  return out;
}

std::string ply_binary(const Mesh& mesh) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by subfab\nelement vertex " +
                    std::to_string(mesh.num_vertices()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(mesh.num_faces()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  out.reserve(out.size() + mesh.num_vertices() * 24 + mesh.num_faces() * 13);
  for (const auto& p : mesh.vertices) {
    append_le(out, p.x());
    append_le(out, p.y());
    append_le(out, p.z());
  }
  for (const auto& t : mesh.faces) {
    append_le(out, std::uint8_t{3});
    for (int v : t) append_le(out, std::int32_t{v});
  }
  return out;
}

std::string stl_binary(const Mesh& mesh, const std::string& name) {
  if (mesh.num_faces() > UINT32_MAX)
    throw IoError(name + ": cannot write binary STL: more than 2^32 triangles");
  for (const auto& p : mesh.vertices)
    if (p.cwiseAbs().maxCoeff() > std::numeric_limits<float>::max())
      throw InvalidMeshError(name + ": cannot write binary STL: coordinate " + std::to_string(p.cwiseAbs().maxCoeff()) +
                             " does not fit in float32; scale the mesh or use .ply");
  std::string out(80, ' ');
  const std::string header = "binary STL written by subfab";  // must not start with "solid"
  out.replace(0, header.size(), header);
  out.reserve(84 + 50 * mesh.num_faces());
  append_le(out, static_cast<std::uint32_t>(mesh.num_faces()));
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 n = face_unit_normal(mesh, f);
    for (int k = 0; k < 3; ++k) append_le(out, static_cast<float>(n[k]));
    for (int v : mesh.faces[f]) {
      const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
      for (int k = 0; k < 3; ++k) append_le(out, static_cast<float>(p[k]));
    }
    append_le(out, std::uint16_t{0});
  }
  return out;
}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};

void write_file(const std::filesystem::path& path, const std::string& name, const std::string& bytes) {
  std::FILE* raw = std::fopen(path.c_str(), "wb");
  if (!raw) throw IoError(name + ": cannot open for writing: " + std::strerror(errno));
  std::unique_ptr<std::FILE, FileCloser> file(raw);
  if (std::fwrite(bytes.data(), 1, bytes.size(), raw) != bytes.size())
    throw IoError(name + ": write failed: " + std::strerror(errno));
  if (std::fclose(file.release()) != 0) throw IoError(name + ": write failed: " + std::strerror(errno));
}

}  // namespace

void write_mesh(const Mesh& mesh, const std::filesystem::path& path) {
  const std::string name = path.string();
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.num_vertices())
        throw InvalidMeshError(name + ": cannot write: face " + std::to_string(f) + " has vertex index " +
                               std::to_string(v) + ", out of range (" + std::to_string(mesh.num_vertices()) +
                               " vertices)");
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw InvalidMeshError(name + ": cannot write: vertex " + std::to_string(v) + " has a non-finite coordinate");
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string bytes;
  if (ext == ".obj")
    bytes = obj_text(mesh);
  else if (ext == ".off")
    bytes = off_text(mesh);
  else if (ext == ".ply")
    bytes = ply_binary(mesh);
  else if (ext == ".stl")
    bytes = stl_binary(mesh, name);
  else
    throw IoError(name + ": cannot write: unknown extension '" + ext + "' (use .obj, .off, .ply or .stl)");
  write_file(path, name, bytes);
}

}  // namespace subfab
