// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/match_frame_blocks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/rotate_accurately.h"
#include "subfab/core/parallel.h"
#include "subfab/geometry/rotate_into_frame.h"

namespace subfab {
namespace {

//! Max |exported vertex - back x frame vertex|, or why the frame block does not match.
struct BlockMatch {
  double offset = 0.0;
  double largest = 0.0;  // largest |coordinate| of either
  std::string refused;
};

BlockMatch match_block(const Mesh& exported, const Mesh& frame, const Eigen::Matrix3d& back, double max_offset) {
  BlockMatch r;
  if (frame.num_vertices() != exported.num_vertices() || frame.num_faces() != exported.num_faces()) {
    r.refused = "it has " + std::to_string(frame.num_vertices()) + " vertices and " +
                std::to_string(frame.num_faces()) + " faces, the exported block " +
                std::to_string(exported.num_vertices()) + " and " + std::to_string(exported.num_faces());
    return r;
  }
  if (frame.faces != exported.faces) {
    r.refused = "its faces are not the exported block's (same vertex ids expected)";
    return r;
  }
  std::size_t worst = 0;
  for (std::size_t v = 0; v < frame.num_vertices(); ++v) {
    const Vec3 turned = detail::rotate_accurately(back, frame.vertices[v]);
    const double d = (exported.vertices[v] - turned).norm();
    r.largest = std::max({r.largest, exported.vertices[v].cwiseAbs().maxCoeff(), turned.cwiseAbs().maxCoeff()});
    if (!(d <= r.offset)) {  // NaN counts as the worst
      r.offset = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
      worst = v;
    }
  }
  if (!(r.offset <= max_offset)) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "vertex %zu turned back lies %.3g from the exported vertex (at most %.3g allowed)",
                  worst, r.offset, max_offset);
    r.refused = buf;
  }
  return r;
}

//! The volume of the faces of `m` grown by delta (Steiner's formula per
//! triangle, summed), over the faces whose box grown by delta meets `near`
//! (all faces when null).
double grown_faces_volume(const Mesh& m, double delta, const BoundingBox* near) {
  constexpr double pi = 3.141592653589793;
  double sum = 0.0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const Triangle& t = m.faces[f];
    const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = m.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = m.vertices[static_cast<std::size_t>(t[2])];
    if (near) {
      const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - delta, hi = a.cwiseMax(b).cwiseMax(c).array() + delta;
      if ((hi.array() < near->min.array()).any() || (lo.array() > near->max.array()).any()) continue;
    }
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double perimeter = (b - a).norm() + (c - b).norm() + (a - c).norm();
    sum += 2 * delta * area + 0.5 * pi * delta * delta * perimeter + 4.0 / 3.0 * pi * delta * delta * delta;
  }
  return sum;
}

//! The offset every vertex lies within of R^T x its frame twin, with the
//! rounding of a boolean's output vertices (half an ulp of `largest`).
double frame_delta(const FrameMatch& match, double largest) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  return std::max(match.input_offset, match.block_offset) + match.computing_error + eps * largest;
}

//! stretch^3 x frame_volume + grown, rounded up: each sum of positive terms
//! is within (number of terms) x eps of its value, relative (1e-9 covers a
//! billion faces).
double transferred(double frame_volume, double grown, const FrameMatch& match) {
  const double s = match.stretch;
  return (s * s * s * std::max(frame_volume, 0.0) + grown) * (1.0 + 1e-9);
}

}  // namespace

double outside_volume_bound(double frame_volume, const Mesh& block, const Mesh& input, const FrameMatch& match) {
  const double largest = std::max({largest_coordinate(block), largest_coordinate(input), largest_coordinate(match.input)});
  const double delta = frame_delta(match, largest);
  const BoundingBox box = bounding_box(block);
  return transferred(frame_volume, grown_faces_volume(block, delta, nullptr) + grown_faces_volume(input, delta, &box),
                     match);
}

double overlap_volume_bound(double frame_volume, const Mesh& a, const Mesh& b, const FrameMatch& match) {
  const double largest = std::max({largest_coordinate(a), largest_coordinate(b), largest_coordinate(match.input)});
  const double delta = frame_delta(match, largest);
  const BoundingBox box_a = bounding_box(a), box_b = bounding_box(b);
  return transferred(frame_volume, grown_faces_volume(a, delta, &box_b) + grown_faces_volume(b, delta, &box_a), match);
}

std::size_t FrameMatch::num_refused() const {
  return static_cast<std::size_t>(
      std::count_if(refused.begin(), refused.end(), [](const std::string& s) { return !s.empty(); }));
}

FrameMatch match_frame_blocks(const Mesh& input, const std::vector<const Mesh*>& blocks,
                              const std::vector<const Mesh*>& frame_blocks, const Eigen::Matrix3d& rotation,
                              const FrameMatchOptions& options) {
  FrameMatch m;
  m.refused.assign(blocks.size(), std::string());
  const double orth = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!std::isfinite(orth) || orth > options.max_orthogonality_error || !(rotation.determinant() > 0.0)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "the recorded rotation is not a rotation (max |R^T R - I| = %.3g, det %.6g)",
                  orth, rotation.determinant());
    m.frame_error = buf;
    m.refused.assign(blocks.size(), m.frame_error);
    return m;
  }
  // |R^T x|^2 <= |R^T R|_2 |x|^2 (R and R^T have the same singular values) <= (1 + |R^T R - I|_2) |x|^2,
  // |.|_2 <= 3 x the max entry (computed within a few eps), and sqrt(1 + e) <= 1 + e / 2.
  constexpr double eps = std::numeric_limits<double>::epsilon();
  m.stretch = 1.0 + 1.5 * (orth + 8 * eps) + 8 * eps;
  const Eigen::Matrix3d back = rotation.transpose();
  m.input = rotate_into_frame(input, rotation, options.snap_tolerance);
  double largest = largest_coordinate(input);
  for (std::size_t v = 0; v < input.num_vertices(); ++v) {
    const Vec3 turned = detail::rotate_accurately(back, m.input.vertices[v]);
    m.input_offset = std::max(m.input_offset, (input.vertices[v] - turned).norm());
    largest = std::max(largest, turned.cwiseAbs().maxCoeff());
  }
  const double max_offset =
      options.max_vertex_offset * rounding_scale(input);
  std::vector<BlockMatch> r(blocks.size());
  parallel_for(0, blocks.size(), [&](std::size_t i) {
    if (i >= frame_blocks.size() || !frame_blocks[i]) {
      r[i].refused = "no frame block";
      return;
    }
    r[i] = match_block(*blocks[i], *frame_blocks[i], back, max_offset);
  });
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    m.refused[i] = std::move(r[i].refused);
    if (!m.refused[i].empty()) continue;
    m.block_offset = std::max(m.block_offset, r[i].offset);
    largest = std::max(largest, r[i].largest);
  }
  // Each offset: R^T f rounded once per coordinate (Dot2, <= 1 ulp), then a
  // difference and a norm (a few eps of the offset, itself <= the largest).
  m.computing_error = 8 * eps * largest;
  return m;
}

}  // namespace subfab
