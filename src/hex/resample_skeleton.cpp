// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/resample_skeleton.h"

#include <algorithm>
#include <vector>

namespace subfab {
namespace {

//! An arc as a polyline with cumulative arc length, normalised to [0, 1].
struct Polyline {
  std::vector<Vec3> points;
  std::vector<double> radii;
  std::vector<double> t;  // normalised arc length of each point

  void at(double s, Vec3& p, double& r) const {
    const auto it = std::upper_bound(t.begin(), t.end(), s);
    std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - t.begin()));
    i = std::min(i, t.size() - 1);
    const double span = t[i] - t[i - 1];
    const double w = span > 0 ? std::clamp((s - t[i - 1]) / span, 0.0, 1.0) : 0.0;
    p = (1 - w) * points[i - 1] + w * points[i];
    r = (1 - w) * radii[i - 1] + w * radii[i];
  }
};

bool spheres_apart(const Polyline& line, double a, double b) {
  Vec3 pa, pm, pb;
  double ra, rm, rb;
  line.at(a, pa, ra);
  line.at(0.5 * (a + b), pm, rm);
  line.at(b, pb, rb);
  return (pa - pm).norm() > ra + rm || (pm - pb).norm() > rm + rb;
}

//! A neck between the samples: a node of the polyline strictly inside
//! (a, b) whose radius is under kNeck x the smaller end radius.
bool neck_inside(const Polyline& line, double a, double b, double neck) {
  if (!(neck > 0)) return false;
  Vec3 p;
  double ra, rb;
  line.at(a, p, ra);
  line.at(b, p, rb);
  const double limit = neck * std::min(ra, rb);
  for (std::size_t i = 0; i < line.t.size(); ++i)
    if (line.t[i] > a && line.t[i] < b && line.radii[i] < limit) return true;
  return false;
}

//! A bend between the samples: a node of the polyline strictly inside
//! (a, b) farther than bend x min(r_a, r_b) from the chord joining the
//! samples (the straight tube between them would cut the bend's inside).
bool bend_inside(const Polyline& line, double a, double b, double bend) {
  if (!(bend > 0)) return false;
  Vec3 pa, pb;
  double ra, rb;
  line.at(a, pa, ra);
  line.at(b, pb, rb);
  const double limit = bend * std::min(ra, rb);
  const Vec3 ab = pb - pa;
  const double len2 = ab.squaredNorm();
  for (std::size_t i = 0; i < line.t.size(); ++i) {
    if (!(line.t[i] > a && line.t[i] < b)) continue;
    const Vec3 ap = line.points[i] - pa;
    const double s = len2 > 0 ? std::clamp(ap.dot(ab) / len2, 0.0, 1.0) : 0.0;
    if ((ap - s * ab).norm() > limit) return true;
  }
  return false;
}

struct SplitCriteria {
  double neck = 0;
  double bend = 0;
};

void split(const Polyline& line, double a, double b, int depth, bool force, const SplitCriteria& c,
           std::vector<double>& out) {
  if (depth <= 0 || (!force && !spheres_apart(line, a, b) && !neck_inside(line, a, b, c.neck) &&
                     !bend_inside(line, a, b, c.bend)))
    return;
  const double m = 0.5 * (a + b);
  split(line, a, m, depth - 1, false, c, out);
  out.push_back(m);
  split(line, m, b, depth - 1, false, c, out);
}

}  // namespace

Skeleton resample_skeleton(const Skeleton& skeleton, const ResampleSkeletonOptions& options) {
  Skeleton out;
  std::vector<int> new_index(skeleton.num_nodes(), -1);
  for (std::size_t v = 0; v < skeleton.num_nodes(); ++v)
    if (skeleton.neighbors[v].size() != 2 || skeleton.neighbors[v].empty())
      new_index[v] = out.add_node(skeleton.points[v], skeleton.radii[v]);
  const auto arcs = skeleton_arcs(skeleton);
  for (const SkeletonArc& arc : arcs) {
    Polyline line;
    double length = 0;
    for (std::size_t i = 0; i < arc.nodes.size(); ++i) {
      const auto v = static_cast<std::size_t>(arc.nodes[i]);
      if (i > 0) length += (skeleton.points[v] - line.points.back()).norm();
      line.points.push_back(skeleton.points[v]);
      line.radii.push_back(skeleton.radii[v]);
      line.t.push_back(length);
    }
    for (double& t : line.t) t = length > 0 ? t / length : 0.0;
    std::vector<double> samples;
    // the bend criterion only on loops (an arc back to its own start, or a
    // cycle): see the header
    const bool loop = arc.closed || arc.nodes.front() == arc.nodes.back();
    const SplitCriteria criteria{options.neck_ratio, loop ? options.bend_ratio : 0.0};
    if (arc.closed) {  // at least two inner nodes: a cycle of three or more
      const double third = 1.0 / 3.0;
      split(line, 0, third, options.max_depth, false, criteria, samples);
      samples.push_back(third);
      split(line, third, 2 * third, options.max_depth, false, criteria, samples);
      samples.push_back(2 * third);
      split(line, 2 * third, 1, options.max_depth, false, criteria, samples);
    } else {
      split(line, 0, 1, options.max_depth, true, criteria, samples);
    }
    int first = new_index[static_cast<std::size_t>(arc.nodes.front())];
    if (first < 0) {  // closed cycle: its start node is of degree 2
      first = out.add_node(line.points.front(), line.radii.front());
      new_index[static_cast<std::size_t>(arc.nodes.front())] = first;
    }
    int prev = first;
    for (double s : samples) {
      Vec3 p;
      double r;
      line.at(s, p, r);
      const int v = out.add_node(p, r);
      out.add_edge(prev, v);
      prev = v;
    }
    const int last = new_index[static_cast<std::size_t>(arc.nodes.back())];
    out.add_edge(prev, last);
  }
  return out;
}

}  // namespace subfab
