// SPDX-License-Identifier: GPL-3.0-or-later
//! \file refold_error.cpp
//! The refolding check of the nets (thesis Section 3.3.3): each net's root is
//! placed on its facet by a rigid motion, every other facet by rotating about
//! its fold edge by 180 deg minus the fold's dihedral angle; the error is the
//! largest distance of a refolded corner from its place on the model.
#include <Eigen/Geometry>
#include <algorithm>

#include "subfab/core/error.h"
#include "subfab/unfold/unfold_nets.h"
#include "unfold/facet_unit_normal.h"

namespace subfab {

using unfold_detail::facet_unit_normal;

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

double refold_error(const PolyMesh& mesh, const Unfolding& unfolding) {
  const int nf = static_cast<int>(mesh.facets.size());
  std::vector<Eigen::Affine3d> placed(nf, Eigen::Affine3d::Identity());
  std::vector<char> done(nf, 0);
  auto corner2d = [&](int f, int v) -> Vec2 {
    for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l)
      for (std::size_t i = 0; i < mesh.facets[f].loops[l].size(); ++i)
        if (mesh.facets[f].loops[l][i] == v) return unfolding.positions[f][l][i];
    throw AlgorithmError("fold vertex is not a corner of its facet");
  };
  double worst = 0;
  for (const Net& net : unfolding.nets) {
    // Root: rigid fit from its first two corners and its normal.
    const int r = net.root;
    const auto& loop = mesh.facets[r].loops[0];
    const Vec3 X0 = mesh.vertices[loop[0]], X1 = mesh.vertices[loop[1]];
    const Vec2 p0 = unfolding.positions[r][0][0], p1 = unfolding.positions[r][0][1];
    const Vec3 e1 = (X1 - X0).normalized();
    const Vec3 n = facet_unit_normal(mesh, r);
    const Vec3 e2 = n.cross(e1);
    const Vec2 a = (p1 - p0).normalized();
    Eigen::Matrix3d from, to;
    from << a.x(), -a.y(), 0, a.y(), a.x(), 0, 0, 0, 1;  // columns: a, a_perp, z
    to.col(0) = e1;
    to.col(1) = e2;
    to.col(2) = n;
    Eigen::Affine3d T = Eigen::Affine3d::Identity();
    T.linear() = to * from.transpose();
    T.translation() = X0 - T.linear() * Vec3(p0.x(), p0.y(), 0);
    placed[r] = T;
    done[r] = 1;
    for (int f : net.facets) {
      if (f == r) continue;
      const Fold& fold = unfolding.folds[unfolding.parent_fold[f]];
      const int p = fold.parent;
      if (!done[p]) throw AlgorithmError("net facets are not in tree order");
      const Vec2 q0 = corner2d(p, fold.v0), q1 = corner2d(p, fold.v1);
      const Vec3 o(q0.x(), q0.y(), 0);
      const Vec3 axis = Vec3(q1.x() - q0.x(), q1.y() - q0.y(), 0).normalized();
      const double angle = (180.0 - fold.dihedral_deg) * kPi / 180.0;
      Eigen::Affine3d rot = Eigen::Translation3d(o) * Eigen::AngleAxisd(angle, axis) * Eigen::Translation3d(-o);
      placed[f] = placed[p] * rot;
      done[f] = 1;
    }
    for (int f : net.facets)
      for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l)
        for (std::size_t i = 0; i < mesh.facets[f].loops[l].size(); ++i) {
          const Vec2& q = unfolding.positions[f][l][i];
          const Vec3 x = placed[f] * Vec3(q.x(), q.y(), 0);
          worst = std::max(worst, (x - mesh.vertices[mesh.facets[f].loops[l][i]]).norm());
        }
  }
  for (int f = 0; f < nf; ++f)
    if (!done[f]) throw AlgorithmError("facet " + std::to_string(f) + " is in no net");
  return worst;
}

}  // namespace subfab
