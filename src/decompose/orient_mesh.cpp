// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/orient_mesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <vector>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using Matrix3Xd = Eigen::Matrix<double, 3, Eigen::Dynamic>;

//! Area-weighted normals (A_f n_f = half the cross product), one column per face.
Matrix3Xd weighted_normals(const Mesh& mesh) {
  Matrix3Xd w(3, static_cast<Eigen::Index>(mesh.num_faces()));
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) w.col(static_cast<Eigen::Index>(f)) = 0.5 * face_normal_scaled(mesh, f);
  return w;
}

//! Sum of ||R w||_1 over the columns.
double l1_sum(const Matrix3Xd& w, const Eigen::Matrix3d& r) { return (r * w).cwiseAbs().sum(); }

//! Normals binned on a cube map (bins x bins per face), summed per bin, in
//! face order (deterministic). Empty bins are dropped.
Matrix3Xd cluster_normals(const Matrix3Xd& w, int bins) {
  std::vector<Eigen::Vector3d> sums(static_cast<std::size_t>(6 * bins * bins), Eigen::Vector3d::Zero());
  for (Eigen::Index f = 0; f < w.cols(); ++f) {
    const Eigen::Vector3d n = w.col(f);
    Eigen::Index m;
    const double len = n.cwiseAbs().maxCoeff(&m);
    if (!(len > 0)) continue;
    const int face = 2 * static_cast<int>(m) + (n[m] < 0 ? 1 : 0);
    const auto cell = [&](int c) {
      const double t = (n[(m + c) % 3] / len + 1) * 0.5 * bins;
      return std::clamp(static_cast<int>(std::floor(t)), 0, bins - 1);
    };
    sums[static_cast<std::size_t>((face * bins + cell(1)) * bins + cell(2))] += n;
  }
  std::vector<Eigen::Vector3d> kept;
  for (const auto& s : sums)
    if (s.squaredNorm() > 0) kept.push_back(s);
  Matrix3Xd out(3, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i) out.col(static_cast<Eigen::Index>(i)) = kept[i];
  return out;
}

