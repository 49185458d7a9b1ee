// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/simplify_unfoldable.h"

#include <cmath>
#include <string>

#include "subfab/core/error.h"
#include "subfab/unfold/apply_masks.h"
#include "subfab/unfold/build_lattice.h"
#include "subfab/unfold/extract_charts.h"
#include "subfab/unfold/marching_cubes.h"
#include "geometry/hausdorff_distance.h"
#include "unfold/triangulate_facets.h"

namespace subfab {

SimplifyUnfoldableResult simplify_unfoldable(const Mesh& mesh, const SimplifyUnfoldableOptions& options) {
  if (!(options.granularity > 0) || !std::isfinite(options.granularity))
    throw InvalidArgumentError("granularity must be a positive number");
  Progress* progress = options.progress;
  SimplifyUnfoldableResult result;

  // Stages 1-4 (lattice, marching cubes, charts, masks).
  const Lattice lattice = build_lattice(mesh, {.granularity = options.granularity, .progress = progress});
  const McSurface surface = marching_cubes(lattice, {.progress = progress});
  if (surface.mesh.faces.empty())
    throw InvalidArgumentError("the grid is too coarse for this model: no lattice point lies inside it; use a "
                               "smaller granularity (grid spacing " + std::to_string(lattice.grid.spacing) + ")");
  const Charts charts = extract_charts(surface.mesh, surface.normals, {.progress = progress});
  result.spacing = lattice.grid.spacing;
  result.origin = lattice.grid.origin;
  result.summary.facets_mc = charts.poly.num_facets();
  PolyMesh poly;
  Mesh masked_triangles;
  if (options.masks) {
    MaskResult masked = apply_masks(lattice, {.reference = &mesh, .progress = progress});
    masked_triangles = std::move(masked.surface.mesh);
    poly = std::move(masked.charts.poly);
  } else {
    masked_triangles = surface.mesh;
    poly = charts.poly;
  }
  result.summary.facets_after_masks = poly.num_facets();

  // Stage 5: automatic deletion, then the ids the user gave (numbered as in
  // the output of a run without them).
  const double s = result.spacing;
  result.min_facet_area = options.min_facet_area < 0 ? 4.0 * s * s : options.min_facet_area;
  DeleteFacetsResult deleted = delete_facets(poly, {.min_facet_area = result.min_facet_area,
                                                    .facet_ids = {},
                                                    .grid_origin = result.origin,
                                                    .grid_step = s,
                                                    .max_extension = 1.5 * s,
                                                    .reference = &mesh,
                                                    .max_distance_to_reference = 1.5 * s,
                                                    .max_group_size = 4,
                                                    .progress = progress});
  result.failures = deleted.failures;
  if (!options.delete_facet_ids.empty()) {
    DeleteFacetsResult chosen = delete_facets(deleted.mesh, {.min_facet_area = 0,
                                                             .facet_ids = options.delete_facet_ids,
                                                             .grid_origin = result.origin,
                                                             .grid_step = s,
                                                             .progress = progress});
    result.failures.insert(result.failures.end(), chosen.failures.begin(), chosen.failures.end());
    deleted.mesh = std::move(chosen.mesh);
  }
  result.mesh = std::move(deleted.mesh);
  result.summary.facets_final = result.mesh.num_facets();

  // Stage 6.
  result.unfolding = unfold_nets(result.mesh, {.progress = progress});
  result.summary.nets = result.unfolding.nets.size();

  // Verification (exact where it decides validity) and the distance to the input.
  {
    StageScope stage(progress, "verify");
    if (const std::string r = check_poly_mesh(result.mesh, result.origin, s); !r.empty())
      throw AlgorithmError("the simplified mesh failed its exact check: " + r);
    if (const std::string r = find_net_overlap(result.unfolding); !r.empty())
      throw AlgorithmError("the unfolding failed its check: " + r);
    const double diagonal = bounding_box(mesh).diagonal();
    result.refold_error = refold_error(result.mesh, result.unfolding);
    if (!(result.refold_error <= 1e-9 * diagonal))
      throw AlgorithmError("refolding the nets misses the model by " + std::to_string(result.refold_error) +
                           " (more than 1e-9 of the diagonal)");
    const Mesh triangles = unfold_detail::triangulate_facets(result.mesh);
    result.summary.hausdorff = detail::hausdorff_distance(mesh, triangles, 60000);
    result.hausdorff_after_masks = detail::hausdorff_distance(mesh, masked_triangles, 30000);
    if (progress) {
      progress->info(std::to_string(result.summary.facets_final) + " facets, " +
                     std::to_string(result.summary.nets) + " nets, Hausdorff distance " +
                     std::to_string(result.summary.hausdorff / s) + " x grid spacing");
      if (result.summary.hausdorff > 2 * s)
        progress->warn("the simplified mesh is farther than 2 grid spacings from the input");
    }
  }
  return result;
}

}  // namespace subfab
