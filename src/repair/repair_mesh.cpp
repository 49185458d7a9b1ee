// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/repair/repair_mesh.h"

#include <CGAL/box_intersection_d.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/surface_deviation.h"
#include "repair/repair_steps.h"
#include "subfab/checks/analyze_mesh.h"
#include "subfab/core/error.h"

namespace subfab {

namespace {

void check_options(const MeshRepairOptions& o) {
  if (!(o.max_deviation > 0 && std::isfinite(o.max_deviation)))
    throw InvalidArgumentError("repair: --max-deviation must be a positive fraction of the bounding-box diagonal");
  if (!(o.min_component_fraction >= 0 && o.min_component_fraction < 1))
    throw InvalidArgumentError("repair: the minimum piece size must be a fraction in [0, 1)");
  if (!(o.pinch_separation > 0 && o.pinch_separation < 0.01))
    throw InvalidArgumentError("repair: the pinch separation must be a fraction in (0, 0.01)");
  if (!(o.hausdorff_error > 0 && std::isfinite(o.hausdorff_error)))
    throw InvalidArgumentError("repair: the Hausdorff error bound must be a positive fraction of the diagonal");
  if (o.max_self_intersection_rounds < 1)
    throw InvalidArgumentError("repair: at least one self-intersection round is needed");
}

//! The input faces the deviation is measured against: every face with three
//! distinct corner positions (a face with a repeated corner has no surface
//! of its own to measure).
Mesh measurable(const Mesh& input) {
  Mesh m;
  m.vertices = input.vertices;
  for (const Triangle& t : input.faces) {
    const Vec3 &a = input.vertices[static_cast<std::size_t>(t[0])], &b = input.vertices[static_cast<std::size_t>(t[1])],
               &c = input.vertices[static_cast<std::size_t>(t[2])];
    if (a != b && b != c && a != c && (b - a).cross(c - a).squaredNorm() > 0) m.faces.push_back(t);
  }
  return m;
}

//! The faces of `m` whose bounding box comes within `radius` of the
//! bounding box of a face listed in `changed_m` or (of `other`) in
//! `changed_other`, as a mesh (all vertices kept, so face ids change but
//! positions do not).
Mesh faces_near(const Mesh& m, const Mesh& other, const std::vector<int>& changed_m,
                const std::vector<int>& changed_other, double radius) {
  // Handles: the faces of m, and for the region boxes copies of the changed
  // faces (another array), so that the callback tells them apart.
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const Triangle*>;
  const auto face_box = [](const Mesh& mesh, const Triangle& t, const Triangle* handle, double grow) {
    double lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::numeric_limits<double>::infinity();
      hi[c] = -lo[c];
      for (int v : t) {
        lo[c] = std::min(lo[c], mesh.vertices[static_cast<std::size_t>(v)][c] - grow);
        hi[c] = std::max(hi[c], mesh.vertices[static_cast<std::size_t>(v)][c] + grow);
      }
    }
    return Box(CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]), handle);
  };
  std::vector<Triangle> anchors;
  anchors.reserve(changed_m.size() + changed_other.size());
  for (int f : changed_m) anchors.push_back(m.faces[static_cast<std::size_t>(f)]);
  for (int f : changed_other) anchors.push_back(other.faces[static_cast<std::size_t>(f)]);
  std::vector<Box> region;
  region.reserve(anchors.size());
  for (std::size_t i = 0; i < anchors.size(); ++i)
    region.push_back(face_box(i < changed_m.size() ? m : other, anchors[i], &anchors[i], radius));
  std::vector<Box> all;
  all.reserve(m.num_faces());
  for (const Triangle& t : m.faces) all.push_back(face_box(m, t, &t, 0));
  std::vector<char> keep(m.num_faces(), 0);
  const Triangle* first = m.faces.data();
  const Triangle* last = first + m.faces.size();
  CGAL::box_intersection_d(all.begin(), all.end(), region.begin(), region.end(), [&](const Box& a, const Box& b) {
    for (const Triangle* h : {a.handle(), b.handle()})
      if (h >= first && h < last) keep[static_cast<std::size_t>(h - first)] = 1;
  });
  Mesh out;
  out.vertices = m.vertices;
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (keep[f]) out.faces.push_back(m.faces[f]);
  return out;
}

//! Symmetric Hausdorff distance and mean deviation between the input
//! `reference` and the `result`, measured on the faces that differ.
//! Only the faces within `radius` of a changed face take part: a nearest
//! point farther than that means a deviation above `radius`, which the
//! restricted meshes report as well (a distance to fewer faces is not
//! smaller); then the whole meshes are measured again for the exact figure.
detail::SurfaceDeviation measure_deviation(const Mesh& reference, const Mesh& result, double radius,
                                           double error_bound) {
  const std::vector<int> changed_reference = detail::faces_not_in(reference, result);
  const std::vector<int> changed_result = detail::faces_not_in(result, reference);
  const Mesh near_reference = faces_near(reference, result, changed_reference, changed_result, radius);
  const Mesh near_result = faces_near(result, reference, changed_result, changed_reference, radius);
  detail::SurfaceDeviation d = detail::surface_deviation(
      near_reference, detail::faces_not_in(near_reference, near_result), near_result,
      detail::faces_not_in(near_result, near_reference), error_bound);
  if (d.hausdorff > radius)
    d = detail::surface_deviation(reference, changed_reference, result, changed_result, error_bound);
  return d;
}

