// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/cone_template.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "subfab/core/error.h"

namespace subfab::detail {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

// Local coordinates of a point of the layer: which coarse hexahedron (0 the
// core, 1 + i ring i), its cross-section coordinates in eighths (a along
// c_i -> c_i+1 in a ring, b outwards in a ring; a along c0 -> c1, b along
// c0 -> c3 in the core) and its height in twelfths (0 tip, 12 base).
constexpr int kA = 8, kZ = 12;
struct Point {
  int k, a, b, z;
};

class TemplateBuilder {
 public:
  TemplateBuilder(const HexMesh& in, const ConeLayer& layer, const std::array<Hex, 5>& cells, HexSplitter& splitter,
                  HexMesh& out)
      : in_(in), layer_(layer), cells_(cells), splitter_(splitter), out_(out) {
    for (int k = 0; k < 5; ++k) {
      for (int c = 0; c < 8; ++c) corners_[k][c] = corner_id(k, c & 1, (c >> 1) & 1, c >> 2);
      parity_[k] = frame_parity(k);
    }
    set_heights();
  }

  // a box column of coarse hexahedron k, [a0, a1] x [b0, b1] x [z0, z1]
  void plain(int k, int a0, int a1, int b0, int b1, int z0, int z1) {
    add({{{k, a0, b0, z0}, {k, a1, b0, z0}, {k, a1, b1, z0}, {k, a0, b1, z0},
          {k, a0, b0, z1}, {k, a1, b0, z1}, {k, a1, b1, z1}, {k, a0, b1, z1}}});
  }
  void split_in_height(int k, int a0, int a1, int b0, int b1, int z0, int z1) {
    const int zm = (z0 + z1) / 2;
    plain(k, a0, a1, b0, b1, z0, zm);
    plain(k, a0, a1, b0, b1, zm, z1);
  }
  //! The 2D transition in the plane (along, z), `along` = a (true) or b,
  //! its top split in two and its side at the `high` end of `along` split
  //! at mid-height: three quads around the inner point (middle, mid-height),
  //! joined to the bottom corner of the unsplit side, the side's midpoint
  //! and the top's midpoint. Extruded across the other coordinate.
  void transition(int k, bool along_a, bool high, int a0, int a1, int b0, int b1, int z0, int z1) {
    const int s0 = along_a ? (high ? a0 : a1) : (high ? b0 : b1);  // unsplit side
    const int s1 = along_a ? (high ? a1 : a0) : (high ? b1 : b0);  // split side
    const int sm = (s0 + s1) / 2, zm = (z0 + z1) / 2;
    const int e0 = along_a ? b0 : a0, e1 = along_a ? b1 : a1;
    struct P2 {
      int s, z;
    };
    const P2 bl{s0, z0}, br{s1, z0}, mr{s1, zm}, tr{s1, z1}, mt{sm, z1}, tl{s0, z1}, c{sm, zm};
    // the inner point: in the middle, or, when the box is flatter than
    // wide, nearer the unsplit side, on the diagonal from its bottom corner
    // at 45 degrees (its two quads there would be slivers otherwise)
    // (measured on each of the two faces the pattern is extruded between)
    for (int e : {e0, e1}) {
      const double ee = static_cast<double>(e) / kA;
      auto at = [&](double s, double z) {
        return along_a ? local_position(k, s / kA, ee, z) : local_position(k, ee, s / kA, z);
      };
      const double zgm = height(zm);
      const double w = (at(s1, zgm) - at(s0, zgm)).norm();
      const double h = (at(0.5 * (s0 + s1), height(z1)) - at(0.5 * (s0 + s1), height(z0))).norm();
      const double f = w > 0 ? std::clamp(0.5 * h / w, 0.3, 0.5) : 0.5;
      const double sc = (s0 + f * (s1 - s0)) / kA;
      const Point p = along_a ? Point{k, c.s, e, c.z} : Point{k, e, c.s, c.z};
      override_.emplace(key(p), along_a ? std::array<double, 3>{sc, ee, zgm} : std::array<double, 3>{ee, sc, zgm});
    }
    const std::array<std::array<P2, 4>, 3> quads{{{bl, br, mr, c}, {c, mr, tr, mt}, {c, mt, tl, bl}}};
    for (const auto& q : quads) {
      std::array<Point, 8> h;
      for (int j = 0; j < 4; ++j) {
        const P2 p = q[static_cast<std::size_t>(j)];
        h[static_cast<std::size_t>(j)] = along_a ? Point{k, p.s, e0, p.z} : Point{k, e0, p.s, p.z};
        h[static_cast<std::size_t>(j + 4)] = along_a ? Point{k, p.s, e1, p.z} : Point{k, e1, p.s, p.z};
      }
      add(h);
    }
  }

