// SPDX-License-Identifier: GPL-3.0-or-later
//! \file unfold_nets.cpp
//! Cutting a polygonal mesh into nets and laying them flat without overlaps
//! (thesis Section 3.3.3; outline in subfab/unfold/unfold_nets.h), and the
//! exact overlap check of the result. The refolding check is in
//! refold_error.cpp.
#include "subfab/unfold/unfold_nets.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>
#include <unordered_map>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "unfold/edge_key.h"
#include "unfold/facet_unit_normal.h"
#include "unfold/polygons_overlap.h"

namespace subfab {

using unfold_detail::edge_key;
using unfold_detail::facet_unit_normal;
using unfold_detail::interiors_overlap;
using unfold_detail::Polygon2;
using unfold_detail::update_box;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct CornerRef {
  int facet, loop, index;
};

double polygon_area(const std::vector<std::vector<Vec2>>& loops) {
  double a = 0;
  for (const auto& l : loops)
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2& p = l[i];
      const Vec2& q = l[(i + 1) % l.size()];
      a += p.x() * q.y() - p.y() * q.x();
    }
  return 0.5 * a;
}

// Everything about the mesh the attempts share.
struct Context {
  const PolyMesh* mesh;
  std::unordered_map<std::uint64_t, CornerRef> edges;  // directed edge -> corner where it starts
  std::vector<std::vector<std::vector<Vec2>>> local;   // isometric 2D frame per facet
  std::vector<Vec3> normals;
  std::vector<double> areas;
  // candidate fold edges of each facet: (neighbour, u, v) with u -> v in the facet's loop
  std::vector<std::vector<std::tuple<int, int, int>>> adjacency;
};

Context make_context(const PolyMesh& mesh) {
  Context ctx;
  ctx.mesh = &mesh;
  const int nf = static_cast<int>(mesh.facets.size());
  for (int f = 0; f < nf; ++f)
    for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l) {
      const auto& loop = mesh.facets[f].loops[l];
      for (std::size_t i = 0; i < loop.size(); ++i)
        ctx.edges[edge_key(loop[i], loop[(i + 1) % loop.size()])] = {f, int(l), int(i)};
    }
  ctx.local.resize(nf);
  ctx.normals.resize(nf);
  ctx.areas.resize(nf);
  ctx.adjacency.resize(nf);
  for (int f = 0; f < nf; ++f) {
    const Facet& facet = mesh.facets[f];
    const Vec3 n = facet_unit_normal(mesh, f);
    ctx.normals[f] = n;
    const Vec3 o = mesh.vertices[facet.loops[0][0]];
    const Vec3 e1 = (mesh.vertices[facet.loops[0][1]] - o).normalized();
    const Vec3 e2 = n.cross(e1);
    for (const auto& loop : facet.loops) {
      std::vector<Vec2> pts;
      for (int v : loop) {
        const Vec3 d = mesh.vertices[v] - o;
        pts.emplace_back(d.dot(e1), d.dot(e2));
      }
      ctx.local[f].push_back(std::move(pts));
    }
    ctx.areas[f] = polygon_area(ctx.local[f]);
    for (const auto& loop : facet.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int u = loop[i], v = loop[(i + 1) % loop.size()];
        const auto it = ctx.edges.find(edge_key(v, u));
        if (it == ctx.edges.end())
          throw InvalidMeshError("polygonal mesh is not closed: edge " + std::to_string(u) + "-" + std::to_string(v) +
                                 " of facet " + std::to_string(f) + " has no opposite");
        if (it->second.facet != f) ctx.adjacency[f].emplace_back(it->second.facet, u, v);
      }
  }
  return ctx;
}

// A 2D rigid motion x -> R x + t.
struct Motion {
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  Vec2 t = Vec2::Zero();
  Vec2 operator()(const Vec2& x) const { return R * x + t; }
};

Motion align(const Vec2& from_a, const Vec2& from_b, const Vec2& to_a, const Vec2& to_b) {
  const Vec2 df = from_b - from_a, dt = to_b - to_a;
  const double angle = std::atan2(dt.y(), dt.x()) - std::atan2(df.y(), df.x());
  Motion m;
  m.R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  m.t = to_a - m.R * from_a;
  return m;
}

struct FoldEdge {
  int a, b, u, v;  // u -> v in a's loop
};

