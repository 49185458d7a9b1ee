// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/hex_corners.h"

#include "hex/hex_topology.h"

#include <algorithm>
#include <cmath>

#include "subfab/core/parallel.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab::detail {
namespace {
std::size_t idx(int v) { return static_cast<std::size_t>(v); }

//! Per corner i and edge k of that corner (towards kHexCornerNeighbors[i][k]):
//! the hexahedron edge (kHexEdges index) and whether it runs from i (+1) or
//! towards i (-1).
struct CornerEdge {
  int edge;
  double sign;
};
struct CornerEdges {
  CornerEdge at[8][3];
  CornerEdges() {
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) {
        const int j = kHexCornerNeighbors[idx(i)][idx(k)];
        for (int e = 0; e < 12; ++e) {
          if (kHexEdges[e][0] == i && kHexEdges[e][1] == j) at[i][k] = {e, 1.0};
          if (kHexEdges[e][0] == j && kHexEdges[e][1] == i) at[i][k] = {e, -1.0};
        }
      }
  }
};
const CornerEdges kCornerEdges;

//! Unit vector of b - a and whether it has zero length, by the operations of
//! corner_determinant().
Vec3 unit(const Vec3& a, const Vec3& b, bool& zero) {
  Vec3 e = b - a;
  const double len = e.norm();
  zero = !(len > 0);
  if (!zero) e /= len;
  return e;
}
}  // namespace

std::vector<std::vector<HexCorner>> vertex_corners(const HexMesh& mesh) {
  std::vector<std::vector<HexCorner>> out(mesh.vertices.size());
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    const Hex& hex = mesh.hexes[h];
    for (int c = 0; c < 8; ++c) {
      out[idx(hex[idx(c)])].push_back({static_cast<int>(h), c});
      for (int n : kHexCornerNeighbors[idx(c)]) out[idx(hex[idx(n)])].push_back({static_cast<int>(h), c});
    }
  }
  return out;
}

double corner_determinant(const HexMesh& mesh, const HexCorner& k) {
  const Hex& hex = mesh.hexes[idx(k.hex)];
  const auto& n = kHexCornerNeighbors[idx(k.corner)];
  const Vec3& p = mesh.vertices[idx(hex[idx(k.corner)])];
  Vec3 e[3];
  for (std::size_t i = 0; i < 3; ++i) {
    e[i] = mesh.vertices[idx(hex[idx(n[i])])] - p;
    const double len = e[i].norm();
    if (!(len > 0)) return -1.0;
    e[i] /= len;
  }
  return e[0].dot(e[1].cross(e[2]));
}

double corner_determinant_gradient(const HexMesh& mesh, const HexCorner& k, int v, Vec3& gradient) {
  const Hex& hex = mesh.hexes[idx(k.hex)];
  const auto& n = kHexCornerNeighbors[idx(k.corner)];
  const Vec3& p = mesh.vertices[idx(hex[idx(k.corner)])];
  Vec3 e[3];
  double len[3];
  gradient = Vec3::Zero();
  for (std::size_t i = 0; i < 3; ++i) {
    e[i] = mesh.vertices[idx(hex[idx(n[i])])] - p;
    len[i] = e[i].norm();
    if (!(len[i] > 0)) return -1.0;
    e[i] /= len[i];
  }
  // d det / d e_i = e_j x e_k; d e_i / d (far end of edge i) = (I - e_i e_i^T) / len_i
  Vec3 g[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3 c = e[(i + 1) % 3].cross(e[(i + 2) % 3]);
    g[i] = (c - e[i] * e[i].dot(c)) / len[i];
  }
  for (std::size_t i = 0; i < 3; ++i)
    if (hex[idx(n[i])] == v) gradient += g[i];
  if (hex[idx(k.corner)] == v) gradient -= g[0] + g[1] + g[2];
  return e[0].dot(e[1].cross(e[2]));
}

VertexStar vertex_star(const HexMesh& mesh, const std::vector<int>& hexes, std::size_t v, double sharpness,
                       const CornerCache* cache) {
  VertexStar st;
  build_vertex_star(st, mesh, hexes, v, sharpness, cache);
  return st;
}