//! The 24 proper rotations mapping the coordinate axes to themselves.
std::vector<Eigen::Matrix3d> cube_rotations() {
  std::vector<Eigen::Matrix3d> out;
  std::array<int, 3> perm{0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
      for (int r = 0; r < 3; ++r) p(r, perm[static_cast<std::size_t>(r)]) = (signs >> r) & 1 ? -1.0 : 1.0;
      if (p.determinant() > 0) out.push_back(p);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

//! The symmetric equivalent P R closest to the identity (largest trace); the
//! first such P in a fixed order on ties.
Eigen::Matrix3d closest_to_identity(const Eigen::Matrix3d& r, const std::vector<Eigen::Matrix3d>& symmetries) {
  Eigen::Matrix3d best = r;
  double best_trace = -INFINITY;
  for (const auto& p : symmetries) {
    const Eigen::Matrix3d q = p * r;
    if (q.trace() > best_trace + 1e-12) {
      best_trace = q.trace();
      best = q;
    }
  }
  return best;
}

//! Cosine-like similarity of two frames modulo the cube rotations: max over P
//! of trace(P R1 R2^T) (3 when equal up to symmetry).
double symmetric_similarity(const Eigen::Matrix3d& r1, const Eigen::Matrix3d& r2,
                            const std::vector<Eigen::Matrix3d>& symmetries) {
  const Eigen::Matrix3d m = r1 * r2.transpose();
  double best = -INFINITY;
  for (const auto& p : symmetries) best = std::max(best, (p * m).trace());
  return best;
}

//! Rotation whose third row is z (unit) and whose first row is the basis
//! vector e1 of z's orthogonal plane turned by `twist`.
Eigen::Matrix3d frame_from_axis(const Eigen::Vector3d& z, double twist) {
  const Eigen::Vector3d ref = std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = ref.cross(z).normalized();
  const Eigen::Vector3d e2 = z.cross(e1);
  const Eigen::Vector3d x = std::cos(twist) * e1 + std::sin(twist) * e2;
  Eigen::Matrix3d r;
  r.row(0) = x.transpose();
  r.row(1) = z.cross(x).transpose();
  r.row(2) = z.transpose();
  return r;
}

Eigen::Matrix3d exp_rotation(const Eigen::Vector3d& omega) {
  const double angle = omega.norm();
  if (angle == 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
}

//! Nelder-Mead on E(exp(omega) * r0) over omega in R^3, from a regular
//! simplex of size `step`; stops when the simplex is smaller than tolerance
//! or after max_evals evaluations. Returns the best rotation and its energy sum.
template <typename Energy>
std::pair<Eigen::Matrix3d, double> nelder_mead(const Energy& energy_of, const Eigen::Matrix3d& r0, double step,
                                               double tolerance, int max_evals) {
  const auto energy = [&](const Eigen::Vector3d& omega) { return energy_of(exp_rotation(omega) * r0, omega.norm()); };
  std::array<Eigen::Vector3d, 4> x;
  std::array<double, 4> e;
  x[0] = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) x[static_cast<std::size_t>(i + 1)] = step * Eigen::Vector3d::Unit(i);
  for (std::size_t i = 0; i < 4; ++i) e[i] = energy(x[i]);
  int evals = 4;
  std::array<std::size_t, 4> order{0, 1, 2, 3};
  while (evals < max_evals) {
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return e[a] < e[b] || (e[a] == e[b] && a < b); });
    const std::size_t best = order[0], worst = order[3], second_worst = order[2];
    double size = 0;
    for (std::size_t i = 1; i < 4; ++i) size = std::max(size, (x[order[i]] - x[best]).norm());
    if (size < tolerance) break;
    const Eigen::Vector3d centroid = (x[order[0]] + x[order[1]] + x[order[2]]) / 3.0;
    const Eigen::Vector3d reflected = centroid + (centroid - x[worst]);
    const double er = energy(reflected);
    ++evals;
    if (er < e[best]) {
      const Eigen::Vector3d expanded = centroid + 2.0 * (centroid - x[worst]);
      const double ee = energy(expanded);
      ++evals;
      if (ee < er) {
        x[worst] = expanded;
        e[worst] = ee;
      } else {
        x[worst] = reflected;
        e[worst] = er;
      }
      continue;
    }
    if (er < e[second_worst]) {
      x[worst] = reflected;
      e[worst] = er;
      continue;
    }
    const bool outside = er < e[worst];
    const Eigen::Vector3d contracted =
        outside ? Eigen::Vector3d(centroid + 0.5 * (reflected - centroid)) : Eigen::Vector3d(centroid + 0.5 * (x[worst] - centroid));
    const double ec = energy(contracted);
    ++evals;
    if (ec < std::min(er, e[worst])) {
      x[worst] = contracted;
      e[worst] = ec;
      continue;
    }
    for (std::size_t i = 0; i < 4; ++i) {  // shrink towards the best
      if (i == best) continue;
      x[i] = x[best] + 0.5 * (x[i] - x[best]);
      e[i] = energy(x[i]);
      ++evals;
    }
  }
  const std::size_t best = static_cast<std::size_t>(std::min_element(e.begin(), e.end()) - e.begin());
  return {exp_rotation(x[best]) * r0, e[best]};
}