//! The faces of `surface` that may cross another, when `input` crosses
//! nowhere (its exact self_intersections check passed): the faces whose
//! corner positions are not those of an input face (added or moved by the
//! steps), and every face whose bounding box meets one of theirs. Two other
//! faces are input faces, which do not cross (the steps leave no two vertices
//! at one position, so two such faces share in the surface at least the
//! corners they share in the input). On a 1.1M-face scan with 5 filled holes
//! this stage's time fell to a fifth (42.9 -> 7.8 s wall on the same loaded
//! machine; bench/RESULTS.md, "Repair"); the result is still checked whole.
std::vector<detail::RepairSurface::Face_index> faces_that_may_cross(const detail::RepairSurface& surface,
                                                                    const Mesh& plain, const Mesh& input) {
  using Face = detail::RepairSurface::Face_index;
  std::vector<Face> ids(surface.faces().begin(), surface.faces().end());  // plain's face order
  const std::vector<int> changed = detail::faces_not_in(plain, input);
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const Triangle*>;
  const auto box_of = [&](const Triangle& t) {
    CGAL::Bbox_3 b;
    for (int v : t) {
      const Vec3& p = plain.vertices[static_cast<std::size_t>(v)];
      b += CGAL::Bbox_3(p.x(), p.y(), p.z(), p.x(), p.y(), p.z());
    }
    return Box(b, &t);
  };
  std::vector<Box> all, moved;
  all.reserve(plain.num_faces());
  for (const Triangle& t : plain.faces) all.push_back(box_of(t));
  for (int f : changed) moved.push_back(all[static_cast<std::size_t>(f)]);
  std::vector<char> keep(plain.num_faces(), 0);
  for (int f : changed) keep[static_cast<std::size_t>(f)] = 1;
  const Triangle* first = plain.faces.data();
  CGAL::box_intersection_d(all.begin(), all.end(), moved.begin(), moved.end(), [&](const Box& a, const Box& b) {
    keep[static_cast<std::size_t>(a.handle() - first)] = 1;
    keep[static_cast<std::size_t>(b.handle() - first)] = 1;
  });
  std::vector<Face> out;
  for (std::size_t f = 0; f < ids.size(); ++f)
    if (keep[f]) out.push_back(ids[f]);
  return out;
}

void add_step(MeshRepairReport& report, MeshRepairStep step, Progress* progress) {
  if (progress && step.applied()) progress->info("repair " + step.name + ": " + step.message);
  report.steps.push_back(std::move(step));
}

}  // namespace

bool MeshRepairReport::changed() const {
  for (const auto& s : steps)
    if (s.applied()) return true;
  return false;
}

std::string MeshRepairReport::applied_steps() const {
  std::string out;
  for (const auto& s : steps)
    if (s.applied()) out += (out.empty() ? "" : ", ") + s.name;
  return out.empty() ? "none" : out;
}

