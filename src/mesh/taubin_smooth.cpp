// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/taubin_smooth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

void check_options(const TaubinOptions& o, const Mesh& mesh) {
  if (o.num_passes < 0) throw InvalidArgumentError("smooth: the number of passes must be >= 0");
  if (!(o.lambda > 0 && o.lambda < 1))
    throw InvalidArgumentError("smooth: Taubin lambda must be in (0, 1) (got " + std::to_string(o.lambda) + ")");
  if (!(o.mu == 0 || (o.mu < -o.lambda && o.mu > -1)))
    throw InvalidArgumentError("smooth: Taubin mu must be in (-1, -lambda) (or 0 for a plain Laplacian; got " +
                               std::to_string(o.mu) + ")");
  if (!(o.max_displacement >= 0))
    throw InvalidArgumentError("smooth: the displacement cap must be >= 0 (got " +
                               std::to_string(o.max_displacement) + ")");
  if (!o.anchors.empty() && o.anchors.size() != mesh.vertices.size())
    throw InvalidArgumentError("smooth: " + std::to_string(o.anchors.size()) + " anchors for " +
                               std::to_string(mesh.vertices.size()) + " vertices");
  const int nv = static_cast<int>(mesh.vertices.size());
  for (const Triangle& t : mesh.faces)
    for (int v : t)
      if (v < 0 || v >= nv) throw InvalidArgumentError("smooth: face index " + std::to_string(v) + " out of range");
}

//! Compressed rows: row v is ids[start[v] .. start[v + 1]).
struct Rows {
  std::vector<int> start, ids;
  int begin(int v) const { return start[static_cast<std::size_t>(v)]; }
  int end(int v) const { return start[static_cast<std::size_t>(v) + 1]; }
  int at(int i) const { return ids[static_cast<std::size_t>(i)]; }
};

//! Per vertex: its neighbours (sorted, unique) and its incident faces.
struct Connectivity {
  Rows neighbours, faces;
};

Connectivity build_connectivity(const Mesh& mesh) {
  const std::size_t nv = mesh.vertices.size();
  Connectivity c;
  // Incident faces by counting sort (face order within a row).
  c.faces.start.assign(nv + 1, 0);
  for (const Triangle& t : mesh.faces)
    for (int v : t) ++c.faces.start[static_cast<std::size_t>(v) + 1];
  std::partial_sum(c.faces.start.begin(), c.faces.start.end(), c.faces.start.begin());
  c.faces.ids.resize(static_cast<std::size_t>(c.faces.start[nv]));
  std::vector<int> fill(c.faces.start.begin(), c.faces.start.end() - 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f]) c.faces.ids[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<int>(f);
  const VertexNeighbours n = vertex_neighbours(mesh);
  c.neighbours.start = n.start;
  c.neighbours.ids = n.ids;
  return c;
}

//! cot of the angle between u and v (0 for a degenerate corner).
double cotangent(const Vec3& u, const Vec3& v) {
  const double s = u.cross(v).norm();
  return s > 0 ? u.dot(v) / s : 0.0;
}

//! Weighted mean of the neighbours of v (uniform or clamped cotangent weights).
Vec3 neighbour_mean(const Mesh& mesh, const Connectivity& c, int v, TaubinWeights weights) {
  const auto& P = mesh.vertices;
  const auto& N = c.neighbours;
  const int degree = N.end(v) - N.begin(v);
  Vec3 uniform = Vec3::Zero();
  for (int i = N.begin(v); i < N.end(v); ++i) uniform += P[static_cast<std::size_t>(N.at(i))];
  uniform /= degree;
  if (weights == TaubinWeights::Uniform) return uniform;
  // Half cotangent of the corner opposite each edge (v, w), per incident face.
  std::vector<std::pair<int, double>> halves;
  halves.reserve(static_cast<std::size_t>(2 * (c.faces.end(v) - c.faces.begin(v))));
  const Vec3& p = P[static_cast<std::size_t>(v)];
  for (int i = c.faces.begin(v); i < c.faces.end(v); ++i) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(c.faces.at(i))];
    const int k = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
    const int a = t[static_cast<std::size_t>((k + 1) % 3)], b = t[static_cast<std::size_t>((k + 2) % 3)];
    const Vec3& pa = P[static_cast<std::size_t>(a)];
    const Vec3& pb = P[static_cast<std::size_t>(b)];
    halves.emplace_back(a, 0.5 * cotangent(p - pb, pa - pb));  // corner at b is opposite edge (v, a)
    halves.emplace_back(b, 0.5 * cotangent(p - pa, pb - pa));  // corner at a is opposite edge (v, b)
  }
  std::sort(halves.begin(), halves.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  Vec3 sum = Vec3::Zero();
  double total = 0;
  for (std::size_t i = 0; i < halves.size();) {
    std::size_t j = i;
    double w = 0;
    for (; j < halves.size() && halves[j].first == halves[i].first; ++j) w += halves[j].second;
    if (w > 0 && std::isfinite(w)) {
      sum += w * P[static_cast<std::size_t>(halves[i].first)];
      total += w;
    }
    i = j;
  }
  return total > 0 && std::isfinite(total) ? Vec3(sum / total) : uniform;
}

