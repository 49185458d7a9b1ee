// SPDX-License-Identifier: GPL-3.0-or-later
//! \file repair_infeasible_features.cpp
//! The driver of the local repair (thesis Section 4.3.5, local version; the
//! outline is in the header): stage A's rounds over the features with
//! refinement between them (the edits themselves: fix_infeasible_feature.h),
//! stage B's band refinement and Taubin smoothing, the checks and the report.
#include "subfab/fidelity/repair_infeasible_features.h"

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "fidelity/fix_infeasible_feature.h"
#include "geometry/surface_deviation.h"
#include "subfab/checks/require_closed_solid.h"
#include "subfab/core/error.h"
#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/mesh/refine_mesh.h"
#include "subfab/mesh/taubin_smooth.h"

namespace subfab {
namespace {


void check_options(const RepairOptions& o) {
  auto positive = [](double x) { return x > 0 && std::isfinite(x); };
  if (o.max_rounds < 0) throw InvalidArgumentError("repair: max_rounds must be >= 0");
  if (!positive(o.max_deviation))
    throw InvalidArgumentError("repair: maximum deviation must be a positive fraction of the bbox diagonal (got " +
                               std::to_string(o.max_deviation) + ")");
  if (!positive(o.edge_length))
    throw InvalidArgumentError("repair: edge length must be a positive fraction of the bbox diagonal (got " +
                               std::to_string(o.edge_length) + ")");
  if (o.band_rings < 1) throw InvalidArgumentError("repair: band_rings must be >= 1");
  if (o.widen_every < 1) throw InvalidArgumentError("repair: widen_every must be >= 1");
  if (o.smoothing_steps < 1) throw InvalidArgumentError("repair: smoothing_steps must be >= 1");
  if (o.max_stalled_rounds < 1) throw InvalidArgumentError("repair: max_stalled_rounds must be >= 1");
  if (!(o.lambda > 0 && o.lambda < 1)) throw InvalidArgumentError("repair: Taubin lambda must be in (0, 1)");
  if (!(o.mu == 0 || (o.mu < -o.lambda && o.mu > -1)))
    throw InvalidArgumentError("repair: Taubin mu must be 0 (plain Laplacian) or in (-1, -lambda)");
}

using Neighbours = VertexNeighbours;

//! Vertices of the features (sorted, unique).
std::vector<int> feature_vertices(const FeasibilityResult& features) {
  std::vector<int> v;
  for (const auto& f : features.features) {
    v.push_back(f.vertex0);
    if (f.vertex1 >= 0) v.push_back(f.vertex1);
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

//! Per vertex: edge-ring distance to `sources` if < `rings`, else -1 (BFS).
std::vector<int> band_vertices(const Neighbours& n, std::size_t num_vertices, const std::vector<int>& sources,
                               int rings) {
  std::vector<int> dist(num_vertices, -1);
  std::vector<int> frontier = sources;
  for (int v : sources) dist[static_cast<std::size_t>(v)] = 0;
  for (int d = 1; d < rings && !frontier.empty(); ++d) {
    std::vector<int> next;
    for (int v : frontier)
      for (int i = n.begin(v); i < n.end(v); ++i) {
        const int w = n.ids[static_cast<std::size_t>(i)];
        if (dist[static_cast<std::size_t>(w)] >= 0) continue;
        dist[static_cast<std::size_t>(w)] = d;
        next.push_back(w);
      }
    frontier = std::move(next);
  }
  return dist;
}

double longest_edge(const Mesh& mesh, const Triangle& t) {
  double l = 0;
  for (int e = 0; e < 3; ++e)
    l = std::max(l, (mesh.vertices[static_cast<std::size_t>(t[e])] -
                     mesh.vertices[static_cast<std::size_t>(t[(e + 1) % 3])])
                        .norm());
  return l;
}

std::string summary(const Mesh& mesh, const FeasibilityResult& features) {
  std::ostringstream msg;
  msg << features.num_edges << " crease edge(s) and " << features.num_vertices << " corner vertex(es) ("
      << describe_infeasible_features(features, mesh, 2) << ")";
  return msg.str();
}

double max_displacement(const Mesh& mesh, const Mesh& reference) {
  double d = 0;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    d = std::max(d, (mesh.vertices[v] - reference.vertices[v]).norm());
  return d;
}

bool same_feature(const InfeasibleFeature& a, const InfeasibleFeature& b) {
  return a.kind == b.kind && a.vertex0 == b.vertex0 && a.vertex1 == b.vertex1;
}

}  // namespace

RepairResult repair_infeasible_features(const Mesh& input, const RepairOptions& options) {
  check_options(options);
  RepairResult result;
  RepairReport& report = result.report;
  report.bbox_diagonal = bounding_box(input).diagonal();
  FeasibilityResult features = find_infeasible_features(input);
  report.num_creases = static_cast<int>(features.num_edges);
  report.num_vertices = static_cast<int>(features.num_vertices);
  report.num_features = static_cast<int>(features.size());
  if (features.feasible()) {
    result.mesh = input;
    return result;
  }
  Progress* progress = options.progress;
  if (progress) {
    std::ostringstream msg;
    msg << features.size() << " infeasible features (" << report.num_creases << " creases, " << report.num_vertices
        << " vertices) in this frame: repairing them locally";
    progress->info(msg.str());
  }
  const double diagonal = report.bbox_diagonal;
  const double target_edge = options.edge_length * diagonal;
  const double cap = options.max_deviation * diagonal;
  Mesh mesh = input;       // being repaired
  Mesh reference = input;  // same connectivity, each vertex at its point of the input surface

  // A. Local edits that each strictly reduce the number of features
  // (detail::fix_infeasible_feature), with refinement of the stars no edit fixes.
  {
    detail::RepairWork w{input, input, 1e-9 * diagonal};
    int level = 0;
    // The chamfer is tried only once refinement is exhausted: on the refined
    // stars its strip is small, and the meshes the other edits repair are
    // repaired exactly as without it.
    detail::LocalEdits edits = detail::LocalEdits::Basic;
    // Moves are first limited to a small part of the cap, so that cheap
    // fixes do not use up the deviation that harder features need.
    const std::array<double, 3> budgets{cap / 16, cap / 4, cap};
    std::size_t budget = 0;
    while (!features.feasible() && report.num_rounds < options.max_rounds) {
      bool fixed_any = false;
      const std::vector<InfeasibleFeature> snapshot = features.features;
      for (const InfeasibleFeature& f : snapshot) {
        if (std::none_of(features.features.begin(), features.features.end(),
                         [&](const InfeasibleFeature& g) { return same_feature(f, g); }))
          continue;
        fixed_any = detail::fix_infeasible_feature(w, f, features, budgets[budget], edits) || fixed_any;
        if (features.feasible()) break;
      }
      ++report.num_rounds;
      if (progress) {
        std::ostringstream msg;
        msg << "repair round " << report.num_rounds << " (local edits): " << w.mesh.faces.size() << " faces, deviation <= "
            << max_displacement(w.mesh, w.reference) << ", " << summary(w.mesh, features) << " left";
        progress->info(msg.str());
      }
      if (fixed_any || features.feasible()) continue;
      if (budget + 1 < budgets.size()) {
        ++budget;
        continue;
      }
      budget = 0;
      // No edit helped: refine the faces around the remaining features.
      const std::vector<std::vector<int>> star = detail::vertex_stars(w.mesh);
      std::vector<int> split;
      for (int v : feature_vertices(features))
        for (int u : detail::ring_vertices(w.mesh, star, v, 1))
          for (int f : star[static_cast<std::size_t>(u)])
            if (longest_edge(w.mesh, w.mesh.faces[static_cast<std::size_t>(f)]) > target_edge) split.push_back(f);
      // Bounded work: at most 6 levels, and a few hundred new faces per input
      // feature (a long sharp crease needs the fillet of B, not vertex edits).
      if (split.empty() || ++level > 6 ||
          w.mesh.faces.size() > input.faces.size() + 400 * static_cast<std::size_t>(report.num_features)) {
        if (edits == detail::LocalEdits::WithRidgeChamfer) break;
        edits = detail::LocalEdits::WithRidgeChamfer;  // one more pass over the budgets, with the chamfer
        continue;
      }
      RefineResult refined = refine_mesh(w.mesh, split);
      w.reference.vertices = refine_mesh(w.reference, split).mesh.vertices;
      w.reference.faces = refined.mesh.faces;
      w.mesh = std::move(refined.mesh);
      features = find_infeasible_features(w.mesh);
    }
    if (features.feasible()) {
      mesh = std::move(w.mesh);
      reference = std::move(w.reference);
    } else {  // B below starts again from the input (the edits may have used up the deviation cap)
      features = find_infeasible_features(input);
    }
  }
  // B. What the local edits could not fix (sharp creases that need a fillet
  // of several strips): rounds of band refinement and Taubin smoothing.

  // Fewest features after a round of B so far (the first round sets it: the
  // refinement first multiplies the features of the input), and the rounds
  // since that count last dropped.
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  int stalled = 0;
  for (int round = 0; !features.feasible(); ++round) {
    if (stalled >= options.max_stalled_rounds) {
      std::ostringstream msg;
      msg << "cannot repair " << summary(mesh, features) << ": " << stalled
          << " rounds of local refinement and smoothing did not reduce the number of features below " << fewest
          << "; the model cannot be decomposed into exact height-field blocks in this frame (try another "
             "orientation, or smooth the model there)";
      throw AlgorithmError(msg.str());
    }
    if (round >= options.max_rounds) {
      std::ostringstream msg;
      msg << "cannot repair " << summary(mesh, features) << " within " << options.max_rounds
          << " rounds of local refinement and smoothing; the model cannot be decomposed into exact height-field "
             "blocks in this frame (try another orientation, or smooth the model there)";
      throw AlgorithmError(msg.str());
    }
    const int rings = options.band_rings + round / options.widen_every;
    // b. Refine the band down to the target edge length.
    for (;;) {
      const Neighbours n = vertex_neighbours(mesh);
      const std::vector<int> sources = feature_vertices(features);
      const std::vector<int> dist = band_vertices(n, mesh.vertices.size(), sources, rings);
      // Faces of the band (in rings) that are long and near a feature
      // vertex (bounding box within `rings + 1` target edges): the refined
      // region shrinks to a tube of a few target edges around the features.
      const double reach = (rings + 1) * target_edge;
      std::vector<int> split;
      for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Triangle& t = mesh.faces[f];
        const bool in_band = std::any_of(t.begin(), t.end(), [&](int v) { return dist[static_cast<std::size_t>(v)] >= 0; });
        if (!in_band || longest_edge(mesh, t) <= target_edge) continue;
        BoundingBox box;
        for (int v : t) box.extend(mesh.vertices[static_cast<std::size_t>(v)]);
        const bool near = std::any_of(sources.begin(), sources.end(), [&](int v) {
          const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
          return (p.cwiseMax(box.min).cwiseMin(box.max) - p).norm() <= reach;
        });
        if (near) split.push_back(static_cast<int>(f));
      }
      if (split.empty()) break;
      RefineResult refined = refine_mesh(mesh, split);
      reference.vertices = refine_mesh(reference, split).mesh.vertices;  // same combinatorics
      reference.faces = refined.mesh.faces;
      mesh = std::move(refined.mesh);
      features = find_infeasible_features(mesh);
      if (features.feasible()) break;  // rounding of midpoints can resolve a feature
    }
    if (features.feasible()) break;
    // c. Taubin smoothing of the band.
    const Neighbours n = vertex_neighbours(mesh);
    const std::vector<int> dist = band_vertices(n, mesh.vertices.size(), feature_vertices(features), rings);
    std::vector<int> movable;
    for (std::size_t v = 0; v < dist.size(); ++v)
      if (dist[v] >= 0) movable.push_back(static_cast<int>(v));
    TaubinOptions taubin;
    taubin.num_passes = options.smoothing_steps;
    taubin.lambda = options.lambda;
    taubin.mu = options.mu;
    taubin.weights = TaubinWeights::Uniform;
    taubin.keep_axis_aligned = true;  // axis-aligned flats stay exactly flat
    taubin_smooth(mesh, movable, taubin);
    // d. Deviation cap (max vertex displacement bounds the Hausdorff distance).
    const double bound = max_displacement(mesh, reference);
    if (bound > cap) {
      std::ostringstream msg;
      features = find_infeasible_features(mesh);  // ids of this mesh, for the message
      msg << "cannot repair " << summary(mesh, features) << " without moving the surface by more than "
          << options.max_deviation << " of the bounding-box diagonal (" << cap << " model units; reached " << bound
          << " after " << round + 1 << " rounds); the model cannot be decomposed into exact height-field blocks "
          << "in this frame (allow a larger deviation with --max-deviation, or try another orientation)";
      throw AlgorithmError(msg.str());
    }
    ++report.num_rounds;
    features = find_infeasible_features(mesh);
    if (features.size() < fewest) {
      fewest = features.size();
      stalled = 0;
    } else {
      ++stalled;
    }
    if (progress) {
      std::ostringstream msg;
      msg << "repair round " << round + 1 << ": " << mesh.faces.size() << " faces, " << movable.size()
          << " vertices smoothed, deviation <= " << bound << ", " << features.size() << " features left";

      progress->info(msg.str());
    }
  }

  // 3. Still a valid solid?
  require_closed_solid_result(mesh, "repairing the infeasible features produced an invalid solid (",
                              "); try a smaller edge length or fewer smoothing steps");
  // 4. Report.
  const std::vector<int> changed_input = detail::faces_not_in(input, mesh);
  const std::vector<int> changed = detail::faces_not_in(mesh, input);
  report.num_faces_removed = static_cast<int>(changed_input.size());
  report.num_faces_new = static_cast<int>(changed.size());
  report.hausdorff_error = std::max(1e-5 * diagonal, 1e-300);
  // Exact where the surface did not move: `reference` describes the input
  // surface with the result's connectivity.
  const detail::SurfaceDeviation deviation =
      detail::surface_deviation(input, changed_input, mesh, changed, report.hausdorff_error);
  report.max_deviation = std::min(deviation.hausdorff, max_displacement(mesh, reference));
  report.mean_deviation = deviation.mean;
  if (progress) {
    std::ostringstream msg;
    msg << "repaired " << report.num_features << " infeasible features in " << report.num_rounds << " rounds: "
        << report.num_faces_removed << " faces replaced by " << report.num_faces_new << ", deviation max "
        << report.max_deviation << " (" << report.max_deviation_fraction() << " of the diagonal), mean "
        << report.mean_deviation;
    progress->warn(msg.str());
  }
  result.mesh = std::move(mesh);
  return result;
}

}  // namespace subfab