struct Layout {
  std::vector<Polygon2> polys;  // per facet, placed
  std::vector<int> net_of;
  std::vector<FoldEdge> folds;
  int num_nets = 0;
  std::vector<double> net_area;
  std::vector<int> net_root;
};

enum class Strategy { LongestEdge, NormalOrder, Breadth };

class Grower {
 public:
  Grower(const Context& ctx, Strategy strategy) : ctx_(ctx), strategy_(strategy) {}

  Layout run(int first_root, bool merge) {
    const int nf = static_cast<int>(ctx_.local.size());
    layout_.polys.assign(nf, {});
    layout_.net_of.assign(nf, -1);
    std::vector<int> order(nf);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return ctx_.areas[x] > ctx_.areas[y]; });
    grow(first_root);
    for (int f : order)
      if (layout_.net_of[f] < 0) grow(f);
    if (merge) merge_small_nets();
    return std::move(layout_);
  }

 private:
  // Places facet c from parent p across the edge u -> v of p.
  Polygon2 place(int p, int c, int u, int v) const {
    const CornerRef pu = ctx_.edges.at(edge_key(u, v));  // corner u in p
    const CornerRef cv = ctx_.edges.at(edge_key(v, u));  // corner v in c (edge v -> u)
    const auto& ploop = layout_.polys[p].loops[pu.loop];
    const Vec2 P_u = ploop[pu.index];
    const Vec2 P_v = ploop[(pu.index + 1) % ploop.size()];
    const auto& cloop = ctx_.local[c][cv.loop];
    const int cu_index = (cv.index + 1) % static_cast<int>(cloop.size());
    const Motion m = align(cloop[cu_index], cloop[cv.index], P_u, P_v);
    Polygon2 poly;
    for (const auto& loop : ctx_.local[c]) {
      std::vector<Vec2> pts;
      for (const auto& x : loop) pts.push_back(m(x));
      poly.loops.push_back(std::move(pts));
    }
    poly.loops[cv.loop][cv.index] = P_v;
    poly.loops[cv.loop][cu_index] = P_u;
    update_box(poly);
    (void)c;
    return poly;
  }

  bool fits(const Polygon2& poly, int net, int except) const {
    for (int g : members_[net])
      if (g != except && interiors_overlap(poly, layout_.polys[g])) return false;
    return true;
  }

  double priority(int p, int c, int u, int v, int depth) const {
    const double len = (ctx_.mesh->vertices[u] - ctx_.mesh->vertices[v]).norm();
    switch (strategy_) {
      case Strategy::LongestEdge:
        return len;
      case Strategy::NormalOrder:
        return ctx_.normals[c].dot(root_normal_) + 1e-6 * len;
      case Strategy::Breadth:
        return -depth + 1e-6 * len;
    }
    return len;
  }

  void grow(int root) {
    const int net = layout_.num_nets++;
    members_.emplace_back();
    layout_.net_root.push_back(root);
    layout_.net_area.push_back(0);
    root_normal_ = ctx_.normals[root];
    Polygon2 poly;
    poly.loops = ctx_.local[root];
    update_box(poly);
    // translate so nets do not start on top of each other (layout is later)
    layout_.polys[root] = poly;
    add(root, net);
    std::vector<int> depth(ctx_.local.size(), 0);
    using Item = std::tuple<double, int, int, int, int>;  // priority, -child, -u, parent, v
    std::priority_queue<Item> queue;
    auto push_edges = [&](int f) {
      for (const auto& [g, u, v] : ctx_.adjacency[f])
        if (layout_.net_of[g] < 0) queue.emplace(priority(f, g, u, v, depth[f] + 1), -g, -u, f, v);
    };
    push_edges(root);
    while (!queue.empty()) {
      const auto [pr, neg_c, neg_u, p, v] = queue.top();
      queue.pop();
      const int c = -neg_c, u = -neg_u;
      if (layout_.net_of[c] >= 0) continue;
      Polygon2 placed = place(p, c, u, v);
      if (!fits(placed, net, -1)) continue;
      layout_.polys[c] = std::move(placed);
      layout_.folds.push_back({p, c, u, v});
      depth[c] = depth[p] + 1;
      add(c, net);
      push_edges(c);
    }
  }

  void add(int f, int net) {
    layout_.net_of[f] = net;
    members_[net].push_back(f);
    layout_.net_area[net] += ctx_.areas[f];
  }

  // Re-attaches whole small nets to other nets across a shared edge.
  void merge_small_nets() {
    bool changed = true;
    while (changed) {
      changed = false;
      std::vector<int> nets;
      for (int n = 0; n < layout_.num_nets; ++n)
        if (!members_[n].empty()) nets.push_back(n);
      std::stable_sort(nets.begin(), nets.end(),
                       [&](int x, int y) { return layout_.net_area[x] < layout_.net_area[y]; });
      for (int s : nets) {
        if (try_attach(s)) {
          changed = true;
          break;
        }
      }
    }
    // compact net ids
    std::vector<int> remap(layout_.num_nets, -1);
    int next = 0;
    std::vector<double> area;
    std::vector<int> roots;
    for (int n = 0; n < layout_.num_nets; ++n)
      if (!members_[n].empty()) {
        remap[n] = next++;
        area.push_back(layout_.net_area[n]);
        roots.push_back(layout_.net_root[n]);
      }
    for (int& n : layout_.net_of) n = remap[n];
    layout_.num_nets = next;
    layout_.net_area = area;
    layout_.net_root = roots;
  }

  bool try_attach(int s) {
    // candidate edges: (facet in s, facet elsewhere), largest target net first
    std::vector<std::tuple<double, int, int, int, int>> cands;  // -target area, t, sf, u, v (u->v in t)
    for (int sf : members_[s])
      for (const auto& [t, v, u] : ctx_.adjacency[sf]) {  // v -> u in sf, so u -> v in t
        const int tn = layout_.net_of[t];
        if (tn == s) continue;
        cands.emplace_back(-layout_.net_area[tn], t, sf, u, v);
      }
    std::sort(cands.begin(), cands.end());
    for (const auto& [neg_area, t, sf, u, v] : cands) {
      const int tn = layout_.net_of[t];
      // motion taking sf's copy of the edge onto t's copy
      const CornerRef tu = ctx_.edges.at(edge_key(u, v));
      const CornerRef sv = ctx_.edges.at(edge_key(v, u));
      const auto& tl = layout_.polys[t].loops[tu.loop];
      const Vec2 T_u = tl[tu.index], T_v = tl[(tu.index + 1) % tl.size()];
      const auto& sl = layout_.polys[sf].loops[sv.loop];
      const Vec2 S_v = sl[sv.index], S_u = sl[(sv.index + 1) % sl.size()];
      const Motion m = align(S_u, S_v, T_u, T_v);
      std::vector<Polygon2> moved;
      bool ok = true;
      for (int f : members_[s]) {
        Polygon2 p;
        for (const auto& loop : layout_.polys[f].loops) {
          std::vector<Vec2> pts;
          for (const auto& x : loop) pts.push_back(x == S_u ? T_u : (x == S_v ? T_v : m(x)));
          p.loops.push_back(std::move(pts));
        }
        update_box(p);
        if (!fits(p, tn, -1)) {
          ok = false;
          break;
        }
        moved.push_back(std::move(p));
      }
      // the moved net must still be overlap-free in itself (rounding of the motion)
      for (std::size_t i = 0; ok && i < moved.size(); ++i)
        for (std::size_t k = i + 1; ok && k < moved.size(); ++k)
          if (interiors_overlap(moved[i], moved[k])) ok = false;
      if (!ok) continue;
      for (std::size_t i = 0; i < members_[s].size(); ++i) layout_.polys[members_[s][i]] = std::move(moved[i]);
      layout_.folds.push_back({t, sf, u, v});
      for (int f : members_[s]) {
        layout_.net_of[f] = tn;
        members_[tn].push_back(f);
      }
      layout_.net_area[tn] += layout_.net_area[s];
      layout_.net_area[s] = 0;
      members_[s].clear();
      return true;
    }
    return false;
  }

  const Context& ctx_;
  Strategy strategy_;
  Layout layout_;
  std::vector<std::vector<int>> members_;
  Vec3 root_normal_ = Vec3::UnitZ();
};

}  // namespace