//! Pulls p back radially so that |p - anchor| <= cap holds as computed.
Vec3 cap_displacement(const Vec3& p, const Vec3& anchor, double cap) {
  const Vec3 d = p - anchor;
  const double length = d.norm();
  if (length <= cap) return p;
  double scale = cap / length;
  Vec3 r = anchor + d * scale;
  for (int i = 0; i < 64 && (r - anchor).norm() > cap; ++i) {
    scale *= 1 - 1e-15 * (1 << std::min(i, 40));
    r = anchor + d * scale;
  }
  return (r - anchor).norm() <= cap ? r : anchor;
}

//! One Jacobi step p += factor * (mean - p) on the movable vertices.
void laplacian_step(Mesh& mesh, const Connectivity& c, const std::vector<int>& movable, double factor,
                    const TaubinOptions& o, std::span<const Vec3> anchors, std::vector<Vec3>& moved) {
  parallel_for(
      0, movable.size(),
      [&](std::size_t i) {
        const int v = movable[i];
        const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
        if (c.neighbours.end(v) == c.neighbours.begin(v)) {
          moved[i] = p;
          return;
        }
        const Vec3 step = factor * (neighbour_mean(mesh, c, v, o.weights) - p);
        Vec3 r = p + step;
        if (o.keep_axis_aligned)
          for (int k = 0; k < 3; ++k) {
            bool shared = true;
            for (int j = c.neighbours.begin(v); shared && j < c.neighbours.end(v); ++j)
              shared = mesh.vertices[static_cast<std::size_t>(c.neighbours.at(j))][k] == p[k];
            if (shared) r[k] = p[k];
          }
        moved[i] = cap_displacement(r, anchors[static_cast<std::size_t>(v)], o.max_displacement);
      },
      512);
  for (std::size_t i = 0; i < movable.size(); ++i) mesh.vertices[static_cast<std::size_t>(movable[i])] = moved[i];
}

}  // namespace

TaubinReport taubin_smooth(Mesh& mesh, const TaubinOptions& options) {
  std::vector<int> all(mesh.vertices.size());
  std::iota(all.begin(), all.end(), 0);
  return taubin_smooth(mesh, all, options);
}

TaubinReport taubin_smooth(Mesh& mesh, std::span<const int> movable_ids, const TaubinOptions& options) {
  check_options(options, mesh);
  const int nv = static_cast<int>(mesh.vertices.size());
  std::vector<int> movable(movable_ids.begin(), movable_ids.end());
  for (int v : movable)
    if (v < 0 || v >= nv) throw InvalidArgumentError("smooth: movable vertex " + std::to_string(v) + " out of range");
  std::sort(movable.begin(), movable.end());
  movable.erase(std::unique(movable.begin(), movable.end()), movable.end());

  std::vector<Vec3> own_anchors;
  std::span<const Vec3> anchors = options.anchors;
  if (anchors.empty()) {
    own_anchors = mesh.vertices;
    anchors = own_anchors;
  }
  TaubinReport report;
  if (!movable.empty() && options.num_passes > 0) {
    const Connectivity c = build_connectivity(mesh);
    std::vector<Vec3> moved(movable.size());
    for (int pass = 0; pass < options.num_passes; ++pass) {
      laplacian_step(mesh, c, movable, options.lambda, options, anchors, moved);
      if (options.mu != 0) laplacian_step(mesh, c, movable, options.mu, options, anchors, moved);
      ++report.num_passes;
    }
  }
  for (int v : movable) {
    const double d = (mesh.vertices[static_cast<std::size_t>(v)] - anchors[static_cast<std::size_t>(v)]).norm();
    report.max_displacement = std::max(report.max_displacement, d);
    if (std::isfinite(options.max_displacement) && options.max_displacement > 0 && d >= options.max_displacement * (1 - 1e-9)) ++report.num_capped;
  }
  return report;
}

}  // namespace subfab