//! sum_f ||R w_f||_1 for rotations R = exp(omega) r0 near r0, fast: a face
//! whose rotated unit normal has every component of magnitude > radius at r0
//! keeps its component signs for |omega| <= radius (a turn by angle t moves a
//! unit vector by at most t), so those faces add up to a linear function of R;
//! only the others are summed explicitly. Beyond the radius, the full sum.
class LocalEnergy {
 public:
  LocalEnergy(const Matrix3Xd& w, const Eigen::Matrix3d& r0, double radius) : w_(w), radius_(radius) {
    linear_.setZero();
    std::vector<Eigen::Index> near;
    const Matrix3Xd rotated = r0 * w;
    for (Eigen::Index f = 0; f < w.cols(); ++f) {
      const Eigen::Vector3d v = rotated.col(f);
      const double len = v.norm();
      if (v.cwiseAbs().minCoeff() > (radius * (1 + 1e-9) + 1e-12) * len) {
        for (int i = 0; i < 3; ++i) linear_.col(i) += (v[i] > 0 ? 1.0 : -1.0) * w.col(f);
      } else {
        near.push_back(f);
      }
    }
    near_.resize(3, static_cast<Eigen::Index>(near.size()));
    for (std::size_t i = 0; i < near.size(); ++i) near_.col(static_cast<Eigen::Index>(i)) = w.col(near[i]);
  }
  //! Energy sum of r = exp(omega) r0, given |omega|.
  double operator()(const Eigen::Matrix3d& r, double omega_norm) const {
    if (omega_norm > radius_) return l1_sum(w_, r);
    double e = l1_sum(near_, r);
    for (int i = 0; i < 3; ++i) e += r.row(i).dot(linear_.col(i));
    return e;
  }

 private:
  const Matrix3Xd& w_;
  double radius_;
  Eigen::Matrix3d linear_;  // column i: sum over far faces of sign_i * w_f
  Matrix3Xd near_;
};

//! Re-orthonormalised proper rotation.
Eigen::Matrix3d orthonormalize(const Eigen::Matrix3d& r) {
  return Eigen::Quaterniond(r).normalized().toRotationMatrix();
}

//! The frame a CAD part was drawn in, from its largest flat faces: z along
//! the normal direction holding the most area, x along the one holding the
//! most area among those perpendicular to it (within `angle` radians;
//! directions grouped within `angle`, +n and -n together). None when no
//! direction perpendicular to the first holds any area (a part with one flat
//! face, or none). canonical = rotation x input.
std::optional<Eigen::Matrix3d> design_frame(const Matrix3Xd& w, double angle) {
  struct Direction {
    Eigen::Vector3d u;    // its largest face's unit normal (the group is every normal within `angle` of +-u)
    Eigen::Vector3d sum;  // area-weighted unit normals, flipped onto u
    double area = 0;
  };
  std::vector<Direction> directions;
  std::vector<Eigen::Index> order(static_cast<std::size_t>(w.cols()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](Eigen::Index a, Eigen::Index b) { return w.col(a).norm() > w.col(b).norm(); });
  const double same = std::cos(angle);
  constexpr std::size_t kMaxDirections = 64;  // the largest faces' directions; a CAD part has few
  for (Eigen::Index f : order) {
    const double a = w.col(f).norm();
    if (!(a > 0)) break;
    const Eigen::Vector3d n = w.col(f) / a;
    bool found = false;
    for (Direction& d : directions) {
      const double c = n.dot(d.u);
      if (std::abs(c) >= same) {
        d.sum += (c > 0 ? a : -a) * n;
        d.area += a;
        found = true;
        break;
      }
    }
    if (!found && directions.size() < kMaxDirections) directions.push_back({n, a * n, a});
  }
  if (directions.size() < 2) return std::nullopt;
  const auto largest = [&](auto&& keep) {
    const Direction* best = nullptr;
    for (const Direction& d : directions)
      if (keep(d) && (!best || d.area > best->area)) best = &d;
    return best;
  };
  const Direction* first = largest([](const Direction&) { return true; });
  const Eigen::Vector3d z = first->sum.normalized();
  const Direction* second =
      largest([&](const Direction& d) { return &d != first && std::abs(d.sum.normalized().dot(z)) <= std::sin(angle); });
  if (!second) return std::nullopt;
  const Eigen::Vector3d x = (second->sum - second->sum.dot(z) * z).normalized();
  Eigen::Matrix3d r;
  r.row(0) = x.transpose();
  r.row(1) = z.cross(x).transpose();
  r.row(2) = z.transpose();
  return r;
}

