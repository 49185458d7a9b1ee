// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/fidelity/smooth_for_decomposition.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/surface_deviation.h"
#include "subfab/checks/check_degenerate_faces.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/checks/require_closed_solid.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

// Offending faces fetched per exact check (the checks list them in face
// order); more are found by the next round of the same back-off loop.
constexpr std::size_t kMaxOffendingFaces = 4096;

void check_options(const SmoothOptions& o) {
  if (o.num_passes < 0) throw InvalidArgumentError("smooth: the number of passes must be >= 0");
  if (o.check_every < 1) throw InvalidArgumentError("smooth: check_every must be >= 1");
  if (!(o.max_deviation >= 0 && std::isfinite(o.max_deviation)))
    throw InvalidArgumentError("smooth: the maximum deviation must be a finite fraction of the bbox diagonal >= 0 (got " +
                               std::to_string(o.max_deviation) + ")");
  if (!(o.hausdorff_error > 0 && std::isfinite(o.hausdorff_error)))
    throw InvalidArgumentError("smooth: the Hausdorff error bound must be a positive fraction of the diagonal");
  // lambda and mu are checked by taubin_smooth().
}

//! Component id per face (faces linked through shared vertices), ids in
//! order of first face.
std::vector<int> face_components(const Mesh& mesh, int& num_components) {
  std::vector<int> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (const Triangle& t : mesh.faces)
    for (int e = 1; e < 3; ++e) {
      const int a = find(t[0]), b = find(t[static_cast<std::size_t>(e)]);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> id(mesh.vertices.size(), -1), component(mesh.faces.size());
  num_components = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    int& c = id[static_cast<std::size_t>(find(mesh.faces[f][0]))];
    if (c < 0) c = num_components++;
    component[f] = c;
  }
  return component;
}

//! Signed volume of each component (positive: a solid's outer shell,
//! negative: the boundary of a cavity).
std::vector<double> component_volumes(const Mesh& mesh, const std::vector<int>& component, int num_components) {
  std::vector<double> volume(static_cast<std::size_t>(num_components), 0.0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle& t = mesh.faces[f];
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    volume[static_cast<std::size_t>(component[f])] += a.dot(b.cross(c)) / 6;
  }
  return volume;
}

//! Faces that make `mesh` an invalid solid, assuming its connectivity is that
//! of a valid one: degenerate faces, faces of self-intersecting pairs (exact)
//! and every face of a component whose volume lost the sign it has in the
//! input (`input_volumes`; shells and cavities may not turn inside out).
//! Sorted, unique; at most about kMaxOffendingFaces of the first two kinds.
std::vector<int> invalid_faces(const Mesh& mesh, const std::vector<int>& component,
                               const std::vector<double>& input_volumes) {
  CheckOptions options;
  options.max_examples = kMaxOffendingFaces;
  std::vector<int> bad = check_degenerate_faces(mesh, options).examples;
  const std::vector<int> crossing = check_self_intersections(mesh, options).examples;
  bad.insert(bad.end(), crossing.begin(), crossing.end());
  const std::vector<double> volume =
      component_volumes(mesh, component, static_cast<int>(input_volumes.size()));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto c = static_cast<std::size_t>(component[f]);
    if (!(volume[c] * input_volumes[c] > 0)) bad.push_back(static_cast<int>(f));
  }
  std::sort(bad.begin(), bad.end());
  bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
  return bad;
}

}  // namespace

