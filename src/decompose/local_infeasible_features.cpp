// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/local_infeasible_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "decompose/exact_normal_signs.h"
#include "decompose/solid_index.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/axis.h"

namespace subfab::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

//! Bit i set iff the face faces axis i (exact n.d >= 0).
std::uint8_t facing_mask(const std::array<std::int8_t, 3>& s) {
  std::uint8_t m = 0;
  for (Axis a : kAllAxes)
    if (s[static_cast<std::size_t>(axis_dimension(a))] * axis_sign(a) >= 0) m |= std::uint8_t(1u << axis_index(a));
  return m;
}

std::uint64_t directed_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

//! A double strictly beyond x on `side` (+1 above, -1 below).
double beyond(double x, int side) {
  const double y = x + side * std::max(1.0, std::abs(x));
  return (side > 0 ? y > x : y < x) && std::isfinite(y) ? y : std::nextafter(x, side * kInf);
}

}  // namespace

std::vector<LocalInfeasibleFeature> find_local_infeasible_features(const Mesh& mesh) {
  const std::size_t nf = mesh.faces.size();
  const std::size_t nv = mesh.vertices.size();
  const std::vector<std::array<std::int8_t, 3>> signs = exact_normal_signs(mesh);
  std::vector<std::uint8_t> mask(nf);
  for (std::size_t f = 0; f < nf; ++f) mask[f] = facing_mask(signs[f]);
  // Vertex -> faces (CSR, faces in id order).
  std::vector<int> start(nv + 1, 0), star;
  for (const Triangle& t : mesh.faces)
    for (int v : t) ++start[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  star.resize(static_cast<std::size_t>(start[nv]));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < nf; ++f)
      for (int v : mesh.faces[f]) star[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<int>(f);
  }
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const Triangle& t = mesh.faces[f];
    for (int e = 0; e < 3; ++e) directed.emplace(directed_key(t[e], t[(e + 1) % 3]), static_cast<int>(f));
  }
  auto pos = [&](int v) -> const Vec3& { return mesh.vertices[static_cast<std::size_t>(v)]; };

  // Per face: up to 3 crease entries and 3 vertex entries (slot per corner).
  std::vector<std::array<LocalInfeasibleFeature, 6>> found(nf);
  parallel_for(
      0, nf,
      [&](std::size_t fi) {
        const int f = static_cast<int>(fi);
        const Triangle& t = mesh.faces[fi];
        for (int e = 0; e < 3; ++e) {
          const int u = t[e], w = t[(e + 1) % 3], q = t[(e + 2) % 3];
          // --- crease (u, w) seen from f's child along it ---
          const auto it = directed.find(directed_key(w, u));
          if (it != directed.end()) {
            const int g = it->second;
            if ((mask[fi] & mask[static_cast<std::size_t>(g)]) == 0) {
              const Triangle& tg = mesh.faces[static_cast<std::size_t>(g)];
              int r = tg[0];
              for (int x : tg)
                if (x != u && x != w) r = x;
              bool enters = true;
              for (int k = 0; k < 3 && enters; ++k) {
                const double c = pos(u)[k];
                if (pos(w)[k] != c) continue;
                int side = pos(q)[k] > c ? 1 : (pos(q)[k] < c ? -1 : -signs[fi][static_cast<std::size_t>(k)]);
                enters = side != 0 && side * (pos(r)[k] - c) > 0;
              }
              if (enters)
                found[fi][static_cast<std::size_t>(e)] = LocalInfeasibleFeature{std::min(u, w), std::max(u, w), f, g};
            }
          }
          // --- vertex u: f's child at the corner u ---
          Box3 cone;
          for (int k = 0; k < 3; ++k) {
            const double x = pos(u)[k], lo = std::min({x, pos(w)[k], pos(q)[k]}),
                         hi = std::max({x, pos(w)[k], pos(q)[k]});
            int side = 0;  // 0: both sides, +1: above only, -1: below only
            if (lo == hi)
              side = -signs[fi][static_cast<std::size_t>(k)];
            else if (x == lo)
              side = 1;
            else if (x == hi)
              side = -1;
            cone.min[k] = side > 0 ? x : beyond(x, -1);
            cone.max[k] = side < 0 ? x : beyond(x, +1);
          }
          std::uint8_t common = mask[fi];
          int blocker = -1;
          for (int s = start[static_cast<std::size_t>(u)]; s < start[static_cast<std::size_t>(u) + 1] && common; ++s) {
            const int g = star[static_cast<std::size_t>(s)];
            if (g == f || (mask[static_cast<std::size_t>(g)] & common) == common) continue;
            const Triangle& tg = mesh.faces[static_cast<std::size_t>(g)];
            if (!triangle_meets_open_box(pos(tg[0]), pos(tg[1]), pos(tg[2]), cone)) continue;
            common &= mask[static_cast<std::size_t>(g)];
            blocker = g;
          }
          if (!common) found[fi][static_cast<std::size_t>(3 + e)] = LocalInfeasibleFeature{u, -1, f, blocker};
        }
      },
      256);

  // Merge in face order: creases once per edge, vertices once per vertex.
  std::vector<LocalInfeasibleFeature> creases, vertices;
  for (const auto& slots : found)
    for (const LocalInfeasibleFeature& x : slots)
      if (x.face >= 0) (x.is_crease() ? creases : vertices).push_back(x);
  auto by_ids = [](const LocalInfeasibleFeature& a, const LocalInfeasibleFeature& b) {
    return std::tie(a.vertex0, a.vertex1, a.face) < std::tie(b.vertex0, b.vertex1, b.face);
  };
  auto same = [](const LocalInfeasibleFeature& a, const LocalInfeasibleFeature& b) {
    return a.vertex0 == b.vertex0 && a.vertex1 == b.vertex1;
  };
  std::sort(creases.begin(), creases.end(), by_ids);
  creases.erase(std::unique(creases.begin(), creases.end(), same), creases.end());
  std::sort(vertices.begin(), vertices.end(), by_ids);
  vertices.erase(std::unique(vertices.begin(), vertices.end(), same), vertices.end());
  creases.insert(creases.end(), vertices.begin(), vertices.end());
  return creases;
}

std::string describe_feature(const Mesh& mesh, const LocalInfeasibleFeature& x) {
  auto pos = [&](int v) -> const Vec3& { return mesh.vertices[static_cast<std::size_t>(v)]; };
  std::ostringstream msg;
  const Vec3 nf = face_unit_normal(mesh, static_cast<std::size_t>(x.face));
  const Vec3 ng = x.other_face >= 0 ? face_unit_normal(mesh, static_cast<std::size_t>(x.other_face)) : nf;
  const double angle = std::acos(std::clamp(nf.dot(ng), -1.0, 1.0)) * 180.0 / M_PI;
  if (x.is_crease()) {
    msg << "crease between vertices " << x.vertex0 << " (" << pos(x.vertex0).transpose() << ") and " << x.vertex1
        << " (" << pos(x.vertex1).transpose() << "), faces " << x.face << " and " << x.other_face << " (normals "
        << angle << " degrees apart, no common milling direction)";
  } else {
    msg << "vertex " << x.vertex0 << " (" << pos(x.vertex0).transpose() << "): no box corner isolates face "
        << x.face << " from face " << x.other_face << " (normals " << angle
        << " degrees apart, no common milling direction)";
  }
  return msg.str();
}

}  // namespace subfab::detail
