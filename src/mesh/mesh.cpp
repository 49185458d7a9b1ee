// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/mesh.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <unordered_set>

namespace subfab {

BoundingBox bounding_box(const Mesh& mesh, bool referenced_only) {
  BoundingBox box;
  if (referenced_only) {
    for (const auto& f : mesh.faces)
      for (int v : f) box.extend(mesh.vertices[static_cast<std::size_t>(v)]);
  } else {
    for (const auto& p : mesh.vertices) box.extend(p);
  }
  return box;
}

double largest_coordinate(const Mesh& mesh) {
  double largest = 0.0;
  for (const Vec3& v : mesh.vertices) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  return largest;
}

double rounding_scale(const Mesh& mesh) { return std::max(bounding_box(mesh).diagonal(), largest_coordinate(mesh)); }

Vec3 face_normal_scaled(const Mesh& mesh, std::size_t f) {
  const auto& t = mesh.faces[f];
  const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
  const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
  const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
  return (b - a).cross(c - a);
}

double face_area(const Mesh& mesh, std::size_t f) { return 0.5 * face_normal_scaled(mesh, f).norm(); }

Vec3 face_unit_normal(const Mesh& mesh, std::size_t f) {
  const Vec3 n = face_normal_scaled(mesh, f);
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

double surface_area(const Mesh& mesh) {
  double area = 0;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) area += face_area(mesh, f);
  return area;
}

double signed_volume(const Mesh& mesh) {
  // Sum of signed tetrahedra against the bounding-box centre (better
  // conditioned than against the origin for models far from it).
  const BoundingBox box = bounding_box(mesh);
  const Vec3 o = box.is_empty() ? Vec3::Zero() : Vec3(0.5 * (box.min + box.max));
  double volume = 0;
  for (const auto& t : mesh.faces) {
    const Vec3 a = mesh.vertices[static_cast<std::size_t>(t[0])] - o;
    const Vec3 b = mesh.vertices[static_cast<std::size_t>(t[1])] - o;
    const Vec3 c = mesh.vertices[static_cast<std::size_t>(t[2])] - o;
    volume += a.dot(b.cross(c));
  }
  return volume / 6.0;
}

VertexNeighbours vertex_neighbours(const Mesh& mesh) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::vector<int>> lists(nv);
  for (const Triangle& t : mesh.faces)
    for (std::size_t e = 0; e < 3; ++e)
      for (std::size_t o : {(e + 1) % 3, (e + 2) % 3})
        if (t[o] != t[e]) lists[static_cast<std::size_t>(t[e])].push_back(t[o]);  // a face repeating a vertex: not its own
  VertexNeighbours n;
  n.start.assign(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v) {
    std::sort(lists[v].begin(), lists[v].end());
    lists[v].erase(std::unique(lists[v].begin(), lists[v].end()), lists[v].end());
    n.start[v + 1] = n.start[v] + static_cast<int>(lists[v].size());
  }
  n.ids.reserve(static_cast<std::size_t>(n.start[nv]));
  for (const auto& l : lists) n.ids.insert(n.ids.end(), l.begin(), l.end());
  return n;
}

double average_edge_length(const Mesh& mesh) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(mesh.num_faces() * 3);
  for (const auto& t : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      edges.emplace_back(a, b);
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  if (edges.empty()) return 0;
  double sum = 0;
  for (const auto& [a, b] : edges)
    sum += (mesh.vertices[static_cast<std::size_t>(a)] - mesh.vertices[static_cast<std::size_t>(b)]).norm();
  return sum / static_cast<double>(edges.size());
}

std::size_t remove_unreferenced_vertices(Mesh& mesh) {
  std::vector<int> remap(mesh.num_vertices(), -1);
  for (const auto& t : mesh.faces)
    for (int v : t) remap[static_cast<std::size_t>(v)] = 0;
  std::vector<Vec3> kept;
  kept.reserve(mesh.num_vertices());
  for (std::size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == 0) {
      remap[v] = static_cast<int>(kept.size());
      kept.push_back(mesh.vertices[v]);
    }
  }
  const std::size_t removed = mesh.num_vertices() - kept.size();
  for (auto& t : mesh.faces)
    for (int& v : t) v = remap[static_cast<std::size_t>(v)];
  mesh.vertices = std::move(kept);
  return removed;
}

std::size_t weld_identical_vertices(Mesh& mesh) {
  const std::size_t n = mesh.num_vertices();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](std::size_t a, std::size_t b) {
    const Vec3& p = mesh.vertices[a];
    const Vec3& q = mesh.vertices[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int> remap(n);
  std::vector<Vec3> kept;
  kept.reserve(n);
  // Vertices keep the order of their first occurrence in the input.
  std::vector<std::size_t> representative(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && mesh.vertices[order[i]] == mesh.vertices[order[i - 1]])
      representative[order[i]] = representative[order[i - 1]];
    else
      representative[order[i]] = order[i];
  }
  std::vector<int> new_index(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    const std::size_t r = representative[v];
    if (new_index[r] < 0) {
      new_index[r] = static_cast<int>(kept.size());
      kept.push_back(mesh.vertices[r]);
    }
    remap[v] = new_index[r];
  }
  for (auto& t : mesh.faces)
    for (int& v : t) v = remap[static_cast<std::size_t>(v)];
  const std::size_t merged = n - kept.size();
  mesh.vertices = std::move(kept);
  return merged;
}

void transform_mesh(Mesh& mesh, const Eigen::Matrix3d& rotation, const Vec3& translation) {
  for (auto& p : mesh.vertices) p = rotation * p + translation;
}

}  // namespace subfab