 private:
  const HexMesh& in_;
  const ConeLayer& layer_;
  const std::array<Hex, 5>& cells_;
  HexSplitter& splitter_;
  HexMesh& out_;
  int corners_[5][8];  // [k][ia + 2 ib + 4 iz]
  int parity_[5];
  std::map<std::tuple<int, int, int>, int> made_;  // layer parameter point -> vertex
  std::map<std::tuple<int, int, int>, std::array<double, 3>> override_;  // local position of the inner points
  double z_at_[kZ + 1];  // geometric height (0 to 1) of each height step

  //! Heights of the three sub-layers in proportion to what each doubles
  //! (the core's width twice, the padding's thickness), so that their 2D
  //! transitions are about as high as wide.
  void set_heights() {
    auto P = [&](int v) { return in_.vertices[idx(v)]; };
    double w = 0, t = 0;
    for (int i = 0; i < 4; ++i) {
      const int j = (i + 1) % 4;
      w += (P(layer_.tip[idx(j)]) - P(layer_.tip[idx(i)])).norm() + (P(layer_.base[idx(j)]) - P(layer_.base[idx(i)])).norm();
      t += (P(layer_.outer_tip[idx(i)]) - P(layer_.tip[idx(i)])).norm() +
           (P(layer_.outer_base[idx(i)]) - P(layer_.base[idx(i)])).norm();
    }
    double h[3] = {w, w, t};
    const double sum = h[0] + h[1] + h[2];
    for (double& x : h) x = sum > 0 ? std::clamp(x / sum, 0.2, 0.6) : 1.0 / 3;
    const double norm = h[0] + h[1] + h[2];
    const double b1 = h[0] / norm, b2 = (h[0] + h[1]) / norm;
    const double levels[4] = {0, b1, b2, 1};
    for (int z = 0; z <= kZ; ++z) {
      const int s = std::min(z / 4, 2);
      z_at_[z] = levels[s] + (levels[s + 1] - levels[s]) * (z - 4 * s) / 4.0;
    }
  }
  double height(int z) const { return z_at_[z]; }

  int corner_id(int k, int ia, int ib, int iz) const {
    const auto& L = layer_;
    if (k == 0) {
      static constexpr int cyc[2][2] = {{0, 3}, {1, 2}};  // (ia, ib) -> corner of the cycle
      const int c = cyc[ia][ib];
      return iz ? L.base[idx(c)] : L.tip[idx(c)];
    }
    const int i = k - 1, j = (i + 1) % 4, c = ia ? j : i;
    if (iz) return ib ? L.outer_base[idx(c)] : L.base[idx(c)];
    return ib ? L.outer_tip[idx(c)] : L.tip[idx(c)];
  }

  //! +1 when the local frame (a, b, z) of coarse hexahedron k is oriented
  //! as the hexahedron itself, -1 when it is its mirror image.
  int frame_parity(int k) const {
    const Hex& h = cells_[idx(k)];
    const int* c = corners_[k];
    // the local bottom face, outward: corners (0,0) (0,1) (1,1) (1,0) at z = 0
    const std::array<int, 4> f{c[0], c[2], c[3], c[1]};
    for (int face = 0; face < 6; ++face) {
      const Quad q = hex_face(h, face);
      for (int s = 0; s < 4; ++s) {
        bool same = true, reversed = true;
        for (int t = 0; t < 4; ++t) {
          same = same && q[idx((s + t) % 4)] == f[idx(t)];
          reversed = reversed && q[idx((s + 4 - t) % 4)] == f[idx(t)];
        }
        if (same) return 1;
        if (reversed) return -1;
      }
    }
    throw AlgorithmError("cone template: a layer hexahedron does not have its own corners (internal error)");
  }

  //! Key in the layer's cross-section parameter plane: the core is
  //! [-1, 1]^2, ring i the trapezoid on its side i out to [-2, 2]^2, x 64.
  std::tuple<int, int, int> key(const Point& p) const {
    if (p.k == 0) return {8 * (2 * p.a - kA), 8 * (2 * p.b - kA), p.z};
    int x = (2 * p.a - kA) * (kA + p.b), y = -kA * (kA + p.b);
    for (int i = 0; i < p.k - 1; ++i) std::tie(x, y) = std::make_tuple(-y, x);
    return {x, y, p.z};
  }

