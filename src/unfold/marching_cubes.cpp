// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/marching_cubes.h"

#include <string>

#include "mc_case_table.h"
#include "subfab/core/parallel.h"

namespace subfab {

const std::vector<std::array<int, 3>>& cube_triangles(int config) {
  return mc::case_table()[static_cast<std::size_t>(config & 255)].triangles;
}
const std::vector<int>& cube_triangle_normals(int config) {
  return mc::case_table()[static_cast<std::size_t>(config & 255)].normals;
}

McSurface marching_cubes(const Lattice& lattice, const MarchingCubesOptions& options) {
  StageScope stage(options.progress, "marching cubes");
  const GridPoints& g = lattice.grid;
  const int nx = g.size[0], ny = g.size[1], nz = g.size[2];
  McSurface out;
  if (nx < 2 || ny < 2 || nz < 2) return out;
  const std::size_t num_points = g.num_points();
  const std::array<std::size_t, 3> stride{1, static_cast<std::size_t>(nx),
                                          static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)};
  const auto& table = mc::case_table();
  const auto& edges = mc::cube_edges();
  // Lattice offset of each cube corner.
  std::array<std::size_t, 8> corner_offset{};
  for (int c = 0; c < 8; ++c)
    corner_offset[static_cast<std::size_t>(c)] =
        ((c & 1) ? stride[0] : 0) + (((c >> 1) & 1) ? stride[1] : 0) + (((c >> 2) & 1) ? stride[2] : 0);

  // 1. One vertex per sign-changing lattice edge, numbered in edge order
  //    (counted per z-slice, then filled: deterministic).
  auto crossing = [&](std::size_t p, int axis, const int (&ijk)[3]) {
    if (ijk[axis] + 1 >= g.size[static_cast<std::size_t>(axis)]) return false;
    return lattice.inside[p] != lattice.inside[p + stride[static_cast<std::size_t>(axis)]];
  };
  std::vector<std::size_t> slice_vertices(static_cast<std::size_t>(nz) + 1, 0);
  parallel_for(0, static_cast<std::size_t>(nz), [&](std::size_t k) {
    std::size_t count = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int ijk[3] = {i, j, static_cast<int>(k)};
        const std::size_t p = g.index(i, j, ijk[2]);
        for (int a = 0; a < 3; ++a) count += crossing(p, a, ijk);
      }
    slice_vertices[k + 1] = count;
  });
  for (std::size_t k = 0; k < static_cast<std::size_t>(nz); ++k) slice_vertices[k + 1] += slice_vertices[k];
  const std::size_t num_vertices = slice_vertices[static_cast<std::size_t>(nz)];
  std::vector<std::int32_t> edge_vertex(3 * num_points, -1);  // lattice edge 3 * p + axis -> vertex
  out.mesh.vertices.resize(num_vertices);
  out.vertex_edge.resize(num_vertices);
  parallel_for(0, static_cast<std::size_t>(nz), [&](std::size_t k) {
    std::size_t id = slice_vertices[k];
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int ijk[3] = {i, j, static_cast<int>(k)};
        const std::size_t p = g.index(i, j, ijk[2]);
        for (int a = 0; a < 3; ++a) {
          if (!crossing(p, a, ijk)) continue;
          Vec3 v = g.point(i, j, ijk[2]);
          v[a] = 0.5 * (g.coordinate(a, ijk[a]) + g.coordinate(a, ijk[a] + 1));
          out.mesh.vertices[id] = v;
          out.vertex_edge[id] = 3 * p + static_cast<std::size_t>(a);
          edge_vertex[3 * p + static_cast<std::size_t>(a)] = static_cast<std::int32_t>(id);
          ++id;
        }
      }
  });

  // 2. Triangles, cube by cube (counted per slice of cubes, then filled).
  auto cube_config = [&](std::size_t p) {
    int config = 0;
    for (int c = 0; c < 8; ++c)
      if (lattice.inside[p + corner_offset[static_cast<std::size_t>(c)]]) config |= 1 << c;
    return config;
  };
  const std::size_t num_cube_slices = static_cast<std::size_t>(nz - 1);
  std::vector<std::size_t> slice_faces(num_cube_slices + 1, 0);
  parallel_for(0, num_cube_slices, [&](std::size_t k) {
    std::size_t count = 0;
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        count += table[static_cast<std::size_t>(cube_config(g.index(i, j, static_cast<int>(k))))].triangles.size();
    slice_faces[k + 1] = count;
  });
  for (std::size_t k = 0; k < num_cube_slices; ++k) slice_faces[k + 1] += slice_faces[k];
  out.mesh.faces.resize(slice_faces[num_cube_slices]);
  out.normals.resize(slice_faces[num_cube_slices]);
  parallel_for(0, num_cube_slices, [&](std::size_t k) {
    std::size_t f = slice_faces[k];
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        const std::size_t p = g.index(i, j, static_cast<int>(k));
        const mc::CubeCase& cc = table[static_cast<std::size_t>(cube_config(p))];
        for (std::size_t t = 0; t < cc.triangles.size(); ++t) {
          Triangle tri;
          for (int s = 0; s < 3; ++s) {
            const mc::CubeEdge& e = edges[static_cast<std::size_t>(cc.triangles[t][static_cast<std::size_t>(s)])];
            const std::size_t q = p + corner_offset[static_cast<std::size_t>(e.corners[0])];
            tri[static_cast<std::size_t>(s)] = edge_vertex[3 * q + static_cast<std::size_t>(e.axis)];
          }
          out.mesh.faces[f] = tri;
          out.normals[f] = cc.normals[t];
          ++f;
        }
      }
  });
  if (options.progress)
    options.progress->info(std::to_string(out.mesh.faces.size()) + " marching-cubes triangles, " +
                           std::to_string(num_vertices) + " vertices");
  return out;
}

}  // namespace subfab