void build_vertex_star(VertexStar& st, const HexMesh& mesh, const std::vector<int>& hexes, std::size_t v,
                       double sharpness, const CornerCache* cache) {
  st.v = v;
  st.hexes = &hexes;
  st.slot.assign(8 * hexes.size(), -1);
  st.fixed_min.resize(hexes.size());
  st.fixed_exp.resize(sharpness > 0 ? 8 * hexes.size() : 0);
  st.moved.clear();
  st.neighbours.clear();
  auto neighbour_index = [&](int w) {
    for (std::size_t s = 0; s < st.neighbours.size(); ++s)
      if (st.neighbours[s] == w) return static_cast<int>(s);
    st.neighbours.push_back(w);
    return static_cast<int>(st.neighbours.size() - 1);
  };
  for (std::size_t j = 0; j < hexes.size(); ++j) {
    const Hex& hex = mesh.hexes[idx(hexes[j])];
    double m = 1.0;
    for (std::size_t i = 0; i < 8; ++i) {
      const auto& n = kHexCornerNeighbors[i];
      const bool own = idx(hex[i]) == v;
      if (own || idx(hex[idx(n[0])]) == v || idx(hex[idx(n[1])]) == v || idx(hex[idx(n[2])]) == v) {
        st.slot[8 * j + i] = static_cast<int>(st.moved.size());
        VertexStar::Moved& c = st.moved.emplace_back();
        c.degenerate = false;
        const Vec3& p = mesh.vertices[idx(hex[i])];
        for (std::size_t k = 0; k < 3; ++k) {
          const int w = hex[idx(n[k])];
          c.neighbour[k] = -1;
          c.sign[k] = 0;
          if (own) {  // edge from v to w
            c.neighbour[k] = neighbour_index(w);
            c.sign[k] = 1;
          } else if (idx(w) == v) {  // edge from hex[i] to v
            c.neighbour[k] = neighbour_index(hex[i]);
            c.sign[k] = -1;
          } else if (cache) {  // the same unit vector, or its exact negation
            const CornerEdge& ce = kCornerEdges.at[i][k];
            const std::size_t e = 12 * idx(hexes[j]) + idx(ce.edge);
            if (cache->zero[e]) c.degenerate = true;
            c.fixed[k] = ce.sign > 0 ? cache->units[e] : Vec3(-cache->units[e]);
          } else {
            bool zero = false;
            c.fixed[k] = unit(p, mesh.vertices[idx(w)], zero);
            if (zero) c.degenerate = true;
          }
        }
        continue;
      }
      const double alpha = cache ? cache->values[8 * idx(hexes[j]) + i]
                                 : corner_determinant(mesh, {hexes[j], static_cast<int>(i)});
      m = std::min(m, alpha);
      if (sharpness > 0) st.fixed_exp[8 * j + i] = std::exp(-sharpness * alpha);
    }
    st.fixed_min[j] = m;
  }
  st.units.resize(st.neighbours.size());
  st.zero.resize(st.neighbours.size());
  st.values.resize(st.moved.size());
}

void evaluate_star(const HexMesh& mesh, const VertexStar& st) {
  const Vec3& p = mesh.vertices[st.v];
  for (std::size_t s = 0; s < st.neighbours.size(); ++s) {
    Vec3 e = mesh.vertices[idx(st.neighbours[s])] - p;
    const double len = e.norm();
    st.zero[s] = !(len > 0);
    if (len > 0) e /= len;
    st.units[s] = e;
  }
  for (std::size_t c = 0; c < st.moved.size(); ++c) {
    Vec3 e[3];
    st.values[c] = star_corner_edges(st, c, e) ? e[0].dot(e[1].cross(e[2])) : -1.0;
  }
}

double star_hex_quality(const VertexStar& st, std::size_t j) {
  double q = st.fixed_min[j];
  for (std::size_t i = 0; i < 8; ++i)
    if (const int c = st.slot[8 * j + i]; c >= 0) q = std::min(q, st.values[idx(c)]);
  return q;
}

void store_star(const HexMesh& mesh, const VertexStar& st, CornerCache& cache) {
  evaluate_star(mesh, st);
  for (std::size_t j = 0; j < st.hexes->size(); ++j) {
    const std::size_t h = idx((*st.hexes)[j]);
    for (std::size_t i = 0; i < 8; ++i) {
      const int c = st.slot[8 * j + i];
      if (c < 0) continue;
      cache.values[8 * h + i] = st.values[idx(c)];
      if (idx(mesh.hexes[h][i]) != st.v) continue;
      // v's own corner: its three edges, from v to neighbour[k]
      const VertexStar::Moved& m = st.moved[idx(c)];
      for (std::size_t k = 0; k < 3; ++k) {
        const CornerEdge& ce = kCornerEdges.at[i][k];
        const std::size_t e = 12 * h + idx(ce.edge);
        const Vec3& u = st.units[idx(m.neighbour[k])];
        cache.units[e] = ce.sign > 0 ? u : Vec3(-u);
        cache.zero[e] = st.zero[idx(m.neighbour[k])];
      }
    }
  }
}

CornerCache corner_cache(const HexMesh& mesh) {
  CornerCache out;
  out.values.resize(8 * mesh.hexes.size());
  out.units.resize(12 * mesh.hexes.size());
  out.zero.resize(12 * mesh.hexes.size());
  parallel_for(0, mesh.hexes.size(), [&](std::size_t h) {
    for (int c = 0; c < 8; ++c) out.values[8 * h + idx(c)] = corner_determinant(mesh, {static_cast<int>(h), c});
    const Hex& hex = mesh.hexes[h];
    for (std::size_t e = 0; e < 12; ++e) {
      bool zero = false;
      out.units[12 * h + e] = unit(mesh.vertices[idx(hex[idx(kHexEdges[e][0])])], mesh.vertices[idx(hex[idx(kHexEdges[e][1])])], zero);
      out.zero[12 * h + e] = zero;
    }
  }, 256);
  return out;
}

std::vector<double> hex_qualities(const CornerCache& cache) {
  std::vector<double> out(cache.values.size() / 8);
  parallel_for(0, out.size(), [&](std::size_t h) {
    double q = 1.0;
    for (std::size_t c = 0; c < 8; ++c) q = std::min(q, cache.values[8 * h + c]);
    out[h] = q;
  }, 1024);
  return out;
}

double star_min_moved(const VertexStar& st) {
  double m = 1.0;
  for (double x : st.values) m = std::min(m, x);
  return m;
}

}  // namespace subfab::detail