//! Area of the faces whose normal (a column of `w`) lies exactly on an axis:
//! two of its components are zero.
double aligned_area(const Matrix3Xd& w) {
  double aligned = 0;
  for (Eigen::Index f = 0; f < w.cols(); ++f) {
    const Eigen::Vector3d n = w.col(f);
    if ((n.array() == 0).count() >= 2) aligned += n.norm();
  }
  return aligned;
}

}  // namespace

double axis_aligned_area_fraction(const Mesh& mesh) {
  const Matrix3Xd w = weighted_normals(mesh);
  const double total = w.colwise().norm().sum();
  return total > 0 ? aligned_area(w) / total : 0.0;
}

double orientation_energy(const Mesh& mesh, const Eigen::Matrix3d& rotation) {
  const Matrix3Xd w = weighted_normals(mesh);
  const double area = w.colwise().norm().sum();
  if (!(area > 0)) throw InvalidMeshError("cannot orient a mesh with zero surface area");
  return l1_sum(w, rotation) / area;
}

OrientResult orient_mesh(const Mesh& mesh, const OrientOptions& options) {
  if (options.num_directions < 1 || options.num_twists < 1 || options.num_refined < 0 || !(options.tolerance > 0) ||
      !(options.keep_frame_area >= 0) || !(options.snap_tolerance >= 0) || !(options.precision_snap_tolerance >= 0) || !(options.design_frame_angle >= 0) || !(options.keep_frame_tolerance >= 0) || !(options.min_relative_gain >= 0) ||
      options.num_candidates < 1)
    throw InvalidArgumentError(
        "orientation options: num_directions and num_twists must be >= 1, num_refined >= 0, tolerance > 0, "
        "keep_frame_area, keep_frame_tolerance and min_relative_gain >= 0, num_candidates >= 1");
  if (mesh.empty()) throw InvalidMeshError("cannot orient a mesh with no faces");
  const Matrix3Xd w = weighted_normals(mesh);
  const double area = w.colwise().norm().sum();
  if (!(area > 0)) throw InvalidMeshError("cannot orient a mesh with zero surface area");
  const std::vector<Eigen::Matrix3d> symmetries = cube_rotations();

  // 2. Coarse search on clustered normals over the fundamental region.
  const Matrix3Xd clustered = cluster_normals(w, 12);
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Eigen::Vector3d> axes;
  for (int i = 0; i < options.num_directions; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / options.num_directions;
    if (z < 1.0 / std::sqrt(3.0) - 0.03) break;  // z decreases with i
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    axes.emplace_back(r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z);
  }
  const std::size_t num_twists = static_cast<std::size_t>(options.num_twists);
  const std::size_t num_candidates = axes.size() * num_twists;
  const auto coarse_frame = [&](std::size_t c) {
    const double twist = 0.5 * M_PI * static_cast<double>(c % num_twists) / static_cast<double>(num_twists);
    return frame_from_axis(axes[c / num_twists], twist);
  };
  std::vector<double> coarse(num_candidates);
  parallel_for(
      0, num_candidates, [&](std::size_t c) { coarse[c] = l1_sum(clustered, coarse_frame(c)); }, 64);
  std::vector<std::size_t> ranked(num_candidates);
  std::iota(ranked.begin(), ranked.end(), 0);
  std::stable_sort(ranked.begin(), ranked.end(), [&](std::size_t a, std::size_t b) { return coarse[a] < coarse[b]; });
  // Best distinct candidates (more than ~6 degrees apart modulo symmetry), plus the identity.
  std::vector<Eigen::Matrix3d> starts{Eigen::Matrix3d::Identity()};
  const double min_similarity = 1.0 + 2.0 * std::cos(6.0 * M_PI / 180.0);
  for (std::size_t c : ranked) {
    if (static_cast<int>(starts.size()) > options.num_refined) break;
    const Eigen::Matrix3d r = coarse_frame(c);
    bool distinct = true;
    for (const auto& s : starts) distinct = distinct && symmetric_similarity(r, s, symmetries) < min_similarity;
    if (distinct) starts.push_back(r);
  }

  // 3. Local refinement: every start on the clustered normals (cheap), then
  //    the best few on the exact energy, with restarts at smaller steps.
  std::vector<Eigen::Matrix3d> rough(starts.size());
  std::vector<double> rough_energy(starts.size());
  parallel_for(0, starts.size(), [&](std::size_t s) {
    Eigen::Matrix3d r = starts[s];
    const auto energy = [&](const Eigen::Matrix3d& q, double) { return l1_sum(clustered, q); };
    for (double step : {0.04, 4e-3}) r = orthonormalize(nelder_mead(energy, r, step, 1e-5, 200).first);
    rough[s] = r;
    rough_energy[s] = l1_sum(w, r);
  });
  std::vector<std::size_t> order(starts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rough_energy[a] < rough_energy[b]; });
  order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(options.num_candidates)));
  std::vector<Eigen::Matrix3d> refined(order.size());
  std::vector<double> energies(order.size());
  parallel_for(0, order.size(), [&](std::size_t s) {
    Eigen::Matrix3d r = rough[order[s]];
    double e = rough_energy[order[s]];
    for (double step : {0.02, 1e-3, 3e-5, 1e-6}) {
      const LocalEnergy energy(w, r, 6 * step);
      auto [r2, e2] = nelder_mead(energy, r, step, options.tolerance, 300);
      if (e2 < e) {
        r = orthonormalize(r2);
        e = l1_sum(w, r);
      }
    }
    refined[s] = orthonormalize(closest_to_identity(r, symmetries));
    energies[s] = l1_sum(w, refined[s]);
  });

  // 4. Candidates: the input frame and the distinct local optima (several
  //    starts may converge to the same frame), in preference order.
  const double energy_identity = l1_sum(w, Eigen::Matrix3d::Identity());
  double best_energy = energy_identity;
  for (double e : energies) best_energy = std::min(best_energy, e);
  // The area whose normals are exactly on an axis in the input frame.
  const bool axis_aligned_input = aligned_area(w) >= options.keep_frame_area * area &&
                                  energy_identity <= best_energy * (1 + options.keep_frame_tolerance);
  struct Ranked {
    OrientCandidate candidate;
    double key;  // preference: smaller first
  };
  std::vector<Ranked> ranked_candidates;
  {
    OrientCandidate input;
    input.input_frame = true;
    input.energy = energy_identity / area;
    const double key = axis_aligned_input ? -INFINITY : energy_identity / (1 + std::max(1e-9, options.min_relative_gain));
    ranked_candidates.push_back({input, key});
  }
  std::vector<std::size_t> by_energy(refined.size());
  std::iota(by_energy.begin(), by_energy.end(), 0);
  std::stable_sort(by_energy.begin(), by_energy.end(), [&](std::size_t a, std::size_t b) { return energies[a] < energies[b]; });
  // Starts converging to the same optimum stop at slightly different places
  // (E is flat along some directions): frames within half a degree modulo
  // symmetry are one candidate, the lower-energy one kept.
  const double same_frame = 1.0 + 2.0 * std::cos(0.5 * M_PI / 180.0);
  for (std::size_t s : by_energy) {
    if (refined[s].isIdentity(0.0)) continue;  // the input frame is already a candidate
    bool distinct = true;
    for (std::size_t k = 1; k < ranked_candidates.size(); ++k)
      distinct = distinct && symmetric_similarity(refined[s], ranked_candidates[k].candidate.rotation, symmetries) < same_frame;
    if (!distinct) continue;
    OrientCandidate c;
    c.rotation = refined[s];
    c.energy = energies[s] / area;
    ranked_candidates.push_back({c, energies[s]});
  }
  // The frame the part was drawn in, from its largest flat faces (a CAD part
  // exported at an angle): ahead of everything, like an input modelled in its
  // axes, when keep_frame_area of the area then lies exactly on the axes (with
  // the precision snap, as the check below takes it) and its energy is within
  // keep_frame_tolerance of the best; else ranked by energy. Its energy is
  // not refined (a refinement would turn the flat faces off the axes).
  if (options.design_frame_angle > 0) {
    if (const auto drawn = design_frame(w, options.design_frame_angle)) {
      const Eigen::Matrix3d r = orthonormalize(closest_to_identity(*drawn, symmetries));
      bool distinct = !r.isIdentity(1e-12);
      for (std::size_t k = 0; k < ranked_candidates.size() && distinct; ++k)
        distinct = ranked_candidates[k].candidate.input_frame
                       ? symmetric_similarity(r, Eigen::Matrix3d::Identity(), symmetries) < same_frame
                       : symmetric_similarity(r, ranked_candidates[k].candidate.rotation, symmetries) < same_frame;
      if (distinct) {
        OrientCandidate c;
        c.rotation = r;
        c.energy = l1_sum(w, r) / area;
        c.design_frame = true;
        const double snap = std::max(options.snap_tolerance, options.precision_snap_tolerance);
        const bool drawn_in_axes = axis_aligned_area_fraction(rotate_into_frame(mesh, r, snap)) >= options.keep_frame_area &&
                                   c.energy * area <= best_energy * (1 + options.keep_frame_tolerance);
        ranked_candidates.push_back({c, drawn_in_axes ? -INFINITY : c.energy * area});
      }
    }
  }
  std::stable_sort(ranked_candidates.begin(), ranked_candidates.end(),
                   [](const Ranked& a, const Ranked& b) { return a.key < b.key; });

  // 5. The first candidate without infeasible features; else the fewest.
  OrientResult result;
  result.energy_before = energy_identity / area;
  for (const Ranked& r : ranked_candidates) result.candidates.push_back(r.candidate);
  std::vector<FeasibilityResult> checks(result.candidates.size());
  if (options.check_feasibility) {
    std::optional<std::size_t> feasible;
    for (std::size_t c = 0; c < result.candidates.size() && !feasible; ++c) {
      const Mesh turned = result.candidates[c].input_frame
                              ? mesh
                              : rotate_into_frame(mesh, result.candidates[c].rotation, options.snap_tolerance);
      checks[c] = find_infeasible_features(turned);
      result.candidates[c].snap_tolerance = options.snap_tolerance;
      if (!checks[c].feasible() && !result.candidates[c].input_frame &&
          options.precision_snap_tolerance > options.snap_tolerance) {
        // Infeasible only through the file's rounding? (flat faces tilted by it)
        FeasibilityResult snapped = find_infeasible_features(
            rotate_into_frame(mesh, result.candidates[c].rotation, options.precision_snap_tolerance));
        if (snapped.feasible()) {
          checks[c] = std::move(snapped);
          result.candidates[c].snap_tolerance = options.precision_snap_tolerance;
        }
      }
      result.candidates[c].num_infeasible = static_cast<long>(checks[c].size());
      if (checks[c].feasible()) feasible = c;
    }
    if (!feasible && options.feasibility_budget > 0) {
      // 6. Search the coarse frames, best coarse energy first, for a feasible one.
      const auto is_feasible = [&](const Eigen::Matrix3d& r) {
        return find_infeasible_features(rotate_into_frame(mesh, r, options.snap_tolerance)).feasible();
      };
      const double per_frame = std::max(1.0, static_cast<double>(mesh.num_faces()));
      const std::size_t max_frames =
          std::min(ranked.size(), static_cast<std::size_t>(options.feasibility_budget / per_frame));
      constexpr std::size_t batch = 16;
      std::optional<Eigen::Matrix3d> found;
      for (std::size_t b = 0; b < max_frames && !found; b += batch) {
        const std::size_t e = std::min(max_frames, b + batch);
        std::vector<Eigen::Matrix3d> frames(e - b);
        std::vector<char> ok(e - b, 0);
        parallel_for(
            b, e,
            [&](std::size_t i) {
              frames[i - b] = orthonormalize(closest_to_identity(coarse_frame(ranked[i]), symmetries));
              ok[i - b] = is_feasible(frames[i - b]) ? 1 : 0;
            },
            1);
        result.num_searched = e;
        for (std::size_t i = 0; i < ok.size() && !found; ++i)
          if (ok[i]) found = frames[i];
      }
      if (found) {
        // Local refinement on the exact energy; infeasible frames are walls.
        Eigen::Matrix3d r = *found;
        double e = l1_sum(w, r);
        const int evals = static_cast<int>(std::min<double>(options.feasibility_refine_evals,
                                                            0.25 * options.feasibility_budget / per_frame));
        if (evals >= 8) {
          const auto energy = [&](const Eigen::Matrix3d& q, double) {
            const Eigen::Matrix3d o = orthonormalize(q);
            return is_feasible(o) ? l1_sum(w, o) : INFINITY;
          };
          for (double step : {0.02, 1e-3}) {
            const auto [r2, e2] = nelder_mead(energy, r, step, 1e-7, evals / 2);
            const Eigen::Matrix3d o = orthonormalize(r2);
            if (e2 < e && is_feasible(o)) {
              r = o;
              e = l1_sum(w, r);
            }
          }
        }
        OrientCandidate c;
        c.rotation = r;
        c.energy = e / area;
        c.num_infeasible = 0;
        c.snap_tolerance = options.snap_tolerance;
        result.candidates.push_back(c);
        checks.emplace_back();
        feasible = result.candidates.size() - 1;
        result.found_by_search = true;
      }
    }
    if (feasible) {
      result.chosen = *feasible;
      result.num_rejected = *feasible;
    } else {
      for (std::size_t c = 1; c < result.candidates.size(); ++c)
        if (checks[c].size() < checks[result.chosen].size()) result.chosen = c;
      result.num_rejected = result.candidates.size();
    }
    result.infeasible = std::move(checks[result.chosen]);
  }
  const OrientCandidate& chosen = result.candidates[result.chosen];
  result.rotation = chosen.input_frame ? Eigen::Matrix3d::Identity() : chosen.rotation;
  result.energy_after = chosen.energy;
  result.snap_tolerance = chosen.snap_tolerance > 0 ? chosen.snap_tolerance : options.snap_tolerance;
  if (options.progress) {
    std::ostringstream msg;
    msg << "orientation energy " << result.energy_before << " -> " << result.energy_after << " ("
        << (chosen.input_frame ? "input frame" : "turned") << "; " << num_candidates << " coarse candidates, "
        << starts.size() << " refined, " << result.candidates.size() << " candidate frames";
    if (options.check_feasibility) {
      msg << ", " << result.num_rejected << " rejected for creases or corners no axis-aligned block can cover";
      if (result.num_searched > 0)
        msg << "; " << result.num_searched << " coarse frames searched for a feasible one, "
            << (result.found_by_search ? "found" : "none found");
      if (!result.infeasible.feasible()) msg << "; none is free of them, the fewest kept";
      if (result.snap_tolerance > options.snap_tolerance && !chosen.input_frame)
        msg << "; feasible once coordinates within the file's own rounding are snapped ("
            << result.snap_tolerance << " x diagonal)";
    }
    msg << ")";
    options.progress->info(msg.str());
  }
  return result;
}

}  // namespace subfab