MeshRepairResult repair_mesh(const Mesh& input, const MeshRepairOptions& options) {
  check_options(options);
  const auto start = std::chrono::steady_clock::now();
  Progress* progress = options.progress;
  MeshRepairResult result;
  MeshRepairReport& report = result.report;
  report.input_vertices = input.num_vertices();
  report.input_faces = input.num_faces();
  report.max_deviation_cap = options.max_deviation;
  if (input.faces.empty())
    throw InvalidMeshError("the mesh has no faces: there is nothing to repair; give a triangle mesh that bounds a "
                           "volume");

  // 0. What is wrong, with the same exact checks as `subfab info`.
  MeshReport problems;
  {
    StageScope stage(progress, "repair: check input");
    problems = analyze_mesh(input);
  }
  for (const auto& check : problems.checks)
    if (check.failed()) report.problems.push_back(check.name + ": " + check.message);
  for (const char* fatal : {"finite_coordinates", "face_indices"}) {
    const CheckResult* check = problems.find(fatal);
    if (check && check->failed())
      throw InvalidMeshError(check->message + " (repair cannot guess a vertex that is not there or has no position: "
                             "export the file again from its source)");
  }
  report.bbox_diagonal = bounding_box(input).diagonal();
  if (!(report.bbox_diagonal > 0))
    throw InvalidMeshError("every vertex is at the same point: the mesh encloses no volume and cannot be repaired");
  if (problems.all_passed()) {
    result.mesh = input;
    report.output_vertices = input.num_vertices();
    report.output_faces = input.num_faces();
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress->info("repair: nothing to do, the mesh passes every check");
    return result;
  }

  // 1-12. The steps (repair_mesh.h).
  detail::RepairSurface surface;
  {
    StageScope stage(progress, "repair: soup");
    detail::RepairSoup soup;
    soup.points.reserve(input.num_vertices());
    for (const Vec3& p : input.vertices) soup.points.emplace_back(p.x(), p.y(), p.z());
    soup.triangles.reserve(input.num_faces());
    for (const Triangle& t : input.faces)
      soup.triangles.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                                static_cast<std::size_t>(t[2])});
    const std::size_t first_step = report.steps.size();
    add_step(report, detail::merge_duplicate_vertices(soup), progress);
    add_step(report, detail::remove_repeated_corner_faces(soup), progress);
    add_step(report, detail::remove_duplicate_faces(soup), progress);
    if (soup.triangles.empty())
      throw InvalidMeshError("no face is left once faces with a repeated corner are removed: there is no surface to "
                             "repair");
    // The soup is still the input when steps 1-3 changed nothing: then the
    // input's checks say whether orienting has anything to do.
    bool soup_is_input = true;
    for (std::size_t i = first_step; i < report.steps.size(); ++i) soup_is_input = soup_is_input && !report.steps[i].applied();
    const auto passed = [&](const char* name) {
      const CheckResult* check = problems.find(name);
      return check && check->passed();
    };
    const detail::SoupState state =
        soup_is_input && passed("non_manifold_edges") && passed("non_manifold_vertices") && passed("consistent_orientation")
            ? detail::SoupState::ManifoldConsistent
            : detail::SoupState::Unknown;
    for (auto& step : detail::orient_soup(soup, surface, state)) add_step(report, std::move(step), progress);
  }
  {
    StageScope stage(progress, "repair: close");
    add_step(report, detail::stitch_borders(surface), progress);
    add_step(report, detail::remove_small_components(surface, options.min_component_fraction), progress);
    add_step(report, detail::remove_zero_area_faces(surface), progress);
    add_step(report, detail::fill_holes(surface), progress);
    add_step(report, detail::remove_flat_components(surface), progress);
    add_step(report, detail::separate_pinches(surface, options.pinch_separation * report.bbox_diagonal), progress);
  }
  {
    StageScope stage(progress, "repair: self-intersections");
    const CheckResult* input_crossings = problems.find("self_intersections");
    std::vector<detail::RepairSurface::Face_index> candidates;
    if (input_crossings && input_crossings->passed())
      candidates = faces_that_may_cross(surface, detail::to_plain_mesh(surface), input);
    add_step(report,
             detail::resolve_self_intersections(surface, options.max_self_intersection_rounds,
                                                input_crossings && input_crossings->passed() ? &candidates : nullptr),
             progress);
    add_step(report, detail::remove_zero_area_faces(surface), progress);
    // The resolution can pinch vertices again (two parts of the hull meeting at a point).
    auto again = detail::split_pinched_vertices(surface);
    if (again.applied()) {
      add_step(report, std::move(again), progress);
      add_step(report, detail::separate_pinches(surface, options.pinch_separation * report.bbox_diagonal), progress);
      add_step(report, detail::resolve_self_intersections(surface, options.max_self_intersection_rounds), progress);
    }
    add_step(report, detail::orient_outward(surface), progress);
  }
  result.mesh = detail::to_plain_mesh(surface);
  report.output_vertices = result.mesh.num_vertices();
  report.output_faces = result.mesh.num_faces();

  // The result must pass every check `subfab info` runs.
  {
    StageScope stage(progress, "repair: check result");
    const MeshReport after = analyze_mesh(result.mesh);
    for (const auto& check : after.checks)
      if (check.failed())
        throw InvalidMeshError("the repair could not make a valid solid (steps applied: " + report.applied_steps() +
                               "); the result still fails " + check.name + ": " + check.message);
  }

  // The deviation from the input, on the faces that differ.
  {
    StageScope stage(progress, "repair: deviation");
    report.hausdorff_error = options.hausdorff_error * report.bbox_diagonal;
    const detail::SurfaceDeviation d =
        measure_deviation(measurable(input), result.mesh,
                          options.max_deviation * report.bbox_diagonal + 2 * report.hausdorff_error,
                          report.hausdorff_error);
    report.max_deviation = d.hausdorff;
    report.mean_deviation = d.mean;
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report.max_deviation_fraction() > options.max_deviation) {
    std::ostringstream msg;
    msg << "the repair (" << report.applied_steps() << ") moves the surface by " << report.max_deviation << " ("
        << report.max_deviation_fraction() << " of the bounding-box diagonal), more than the cap "
        << options.max_deviation << "; raise --max-deviation if that is acceptable, or fix the mesh in a mesh editor";
    throw InvalidMeshError(msg.str());
  }
  return result;
}

}  // namespace subfab