double dihedral_angle_deg(const PolyMesh& mesh, int a, int b, int v0, int v1) {
  const Vec3 na = facet_unit_normal(mesh, a), nb = facet_unit_normal(mesh, b);
  const double angle = std::atan2(na.cross(nb).norm(), na.dot(nb)) * 180.0 / kPi;
  const bool convex = na.cross(nb).dot(mesh.vertices[v1] - mesh.vertices[v0]) > 0;
  return convex ? 180.0 - angle : 180.0 + angle;
}

Unfolding unfold_nets(const PolyMesh& mesh, const UnfoldNetsOptions& options) {
  StageScope scope(options.progress, "unfold");
  Unfolding out;
  const int nf = static_cast<int>(mesh.facets.size());
  if (nf == 0) return out;
  const Context ctx = make_context(mesh);
  std::vector<int> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return ctx.areas[x] > ctx.areas[y]; });
  const int num_roots = std::max(1, std::min(options.num_roots, nf));
  const Strategy strategies[] = {Strategy::LongestEdge, Strategy::NormalOrder, Strategy::Breadth};
  const std::size_t num_attempts = static_cast<std::size_t>(num_roots) * 3;
  std::vector<Layout> layouts(num_attempts);
  parallel_for(0, num_attempts, [&](std::size_t i) {
    Grower g(ctx, strategies[i % 3]);
    layouts[i] = g.run(order[i / 3], options.merge_small_nets);
  });
  std::size_t best = 0;
  auto score = [&](const Layout& l) {
    return std::make_pair(l.num_nets, -*std::max_element(l.net_area.begin(), l.net_area.end()));
  };
  for (std::size_t i = 1; i < num_attempts; ++i)
    if (score(layouts[i]) < score(layouts[best])) best = i;
  Layout& layout = layouts[best];
  if (options.progress)
    options.progress->info(std::to_string(layout.num_nets) + " nets (best of " + std::to_string(num_attempts) +
                           " attempts)");

  // Trees: breadth-first from each net's root over its fold edges.
  out.positions.resize(nf);
  for (int f = 0; f < nf; ++f) out.positions[f] = layout.polys[f].loops;
  out.net_of_facet = layout.net_of;
  out.parent_fold.assign(nf, -1);
  std::vector<std::vector<std::pair<int, int>>> fold_adj(nf);  // facet -> (fold edge index, other facet)
  for (std::size_t i = 0; i < layout.folds.size(); ++i) {
    fold_adj[layout.folds[i].a].emplace_back(int(i), layout.folds[i].b);
    fold_adj[layout.folds[i].b].emplace_back(int(i), layout.folds[i].a);
  }
  out.nets.resize(layout.num_nets);
  std::vector<char> seen(nf, 0);
  for (int n = 0; n < layout.num_nets; ++n) {
    Net& net = out.nets[n];
    net.root = layout.net_root[n];
    net.area = layout.net_area[n];
    std::vector<int> queue{net.root};
    seen[net.root] = 1;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      net.facets.push_back(f);
      for (const auto& [ei, g] : fold_adj[f]) {
        if (seen[g]) continue;
        seen[g] = 1;
        const FoldEdge& e = layout.folds[ei];
        Fold fold;
        fold.parent = f;
        fold.child = g;
        // edge direction in the parent's loop
        if (e.a == f) {
          fold.v0 = e.u;
          fold.v1 = e.v;
        } else {
          fold.v0 = e.v;
          fold.v1 = e.u;
        }
        fold.dihedral_deg = dihedral_angle_deg(mesh, f, g, fold.v0, fold.v1);
        out.parent_fold[g] = static_cast<int>(out.folds.size());
        out.folds.push_back(fold);
        queue.push_back(g);
      }
    }
  }
  return out;
}

std::string find_net_overlap(const Unfolding& unfolding) {
  std::vector<Polygon2> polys(unfolding.positions.size());
  for (std::size_t f = 0; f < polys.size(); ++f) {
    polys[f].loops = unfolding.positions[f];
    update_box(polys[f]);
  }
  for (const Net& net : unfolding.nets)
    for (std::size_t i = 0; i < net.facets.size(); ++i)
      for (std::size_t j = i + 1; j < net.facets.size(); ++j)
        if (interiors_overlap(polys[net.facets[i]], polys[net.facets[j]]))
          return "facets " + std::to_string(net.facets[i]) + " and " + std::to_string(net.facets[j]) +
                 " overlap in their net";
  return "";
}

}  // namespace subfab
