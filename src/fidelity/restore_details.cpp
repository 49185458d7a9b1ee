// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/fidelity/restore_details.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "geometry/exact_normal_signs.h"
#include "subfab/checks/check_degenerate_faces.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/core/error.h"
#include "subfab/geometry/axis.h"

namespace subfab {
namespace {

// Offending faces fetched per exact check; more are found in the next round.
constexpr std::size_t kMaxOffendingFaces = 1u << 16;
// Rounds after which the vertices of a failing face go straight back to
// their smoothed positions (bounds the number of solves on hard inputs).
constexpr int kMaxGradualRounds = 24;
// Solved coordinates within this x diagonal of the original's are snapped to
// it (the least-squares solve returns the original up to rounding where
// nothing constrains it).
constexpr double kSnap = 1e-10;

using SparseMatrix = Eigen::SparseMatrix<double>;

void check_input(const Mesh& original, const Mesh& smoothed, const std::vector<HeightBox>& boxes,
                 const RestoreDetailsOptions& o) {
  if (original.faces != smoothed.faces || original.vertices.size() != smoothed.vertices.size())
    throw InvalidArgumentError("restore_details: the original and smoothed meshes must have the same faces and "
                               "vertex count (the smoothed mesh is the original with its vertices moved)");
  if (!(o.anchor_weight > 0) || !std::isfinite(o.anchor_weight))
    throw InvalidArgumentError("restore_details: the anchor weight must be a positive number");
  if (o.max_halvings < 0) throw InvalidArgumentError("restore_details: max_halvings must be >= 0");
  if (o.room && o.room->size() != boxes.size())
    throw InvalidArgumentError("restore_details: one room box per box expected");
  if (o.held)
    for (int v : *o.held)
      if (v < 0 || static_cast<std::size_t>(v) >= original.vertices.size())
        throw InvalidArgumentError("restore_details: held vertex " + std::to_string(v) + " is not a vertex");
}

//! The uniform Laplacian: (L v)_i = v_i - mean of the neighbours of i (a
//! vertex without neighbours: v_i).
SparseMatrix uniform_laplacian(const VertexNeighbours& nb) {
  const auto n = static_cast<Eigen::Index>(nb.start.size() - 1);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < static_cast<int>(n); ++i) {
    entries.emplace_back(i, i, 1.0);
    const double w = nb.count(i) == 0 ? 0.0 : -1.0 / static_cast<double>(nb.count(i));
    for (int k = nb.begin(i); k < nb.end(i); ++k) entries.emplace_back(i, nb.at(k), w);
  }
  SparseMatrix L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

//! Index of the first box holding p (closed), -1 if none.
int region_of(const Vec3& p, const std::vector<HeightBox>& boxes) {
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (boxes[i].box.contains(p)) return static_cast<int>(i);
  return -1;
}

Vec3 clamp_to_box(const Vec3& p, const Box3& b) { return p.cwiseMax(b.min).cwiseMin(b.max); }

//! Solves (4.6) for the vertices not held (held ones fixed at x), in place.
void solve_free(const SparseMatrix& L, const Eigen::MatrixX3d& delta, const std::vector<Vec3>& original,
                const std::vector<char>& held, double w, std::vector<Vec3>& x) {
  const std::size_t n = x.size();
  std::vector<Eigen::Index> column(n, -1);
  Eigen::Index nf = 0;
  for (std::size_t v = 0; v < n; ++v)
    if (!held[v]) column[v] = nf++;
  if (nf == 0) return;
  Eigen::MatrixX3d rhs_rows = delta;  // delta - L[:, held] x_held
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c = 0; c < L.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(L, c); it; ++it) {
      const auto j = static_cast<std::size_t>(it.col());
      if (column[j] >= 0)
        entries.emplace_back(it.row(), column[j], it.value());
      else
        rhs_rows.row(it.row()) -= it.value() * x[j].transpose();
    }
  SparseMatrix A(L.rows(), nf);
  A.setFromTriplets(entries.begin(), entries.end());
  SparseMatrix normal = SparseMatrix(A.transpose()) * A;
  Eigen::MatrixX3d rhs = A.transpose() * rhs_rows;
  for (std::size_t v = 0; v < n; ++v)
    if (column[v] >= 0) {
      normal.coeffRef(column[v], column[v]) += w * w;
      rhs.row(column[v]) += w * w * original[v].transpose();
    }
  Eigen::SimplicialLDLT<SparseMatrix> solver(normal);
  if (solver.info() != Eigen::Success)
    throw AlgorithmError("restore_details: the Laplacian system could not be factorised (internal error)");
  const Eigen::MatrixX3d solution = solver.solve(rhs);
  for (std::size_t v = 0; v < n; ++v)
    if (column[v] >= 0) x[v] = solution.row(column[v]).transpose();
}

}  // namespace

