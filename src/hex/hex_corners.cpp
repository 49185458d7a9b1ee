// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/hex_corners.h"

#include <algorithm>
#include <cmath>

#include "subfab/core/parallel.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab::detail {
namespace {
std::size_t idx(int v) { return static_cast<std::size_t>(v); }
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
                       const std::vector<double>* corner_values) {
  VertexStar st;
  st.v = v;
  st.hexes = &hexes;
  st.slot.assign(8 * hexes.size(), -1);
  st.fixed_min.resize(hexes.size());
  if (sharpness > 0) st.fixed_exp.resize(8 * hexes.size());
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
        VertexStar::Moved c{};
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
          } else {
            Vec3 e = mesh.vertices[idx(w)] - p;
            const double len = e.norm();
            if (!(len > 0)) c.degenerate = true;
            else e /= len;
            c.fixed[k] = e;
          }
        }
        st.slot[8 * j + i] = static_cast<int>(st.moved.size());
        st.moved.push_back(c);
        continue;
      }
      const double alpha = corner_values ? (*corner_values)[8 * idx(hexes[j]) + i]
                                         : corner_determinant(mesh, {hexes[j], static_cast<int>(i)});
      m = std::min(m, alpha);
      if (sharpness > 0) st.fixed_exp[8 * j + i] = std::exp(-sharpness * alpha);
    }
    st.fixed_min[j] = m;
  }
  st.units.resize(st.neighbours.size());
  st.zero.resize(st.neighbours.size());
  st.values.resize(st.moved.size());
  return st;
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
    const VertexStar::Moved& m = st.moved[c];
    Vec3 e[3];
    bool degenerate = m.degenerate;
    for (std::size_t k = 0; k < 3; ++k) {
      if (m.neighbour[k] < 0) {
        e[k] = m.fixed[k];
      } else {
        degenerate = degenerate || st.zero[idx(m.neighbour[k])];
        e[k] = m.sign[k] > 0 ? st.units[idx(m.neighbour[k])] : Vec3(-st.units[idx(m.neighbour[k])]);
      }
    }
    st.values[c] = degenerate ? -1.0 : e[0].dot(e[1].cross(e[2]));
  }
}

double star_hex_quality(const VertexStar& st, std::size_t j) {
  double q = st.fixed_min[j];
  for (std::size_t i = 0; i < 8; ++i)
    if (const int c = st.slot[8 * j + i]; c >= 0) q = std::min(q, st.values[idx(c)]);
  return q;
}

void store_star(const HexMesh& mesh, const VertexStar& st, std::vector<double>& corner_values) {
  evaluate_star(mesh, st);
  for (std::size_t j = 0; j < st.hexes->size(); ++j)
    for (std::size_t i = 0; i < 8; ++i)
      if (const int c = st.slot[8 * j + i]; c >= 0) corner_values[8 * idx((*st.hexes)[j]) + i] = st.values[idx(c)];
}

std::vector<double> all_corner_values(const HexMesh& mesh) {
  std::vector<double> out(8 * mesh.hexes.size());
  parallel_for(0, mesh.hexes.size(), [&](std::size_t h) {
    for (int c = 0; c < 8; ++c) out[8 * h + idx(c)] = corner_determinant(mesh, {static_cast<int>(h), c});
  }, 256);
  return out;
}

std::vector<double> hex_qualities(const std::vector<double>& corner_values) {
  std::vector<double> out(corner_values.size() / 8);
  parallel_for(0, out.size(), [&](std::size_t h) {
    double q = 1.0;
    for (std::size_t c = 0; c < 8; ++c) q = std::min(q, corner_values[8 * h + c]);
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
