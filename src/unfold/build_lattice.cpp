// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/build_lattice.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "subfab/core/error.h"

namespace subfab {

std::size_t Lattice::num_inside() const {
  return static_cast<std::size_t>(std::count(inside.begin(), inside.end(), std::uint8_t{1}));
}

Lattice build_lattice(const Mesh& mesh, const LatticeOptions& options) {
  if (!(options.granularity > 0) || !std::isfinite(options.granularity))
    throw InvalidArgumentError("granularity must be a positive number (got " + std::to_string(options.granularity) +
                               ")");
  if (options.padding < 1) throw InvalidArgumentError("lattice padding must be at least 1");
  if (mesh.faces.empty()) throw InvalidMeshError("the mesh has no faces: nothing to build a lattice on");
  StageScope stage(options.progress, "lattice");

  const BoundingBox box = bounding_box(mesh);
  const double spacing = average_edge_length(mesh) * options.granularity;
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidMeshError("the mesh's average edge length is zero or not finite: cannot size the lattice");

  Lattice lattice;
  lattice.grid.spacing = spacing;
  double num_points = 1;
  for (int a = 0; a < 3; ++a) {
    const double extent = box.max[a] - box.min[a];
    const int cells = static_cast<int>(std::ceil(extent / spacing)) + 2 * options.padding;
    lattice.grid.size[a] = cells + 1;
    num_points *= cells + 1;
    // Centre the grid on the box.
    lattice.grid.origin[a] = 0.5 * (box.min[a] + box.max[a]) - 0.5 * cells * spacing;
  }
  if (num_points > static_cast<double>(options.max_points))
    throw InvalidArgumentError("the lattice would have " + std::to_string(static_cast<long long>(num_points)) +
                               " points (limit " + std::to_string(options.max_points) +
                               "): raise the granularity");

  const std::vector<std::int32_t> winding = classify_grid_points(mesh, lattice.grid);
  lattice.inside.resize(winding.size());
  std::transform(winding.begin(), winding.end(), lattice.inside.begin(),
                 [](std::int32_t w) { return static_cast<std::uint8_t>(w != 0 ? 1 : 0); });
  if (options.progress)
    options.progress->info(std::to_string(lattice.grid.size[0]) + " x " + std::to_string(lattice.grid.size[1]) +
                           " x " + std::to_string(lattice.grid.size[2]) + " lattice, spacing " +
                           std::to_string(spacing) + ", " + std::to_string(lattice.num_inside()) + " points inside");
  return lattice;
}

}  // namespace subfab