RestoreDetailsResult restore_details(const Mesh& original, const Mesh& smoothed, const std::vector<HeightBox>& boxes,
                                     const RestoreDetailsOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_input(original, smoothed, boxes, options);
  const std::size_t n = original.vertices.size();
  RestoreDetailsResult result;
  RestoreDetailsReport& report = result.report;
  const std::vector<Vec3>& s = smoothed.vertices;

  const std::vector<HeightBox>& room = options.room ? *options.room : boxes;
  // 1. regions
  result.region.resize(n);
  std::vector<char> held(n, 0);
  std::vector<Vec3> x = s;
  for (std::size_t v = 0; v < n; ++v) {
    result.region[v] = region_of(s[v], boxes);
    if (result.region[v] < 0) {
      held[v] = 1;
      ++report.num_outside_boxes;
    }
  }
  if (options.held)
    for (int v : *options.held) held[static_cast<std::size_t>(v)] = 1;

  // 2. directions of each face (bit = axis index)
  std::vector<std::uint8_t> directions(smoothed.faces.size(), 0);
  for (std::size_t f = 0; f < smoothed.faces.size(); ++f) {
    const Triangle& t = smoothed.faces[f];
    const auto sign = detail::exact_normal_signs(s[static_cast<std::size_t>(t[0])], s[static_cast<std::size_t>(t[1])],
                                                 s[static_cast<std::size_t>(t[2])]);
    for (int v : t) {
      const int r = result.region[static_cast<std::size_t>(v)];
      if (r < 0) continue;
      const Axis a = boxes[static_cast<std::size_t>(r)].axis;
      if (sign[static_cast<std::size_t>(axis_dimension(a))] * axis_sign(a) >= 0)
        directions[f] = static_cast<std::uint8_t>(directions[f] | (1u << axis_index(a)));
    }
  }

  // 3. active set
  const VertexNeighbours nb = vertex_neighbours(original);
  const SparseMatrix L = uniform_laplacian(nb);
  Eigen::MatrixX3d o(static_cast<Eigen::Index>(n), 3);
  for (std::size_t v = 0; v < n; ++v) o.row(static_cast<Eigen::Index>(v)) = original.vertices[v].transpose();
  const Eigen::MatrixX3d delta = L * o;
  std::vector<int> hits(n, 0);
  const double snap = kSnap * bounding_box(original).diagonal();
  Mesh mesh = original;
  CheckOptions check;
  check.max_examples = kMaxOffendingFaces;
  for (;;) {
    ++report.num_rounds;
    solve_free(L, delta, original.vertices, held, options.anchor_weight, x);
    // Coordinates the solve returned within rounding of the original's are
    // the original's (a face in an axis plane stays in it exactly).
    for (std::size_t v = 0; v < n; ++v)
      if (!held[v])
        for (int k = 0; k < 3; ++k)
          if (std::abs(x[v][k] - original.vertices[v][k]) <= snap) x[v][k] = original.vertices[v][k];
    bool changed = false;
    for (std::size_t v = 0; v < n; ++v) {
      if (held[v]) continue;
      const Vec3 c = clamp_to_box(x[v], room[static_cast<std::size_t>(result.region[v])].box);
      if (c != x[v]) {
        x[v] = c;
        held[v] = 1;
        changed = true;
        ++report.num_held_on_box;
      }
    }
    mesh.vertices = x;
    std::vector<int> bad;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const Triangle& t = mesh.faces[f];
      const auto sign = detail::exact_normal_signs(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                                                   x[static_cast<std::size_t>(t[2])]);
      for (Axis a : kAllAxes)
        if ((directions[f] >> axis_index(a)) & 1u)
          if (sign[static_cast<std::size_t>(axis_dimension(a))] * axis_sign(a) < 0) {
            bad.push_back(static_cast<int>(f));
            break;
          }
    }
    report.num_face_failures += static_cast<int>(bad.size());
    const std::size_t num_direction_failures = bad.size();
    for (const CheckResult& c : {check_degenerate_faces(mesh, check), check_self_intersections(mesh, check)})
      bad.insert(bad.end(), c.examples.begin(), c.examples.end());
    report.num_solid_failures += static_cast<int>(bad.size() - num_direction_failures);
    if (bad.empty() && !changed) break;
    // The vertices of the failing faces go (halfway) back.
    std::vector<int> back;
    for (int f : bad)
      for (int v : mesh.faces[static_cast<std::size_t>(f)]) back.push_back(v);
    std::sort(back.begin(), back.end());
    back.erase(std::unique(back.begin(), back.end()), back.end());
    bool moved = false;
    for (int vi : back) {
      const auto v = static_cast<std::size_t>(vi);
      if (x[v] == s[v]) continue;
      ++hits[v];
      if (!held[v]) ++report.num_held_back;
      held[v] = 1;
      const bool halfway = hits[v] <= options.max_halvings && report.num_rounds < kMaxGradualRounds;
      x[v] = halfway ? Vec3(s[v] + 0.5 * (x[v] - s[v])) : s[v];
      moved = true;
    }
    if (!bad.empty() && !moved)  // every failing face is a face of the smoothed mesh, which passes the checks
      throw AlgorithmError("restore_details: " + std::to_string(bad.size()) +
                           " faces fail at their smoothed positions: the smoothed mesh is not a valid solid facing "
                           "its blocks' directions (internal error; please report it with the input)");
  }

  // Report.
  const double tiny = 1e-9 * bounding_box(original).diagonal();
  for (std::size_t v = 0; v < n; ++v) {
    const double ds = (s[v] - original.vertices[v]).norm(), dr = (x[v] - original.vertices[v]).norm();
    report.max_displacement_smoothed = std::max(report.max_displacement_smoothed, ds);
    report.max_displacement = std::max(report.max_displacement, dr);
    report.mean_displacement_smoothed += ds;
    report.mean_displacement += dr;
    if (x[v] == s[v]) ++report.num_at_smoothed;
    if (dr <= tiny) ++report.num_restored;
  }
  if (n > 0) {
    report.mean_displacement_smoothed /= static_cast<double>(n);
    report.mean_displacement /= static_cast<double>(n);
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.progress) {
    std::ostringstream msg;
    msg << "restored details: " << report.num_restored << " of " << n << " vertices back at their original position, "
        << report.num_at_smoothed << " at the smoothed one, " << report.num_held_on_box << " held on their box, "
        << report.num_held_back << " held back by " << report.num_face_failures << " face(s) turning away and "
        << report.num_solid_failures << " invalid face(s); vertex distance to the original: max "
        << report.max_displacement << " (smoothed " << report.max_displacement_smoothed << "), mean "
        << report.mean_displacement << " (smoothed " << report.mean_displacement_smoothed << "); "
        << report.num_rounds << " solves, " << report.seconds << " s";
    options.progress->info(msg.str());
  }
  result.mesh = std::move(mesh);
  return result;
}

}  // namespace subfab
