// SPDX-License-Identifier: GPL-3.0-or-later
#include "mc_case_table.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <set>
#include <string>

#include "subfab/core/error.h"
#include "subfab/unfold/lattice_directions.h"

namespace subfab::mc {
namespace {

using Int3 = std::array<int, 3>;

Int3 corner2(int c) { return {2 * (c & 1), 2 * ((c >> 1) & 1), 2 * ((c >> 2) & 1)}; }
Int3 sub(const Int3& a, const Int3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Int3 cross(const Int3& a, const Int3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
int dot(const Int3& a, const Int3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Index of the lattice direction parallel to the integer vector n, or -1.
int direction_of(const Int3& n) {
  const int g = std::gcd(std::gcd(std::abs(n[0]), std::abs(n[1])), std::abs(n[2]));
  if (g == 0) return -1;
  const Int3 r{n[0] / g, n[1] / g, n[2] / g};
  const auto& dirs = lattice_directions();
  for (std::size_t i = 0; i < dirs.size(); ++i)
    if (dirs[i] == r) return static_cast<int>(i);
  return -1;
}

// Faces (axis, side) of edge e, as a bitmask over the 6 faces 2 * axis + side.
int edge_faces(int e) {
  const CubeEdge& edge = cube_edges()[static_cast<std::size_t>(e)];
  int mask = 0;
  for (int b = 0; b < 3; ++b)
    if (b != edge.axis) mask |= 1 << (2 * b + ((edge.corners[0] >> b) & 1));
  return mask;
}

using Triangulation = std::vector<Int3>;  // triangles as cube edge ids

// All triangulations of the polygon loop[i..j] closed by the base (j, i).
void triangulations(const std::vector<int>& loop, int i, int j, std::vector<Triangulation>& out) {
  if (j - i < 2) {
    out.push_back({});
    return;
  }
  for (int k = i + 1; k < j; ++k) {
    std::vector<Triangulation> left, right;
    triangulations(loop, i, k, left);
    triangulations(loop, k, j, right);
    for (const auto& l : left)
      for (const auto& r : right) {
        Triangulation t = l;
        t.insert(t.end(), r.begin(), r.end());
        t.push_back({loop[static_cast<std::size_t>(i)], loop[static_cast<std::size_t>(k)],
                     loop[static_cast<std::size_t>(j)]});
        out.push_back(std::move(t));
      }
  }
}

// A diagonal lying on a cube face, seen from the face: key identifies the
// face's axis and the two midpoints (both cubes sharing the face compute the
// same key), side is which face of this cube (0 low, 1 high) it lies on.
struct FaceDiagonal {
  int key;
  int side;
};

// One admissible triangulation of a loop.
struct Candidate {
  Triangulation triangles;
  std::vector<int> normals;
  std::vector<FaceDiagonal> face_diagonals;  // ownership it needs
  int num_normals = 0;                       // distinct normals (the score)
};

// Admissible triangulations of a loop (normals in the 26 directions, no
// fold-back), best score first (stable: enumeration order breaks ties).
std::vector<Candidate> admissible_triangulations(const std::vector<int>& loop) {
  const int n = static_cast<int>(loop.size());
  std::set<std::pair<int, int>> boundary;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    boundary.insert({loop[i], loop[(i + 1) % loop.size()]});
    boundary.insert({loop[(i + 1) % loop.size()], loop[i]});
  }
  std::vector<Triangulation> all;
  triangulations(loop, 0, n - 1, all);
  std::vector<Candidate> out;
  for (Triangulation& tri : all) {
    Candidate c;
    std::vector<Int3> raw;
    bool ok = true;
    for (const Int3& t : tri) {
      const Int3 nrm = cross(sub(edge_midpoint2(t[1]), edge_midpoint2(t[0])), sub(edge_midpoint2(t[2]), edge_midpoint2(t[0])));
      const int d = direction_of(nrm);
      if (d < 0) {
        ok = false;
        break;
      }
      c.normals.push_back(d);
      raw.push_back(nrm);
    }
    if (!ok) continue;
    for (std::size_t x = 0; x < tri.size() && ok; ++x)
      for (std::size_t y = x + 1; y < tri.size() && ok; ++y) {
        int shared = 0;
        for (int u : tri[x])
          for (int v : tri[y]) shared += u == v;
        if (shared == 2 && dot(raw[x], raw[y]) < 0) ok = false;  // folds back
      }
    if (!ok) continue;
    for (const Int3& t : tri)
      for (int s = 0; s < 3; ++s) {
        const int a = t[static_cast<std::size_t>(s)], b = t[static_cast<std::size_t>((s + 1) % 3)];
        if (a > b || boundary.count({a, b})) continue;  // each diagonal once; loop edges are not diagonals
        const int common = edge_faces(a) & edge_faces(b);
        if (!common) continue;
        const int face = __builtin_ctz(static_cast<unsigned>(common));
        const int axis = face / 2;
        Int3 pa = edge_midpoint2(a), pb = edge_midpoint2(b);
        auto drop = [axis](const Int3& p) {
          const int u = p[static_cast<std::size_t>((axis + 1) % 3)], v = p[static_cast<std::size_t>((axis + 2) % 3)];
          return 3 * u + v;
        };
        const int ka = drop(pa), kb = drop(pb);
        c.face_diagonals.push_back({axis * 81 + std::min(ka, kb) * 9 + std::max(ka, kb), face % 2});
      }
    c.num_normals = static_cast<int>(std::set<int>(c.normals.begin(), c.normals.end()).size());
    c.triangles = std::move(tri);
    out.push_back(std::move(c));
  }
  std::stable_sort(out.begin(), out.end(), [](const Candidate& x, const Candidate& y) {
    return std::make_pair(x.face_diagonals.size(), x.num_normals) < std::make_pair(y.face_diagonals.size(), y.num_normals);
  });
  return out;
}

// Depth-first search for a face-diagonal ownership (key -> side) under which
// every problem loop has a candidate; returns the chosen candidate indices.
bool assign_ownership(const std::vector<std::vector<Candidate>>& problems, std::size_t i, std::vector<int>& owner,
                      std::vector<int>& choice) {
  if (i == problems.size()) return true;
  for (std::size_t c = 0; c < problems[i].size(); ++c) {
    const auto& diagonals = problems[i][c].face_diagonals;
    bool fits = true;
    for (const FaceDiagonal& d : diagonals)
      if (owner[static_cast<std::size_t>(d.key)] >= 0 && owner[static_cast<std::size_t>(d.key)] != d.side) fits = false;
    if (!fits) continue;
    std::vector<int> added;
    for (const FaceDiagonal& d : diagonals)
      if (owner[static_cast<std::size_t>(d.key)] < 0) {
        owner[static_cast<std::size_t>(d.key)] = d.side;
        added.push_back(d.key);
      }
    choice[i] = static_cast<int>(c);
    if (assign_ownership(problems, i + 1, owner, choice)) return true;
    for (int k : added) owner[static_cast<std::size_t>(k)] = -1;
  }
  return false;
}

std::vector<std::vector<int>> case_loops(int config) {
  auto inside = [&](int c) { return ((config >> c) & 1) != 0; };
  std::array<int, 12> next;
  next.fill(-1);
  std::array<int, 12> num_in{};
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      Int3 f{0, 0, 0};
      f[static_cast<std::size_t>(axis)] = side ? 1 : -1;
      // Corners of the face in cyclic order, and the face edge between
      // consecutive ones.
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const int base = side << axis;
      const std::array<int, 4> ring{base, base | (1 << u), base | (1 << u) | (1 << v), base | (1 << v)};
      auto edge_between = [](int c0, int c1) {
        const auto& edges = cube_edges();
        for (int e = 0; e < 12; ++e) {
          const auto& ce = edges[static_cast<std::size_t>(e)];
          if ((ce.corners[0] == c0 && ce.corners[1] == c1) || (ce.corners[0] == c1 && ce.corners[1] == c0)) return e;
        }
        return -1;
      };
      // Groups of inside corners connected along the face's edges: each is a
      // run of consecutive inside corners on the ring.
      const int num_inside = inside(ring[0]) + inside(ring[1]) + inside(ring[2]) + inside(ring[3]);
      if (num_inside == 0 || num_inside == 4) continue;
      for (int r = 0; r < 4; ++r) {
        // A run starts at ring[r] when ring[r] is inside and ring[r-1] is not.
        if (!inside(ring[static_cast<std::size_t>(r)]) || inside(ring[static_cast<std::size_t>((r + 3) % 4)])) continue;
        int last = r;
        while (inside(ring[static_cast<std::size_t>((last + 1) % 4)])) last = (last + 1) % 4;
        int p = edge_between(ring[static_cast<std::size_t>((r + 3) % 4)], ring[static_cast<std::size_t>(r)]);
        int q = edge_between(ring[static_cast<std::size_t>(last)], ring[static_cast<std::size_t>((last + 1) % 4)]);
        // Orient p -> q so that (q - p) x f points to the inside corner of p.
        const Int3 pp = edge_midpoint2(p), qq = edge_midpoint2(q);
        const Int3 w = cross(sub(qq, pp), f);
        if (dot(w, sub(corner2(ring[static_cast<std::size_t>(r)]), pp)) < 0) std::swap(p, q);
        if (next[static_cast<std::size_t>(p)] != -1)
          throw AlgorithmError("marching-cubes table: edge with two outgoing segments");
        next[static_cast<std::size_t>(p)] = q;
        ++num_in[static_cast<std::size_t>(q)];
      }
    }
  std::vector<std::vector<int>> loops;
  std::array<bool, 12> used{};
  for (int e = 0; e < 12; ++e) {
    if (next[static_cast<std::size_t>(e)] < 0 || used[static_cast<std::size_t>(e)]) continue;
    std::vector<int> loop;
    for (int x = e; !used[static_cast<std::size_t>(x)]; x = next[static_cast<std::size_t>(x)]) {
      if (next[static_cast<std::size_t>(x)] < 0 || num_in[static_cast<std::size_t>(x)] != 1)
        throw AlgorithmError("marching-cubes table: segments do not close into loops");
      used[static_cast<std::size_t>(x)] = true;
      loop.push_back(x);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace

const std::array<CubeEdge, 12>& cube_edges() {
  static const auto kEdges = [] {
    std::array<CubeEdge, 12> edges{};
    std::size_t k = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (int c = 0; c < 8; ++c)
        if (((c >> axis) & 1) == 0) edges[k++] = CubeEdge{{c, c | (1 << axis)}, axis};
    return edges;
  }();
  return kEdges;
}

std::array<int, 3> edge_midpoint2(int e) {
  const CubeEdge& edge = cube_edges()[static_cast<std::size_t>(e)];
  Int3 p = corner2(edge.corners[0]);
  p[static_cast<std::size_t>(edge.axis)] += 1;
  return p;
}

const std::array<CubeCase, 256>& case_table() {
  static const auto kTable = [] {
    // Loops whose best candidate needs no face diagonal take it; the others
    // ("problem loops") share a face-diagonal ownership found by search.
    std::array<CubeCase, 256> table;
    std::vector<std::vector<Candidate>> problems;
    std::vector<int> problem_case;
    for (int config = 0; config < 256; ++config) {
      for (const auto& loop : case_loops(config)) {
        std::vector<Candidate> cands = admissible_triangulations(loop);
        if (cands.empty())
          throw AlgorithmError("marching-cubes table: no admissible triangulation for a loop of case " +
                               std::to_string(config));
        if (cands.front().face_diagonals.empty()) {
          auto& cc = table[static_cast<std::size_t>(config)];
          cc.triangles.insert(cc.triangles.end(), cands.front().triangles.begin(), cands.front().triangles.end());
          cc.normals.insert(cc.normals.end(), cands.front().normals.begin(), cands.front().normals.end());
        } else {
          problems.push_back(std::move(cands));
          problem_case.push_back(config);
        }
      }
    }
    std::vector<int> owner(3 * 81, -1), choice(problems.size(), -1);
    if (!assign_ownership(problems, 0, owner, choice))
      throw AlgorithmError("marching-cubes table: no consistent ownership of face diagonals");
    for (std::size_t i = 0; i < problems.size(); ++i) {
      const Candidate& c = problems[i][static_cast<std::size_t>(choice[i])];
      auto& cc = table[static_cast<std::size_t>(problem_case[i])];
      cc.triangles.insert(cc.triangles.end(), c.triangles.begin(), c.triangles.end());
      cc.normals.insert(cc.normals.end(), c.normals.begin(), c.normals.end());
    }
    return table;
  }();
  return kTable;
}

}  // namespace subfab::mc