  Vec3 position(const Point& p) const {
    const auto it = override_.find(key(p));
    if (it != override_.end()) return local_position(p.k, it->second[0], it->second[1], it->second[2]);
    return local_position(p.k, static_cast<double>(p.a) / kA, static_cast<double>(p.b) / kA, height(p.z));
  }
  //! Trilinear position in coarse hexahedron k at local (u, v, w) in [0, 1]^3.
  Vec3 local_position(int k, double u, double v, double w) const {
    Vec3 x = Vec3::Zero();
    for (int c = 0; c < 8; ++c) {
      const double f = ((c & 1) ? u : 1 - u) * (((c >> 1) & 1) ? v : 1 - v) * ((c >> 2) ? w : 1 - w);
      x += f * in_.vertices[idx(corners_[k][c])];
    }
    return x;
  }

  int vertex(const Point& p) {
    const bool ea = p.a == 0 || p.a == kA, eb = p.b == 0 || p.b == kA;
    const int* c = corners_[p.k];
    if ((p.z == 0 || p.z == kZ) && ea && eb) return c[(p.a ? 1 : 0) + (p.b ? 2 : 0) + (p.z ? 4 : 0)];
    if (p.z == kZ) {  // the base face: the regular split's midpoints
      const int* t = c + 4;
      if (ea && p.b == kA / 2) return splitter_.edge(t[p.a ? 1 : 0], t[p.a ? 3 : 2]);
      if (eb && p.a == kA / 2) return splitter_.edge(t[p.b ? 2 : 0], t[p.b ? 3 : 1]);
      if (p.a == kA / 2 && p.b == kA / 2) return splitter_.face(t[0], t[1], t[3], t[2]);
    }
    if (p.z == 0 || p.z == kZ) throw AlgorithmError("cone template: a point off the regular grid on the tip or base");
    const auto k = key(p);
    const auto it = made_.find(k);
    if (it != made_.end()) return it->second;
    out_.vertices.push_back(position(p));
    const int v = static_cast<int>(out_.vertices.size()) - 1;
    made_.emplace(k, v);
    return v;
  }

  void add(const std::array<Point, 8>& h) {
    // orientation in the local frame: corner 0 and its three edges
    auto d = [&](int j) {
      return Vec3(h[idx(j)].a - h[0].a, h[idx(j)].b - h[0].b, (h[idx(j)].z - h[0].z) * (double(kA) / kZ));
    };
    const double det = d(1).cross(d(3)).dot(d(4));
    const bool flip = (det > 0) != (parity_[h[0].k] > 0);
    Hex out;
    for (int j = 0; j < 8; ++j) out[idx(j)] = vertex(h[idx(flip ? (j + 4) % 8 : j)]);
    out_.hexes.push_back(out);
  }
};

}  // namespace

void add_cone_template(const HexMesh& in, const ConeLayer& layer, const std::array<Hex, 5>& cells,
                       HexSplitter& splitter, HexMesh& out) {
  TemplateBuilder t(in, layer, cells, splitter, out);
  const int h = kA / 2;
  // 1. the chords through ring 0, the core and ring 2 doubled; their new
  //    sheet leaves towards ring 1, which is split in height to carry it out
  t.transition(0, true, true, 0, kA, 0, kA, 0, 4);
  t.transition(1, true, true, 0, kA, 0, kA, 0, 4);
  t.transition(3, true, false, 0, kA, 0, kA, 0, 4);
  t.split_in_height(2, 0, kA, 0, kA, 0, 4);
  t.plain(4, 0, kA, 0, kA, 0, 4);
  // 2. the chords through ring 3, the core and ring 1; out through ring 2
  for (int a0 : {0, h}) t.transition(0, false, true, a0, a0 + h, 0, kA, 4, 8);
  t.transition(2, true, true, 0, kA, 0, kA, 4, 8);
  t.transition(4, true, false, 0, kA, 0, kA, 4, 8);
  for (int a0 : {0, h}) {
    t.split_in_height(3, a0, a0 + h, 0, kA, 4, 8);
    t.plain(1, a0, a0 + h, 0, kA, 4, 8);
  }
  // 3. the ring loop, its new sheet out through the boundary
  for (int a0 : {0, h})
    for (int b0 : {0, h}) t.plain(0, a0, a0 + h, b0, b0 + h, 8, kZ);
  for (int k = 1; k <= 4; ++k)
    for (int a0 : {0, h}) t.transition(k, false, true, a0, a0 + h, 0, kA, 8, kZ);
}

}  // namespace subfab::detail