SmoothResult smooth_for_decomposition(const Mesh& input_mesh, const SmoothOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_options(options);
  Progress* progress = options.progress;
  StageScope stage(progress, "smooth");
  Mesh input = input_mesh;
  require_closed_solid(input, progress);  // InvalidMeshError: not a usable solid

  SmoothResult result;
  SmoothReport& report = result.report;
  report.bbox_diagonal = bounding_box(input).diagonal();
  report.input_volume = signed_volume(input);
  const double cap = options.max_deviation * report.bbox_diagonal;
  int num_components = 0;
  const std::vector<int> component = face_components(input, num_components);
  const std::vector<double> input_volumes = component_volumes(input, component, num_components);

  Mesh mesh = input;
  std::vector<char> frozen(mesh.vertices.size(), 0);
  TaubinOptions taubin{.num_passes = 0,
                       .lambda = options.lambda,
                       .mu = options.mu,
                       .weights = options.weights,
                       .max_displacement = cap,
                       .anchors = input.vertices};
  double check_seconds = 0;
  for (int pass = 0; pass < options.num_passes; pass += options.check_every) {
    std::vector<int> movable;
    for (std::size_t v = 0; v < frozen.size(); ++v)
      if (!frozen[v]) movable.push_back(static_cast<int>(v));
    if (movable.empty()) break;
    const std::vector<Vec3> before = mesh.vertices;
    taubin.num_passes = std::min(options.check_every, options.num_passes - pass);
    report.num_passes += taubin_smooth(mesh, movable, taubin).num_passes;
    const auto check_start = std::chrono::steady_clock::now();
    // Back off, vertex by vertex, until the solid is valid again.
    for (;;) {
      const std::vector<int> bad = invalid_faces(mesh, component, input_volumes);
      if (bad.empty()) break;
      ++report.num_backoffs;
      int num_reverted = 0;
      for (int f : bad)
        for (int v : mesh.faces[static_cast<std::size_t>(f)]) {
          const auto i = static_cast<std::size_t>(v);
          if (mesh.vertices[i] == before[i]) continue;
          mesh.vertices[i] = before[i];
          frozen[i] = 1;
          ++report.num_vertices_frozen;
          ++num_reverted;
        }
      if (num_reverted == 0)  // every offending face is as before the pass, which was valid
        throw AlgorithmError("smooth: cannot restore a valid solid after pass " + std::to_string(pass + 1) +
                             " (internal error; please report it with the input)");
    }
    check_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - check_start).count();
  }
  const double smooth_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Final exact gate.
  require_closed_solid_result(mesh, "smooth: the smoothed mesh is not a valid solid (",
                              "); internal error, please report it with the input");

  // Deviation.
  std::vector<char> moved(mesh.vertices.size(), 0);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const double d = (mesh.vertices[v] - input.vertices[v]).norm();
    report.max_displacement = std::max(report.max_displacement, d);
    if (d > 0) {
      moved[v] = 1;
      ++report.num_vertices_moved;
      if (cap > 0 && d >= cap * (1 - 1e-9)) ++report.num_vertices_capped;
    }
  }
  std::vector<int> changed;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle& t = mesh.faces[f];
    if (moved[static_cast<std::size_t>(t[0])] || moved[static_cast<std::size_t>(t[1])] ||
        moved[static_cast<std::size_t>(t[2])])
      changed.push_back(static_cast<int>(f));
  }
  report.hausdorff_error = options.hausdorff_error * report.bbox_diagonal;
  const detail::SurfaceDeviation deviation =
      detail::surface_deviation(input, input, mesh, changed, std::max(report.hausdorff_error, 1e-300));
  report.hausdorff = std::min(deviation.hausdorff, report.max_displacement);
  report.mean_deviation = deviation.mean;
  report.volume = signed_volume(mesh);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress) {
    std::ostringstream msg;
    msg << "smoothed " << report.num_vertices_moved << " of " << mesh.vertices.size() << " vertices in "
        << report.num_passes << " passes (" << report.num_vertices_capped << " at the cap, "
        << report.num_vertices_frozen << " frozen to avoid self-intersections): Hausdorff "
        << report.hausdorff << " (" << report.fraction(report.hausdorff) << " of the diagonal), mean "
        << report.mean_deviation << " (passes and checks " << smooth_seconds << " s, of which exact checks "
        << check_seconds << " s; deviation " << report.seconds - smooth_seconds << " s)";
    progress->info(msg.str());
  }
  result.mesh = std::move(mesh);
  return result;
}

}  // namespace subfab
