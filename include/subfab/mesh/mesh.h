// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mesh.h
//! The plain triangle mesh every part of subfab exchanges: flat arrays of
//! vertex positions and triangles, nothing else. Algorithms that need
//! connectivity or exact arithmetic build their own structures from it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <limits>
#include <vector>

namespace subfab {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<int, 3>;

//! A triangle mesh.
//! - vertices: #V positions (model units).
//! - faces:    #F triangles, 0-based indices into vertices, counter-clockwise
//!             seen from outside for a correctly oriented closed solid.
struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> faces;

  std::size_t num_vertices() const { return vertices.size(); }
  std::size_t num_faces() const { return faces.size(); }
  bool empty() const { return faces.empty(); }
};

//! Axis-aligned bounding box. Empty when min > max in any coordinate.
struct BoundingBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  bool is_empty() const { return (min.array() > max.array()).any(); }
  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  Vec3 size() const { return is_empty() ? Vec3::Zero() : Vec3(max - min); }
  double diagonal() const { return size().norm(); }
};

//! Bounding box of the vertices referenced by faces (all vertices if
//! `referenced_only` is false).
BoundingBox bounding_box(const Mesh& mesh, bool referenced_only = true);

//! Largest |coordinate| over all vertices (0 for none): the magnitude that
//! bounds the rounding error of arithmetic on the coordinates.
double largest_coordinate(const Mesh& mesh);

//! Scale of a mesh's rounding errors: max(bounding-box diagonal, largest
//! |coordinate|). Tolerances "relative to the model" multiply it.
double rounding_scale(const Mesh& mesh);

//! Unnormalised normal of face f: (b - a) x (c - a); its length is twice the area.
Vec3 face_normal_scaled(const Mesh& mesh, std::size_t f);

//! Area of face f.
double face_area(const Mesh& mesh, std::size_t f);

//! Unit normal of face f (zero vector for a degenerate face).
Vec3 face_unit_normal(const Mesh& mesh, std::size_t f);

//! Total surface area.
double surface_area(const Mesh& mesh);

//! Signed volume enclosed (positive for a closed, outward-oriented mesh),
//! by the divergence theorem; meaningless if the mesh is not closed.
double signed_volume(const Mesh& mesh);

//! Mean length of the mesh's edges (each undirected edge counted once).
double average_edge_length(const Mesh& mesh);

//! The neighbours of every vertex through the faces' edges, as compressed
//! rows: vertex v's are ids[start[v] .. start[v + 1]), sorted and unique
//! (never v itself).
struct VertexNeighbours {
  std::vector<int> start, ids;  // #V + 1 offsets; neighbour ids
  int begin(int v) const { return start[static_cast<std::size_t>(v)]; }
  int end(int v) const { return start[static_cast<std::size_t>(v) + 1]; }
  int at(int i) const { return ids[static_cast<std::size_t>(i)]; }
  int count(int v) const { return end(v) - begin(v); }
};

//! The vertex neighbours of `mesh` (see VertexNeighbours); a vertex no face
//! references has none. Face indices must be in range.
VertexNeighbours vertex_neighbours(const Mesh& mesh);

//! Removes vertices no face references and renumbers the faces.
//! Returns the number of vertices removed.
std::size_t remove_unreferenced_vertices(Mesh& mesh);

//! Merges vertices with exactly equal coordinates (bitwise-equal doubles)
//! and renumbers faces. Returns the number of vertices merged away.
std::size_t weld_identical_vertices(Mesh& mesh);

//! Applies p -> rotation * p + translation to every vertex.
void transform_mesh(Mesh& mesh, const Eigen::Matrix3d& rotation, const Vec3& translation);

}  // namespace subfab
