// SPDX-License-Identifier: GPL-3.0-or-later
// Conflict graph, cycle splitting and carving order (thesis Section 4.3.3).
#include "order_boxes.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {

std::vector<Box3> box_difference(const Box3& b, const Box3& cut, const std::array<int, 3>& dims) {
  if (!b.overlaps(cut)) return {b};
  std::vector<Box3> pieces;
  Box3 rest = b;
  for (int dim : dims) {
    if (rest.min[dim] < cut.min[dim]) {
      Box3 piece = rest;
      piece.max[dim] = cut.min[dim];
      pieces.push_back(piece);
      rest.min[dim] = cut.min[dim];
    }
    if (rest.max[dim] > cut.max[dim]) {
      Box3 piece = rest;
      piece.min[dim] = cut.max[dim];
      pieces.push_back(piece);
      rest.max[dim] = cut.max[dim];
    }
  }
  return pieces;  // `rest` is now b ∩ cut: left out
}

std::optional<Box3> conflict_region(const HeightBox& first, const HeightBox& second) {
  const Box3& b1 = first.box;
  const Box3& b2 = second.box;
  if (!b1.overlaps(b2)) return std::nullopt;
  const int k = axis_dimension(second.axis);
  Box3 region;
  for (int c = 0; c < 3; ++c) {
    region.min[c] = std::max(b1.min[c], b2.min[c]);
    region.max[c] = std::min(b1.max[c], b2.max[c]);
  }
  if (axis_sign(second.axis) > 0) {
    // first's top w.r.t. +e_k is b1.max[k]; material of `second` above it.
    if (!(b2.min[k] < b1.max[k] && b1.max[k] < b2.max[k])) return std::nullopt;
    region.min[k] = b1.max[k];
    region.max[k] = b2.max[k];
  } else {
    if (!(b2.min[k] < b1.min[k] && b1.min[k] < b2.max[k])) return std::nullopt;
    region.min[k] = b2.min[k];
    region.max[k] = b1.min[k];
  }
  return region;
}

std::vector<Box3> conflict_support(const HeightBox& first, const HeightBox& second) {
  if (!conflict_region(first, second)) return {};
  const int k = axis_dimension(second.axis);
  Box3 lower = second.box;
  if (axis_sign(second.axis) > 0)
    lower.max[k] = first.box.max[k];
  else
    lower.min[k] = first.box.min[k];
  return box_difference(lower, first.box, {0, 1, 2});
}

std::vector<int> strongly_connected_components(const std::vector<std::vector<int>>& out,
                                               const std::vector<char>& alive) {
  const std::size_t n = out.size();
  std::vector<int> index(n, -1), low(n, 0), comp(n, -1);
  std::vector<char> on_stack(n, 0);
  std::vector<int> stack;
  std::vector<std::pair<int, std::size_t>> calls;  // (vertex, next neighbour position)
  int counter = 0, num_comps = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (!alive[s] || index[s] >= 0) continue;
    auto open = [&](int v) {
      index[static_cast<std::size_t>(v)] = low[static_cast<std::size_t>(v)] = counter++;
      stack.push_back(v);
      on_stack[static_cast<std::size_t>(v)] = 1;
      calls.emplace_back(v, 0);
    };
    open(static_cast<int>(s));
    while (!calls.empty()) {
      auto& [v, pos] = calls.back();
      const auto vi = static_cast<std::size_t>(v);
      if (pos < out[vi].size()) {
        const int w = out[vi][pos++];
        const auto wi = static_cast<std::size_t>(w);
        if (!alive[wi]) continue;
        if (index[wi] < 0) {
          open(w);  // invalidates v/pos references: loop again
        } else if (on_stack[wi]) {
          low[vi] = std::min(low[vi], index[wi]);
        }
        continue;
      }
      const int done = v;
      calls.pop_back();
      const auto di = static_cast<std::size_t>(done);
      if (low[di] == index[di]) {
        for (;;) {
          const int w = stack.back();
          stack.pop_back();
          on_stack[static_cast<std::size_t>(w)] = 0;
          comp[static_cast<std::size_t>(w)] = num_comps;
          if (w == done) break;
        }
        ++num_comps;
      }
      if (!calls.empty()) {
        const auto ui = static_cast<std::size_t>(calls.back().first);
        low[ui] = std::min(low[ui], low[di]);
      }
    }
  }
  return comp;
}

namespace {

constexpr std::array<std::array<int, 3>, 6> kCutOrders = {
    {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};

//! The conflict graph over a growing list of boxes (dead ones stay, flagged).
class ConflictGraph {
 public:
  ConflictGraph(std::vector<HeightBox> boxes, const BoxOrderCallbacks& callbacks)
      : callbacks_(callbacks), boxes_(std::move(boxes)) {
    const std::size_t n = boxes_.size();
    alive_.assign(n, 1);
    out_.assign(n, {});
    in_.assign(n, {});
    std::vector<std::pair<int, int>> pairs;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (boxes_[i].box.overlaps(boxes_[j].box)) pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
    add_edges_for_pairs(pairs);
  }

  std::size_t num_vertices() const { return boxes_.size(); }
  bool alive(int v) const { return alive_[static_cast<std::size_t>(v)] != 0; }
  const HeightBox& box(int v) const { return boxes_[static_cast<std::size_t>(v)]; }
  const std::set<int>& out(int v) const { return out_[static_cast<std::size_t>(v)]; }
  const std::set<int>& in(int v) const { return in_[static_cast<std::size_t>(v)]; }

  std::size_t num_edges() const {
    std::size_t e = 0;
    for (std::size_t v = 0; v < out_.size(); ++v)
      if (alive_[v]) e += out_[v].size();
    return e;
  }

  std::vector<int> components() const {
    std::vector<std::vector<int>> adj(out_.size());
    for (std::size_t v = 0; v < out_.size(); ++v) adj[v].assign(out_[v].begin(), out_[v].end());
    return strongly_connected_components(adj, alive_);
  }

  //! Replaces vertex v by boxes `pieces` (sub-boxes of v's box) and computes
  //! their edges against the live boxes that overlapped v.
  void replace(int v, const std::vector<HeightBox>& pieces) {
    const auto vi = static_cast<std::size_t>(v);
    std::vector<int> neighbours;
    for (std::size_t u = 0; u < boxes_.size(); ++u)
      if (alive_[u] && u != vi && boxes_[u].box.overlaps(boxes_[vi].box)) neighbours.push_back(static_cast<int>(u));
    for (int u : out_[vi]) in_[static_cast<std::size_t>(u)].erase(v);
    for (int u : in_[vi]) out_[static_cast<std::size_t>(u)].erase(v);
    out_[vi].clear();
    in_[vi].clear();
    alive_[vi] = 0;
    std::vector<std::pair<int, int>> pairs;
    for (const HeightBox& piece : pieces) {
      const int p = static_cast<int>(boxes_.size());
      boxes_.push_back(piece);
      alive_.push_back(1);
      out_.emplace_back();
      in_.emplace_back();
      for (int u : neighbours)
        if (boxes_[static_cast<std::size_t>(u)].box.overlaps(piece.box)) pairs.emplace_back(u, p);
    }
    add_edges_for_pairs(pairs);
  }

 private:
  //! Tests both directions of every pair (in parallel) and adds the edges in
  //! pair order (deterministic).
  void add_edges_for_pairs(const std::vector<std::pair<int, int>>& pairs) {
    std::vector<std::array<char, 2>> result(pairs.size());
    parallel_for(0, pairs.size(), [&](std::size_t k) {
      const HeightBox& a = boxes_[static_cast<std::size_t>(pairs[k].first)];
      const HeightBox& b = boxes_[static_cast<std::size_t>(pairs[k].second)];
      result[k] = {static_cast<char>(callbacks_.conflict(a, b)), static_cast<char>(callbacks_.conflict(b, a))};
    });
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const auto [a, b] = pairs[k];
      if (result[k][0]) add_edge(a, b);
      if (result[k][1]) add_edge(b, a);
    }
  }
  void add_edge(int a, int b) {
    out_[static_cast<std::size_t>(a)].insert(b);
    in_[static_cast<std::size_t>(b)].insert(a);
  }

  const BoxOrderCallbacks& callbacks_;
  std::vector<HeightBox> boxes_;
  std::vector<char> alive_;
  std::vector<std::set<int>> out_, in_;
};

//! A shortest cycle through s inside component `comp_id` (vertex list
//! s, v1, ..., vk with edges s->v1->...->vk->s).
std::vector<int> shortest_cycle_through(const ConflictGraph& g, const std::vector<int>& comp, int s) {
  const int comp_id = comp[static_cast<std::size_t>(s)];
  std::vector<int> parent(g.num_vertices(), -2);
  std::queue<int> queue;
  queue.push(s);
  parent[static_cast<std::size_t>(s)] = -1;
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop();
    if (g.out(v).count(s)) {
      std::vector<int> cycle;
      for (int u = v; u != -1; u = parent[static_cast<std::size_t>(u)]) cycle.push_back(u);
      std::reverse(cycle.begin(), cycle.end());
      return cycle;
    }
    for (int w : g.out(v)) {
      const auto wi = static_cast<std::size_t>(w);
      if (comp[wi] != comp_id || parent[wi] != -2) continue;
      parent[wi] = v;
      queue.push(w);
    }
  }
  throw AlgorithmError("overlap resolution: internal error, no cycle through box " + std::to_string(s) +
                       " of its strongly connected component");
}

struct SplitChoice {
  int head = -1;              // the box that is split (b of edge a -> b)
  std::vector<Box3> kept;     // its kept pieces
  int num_dropped = 0;
  double score = -1;          // size of the smallest kept piece (+inf if none)
};

}  // namespace

BoxOrderResult order_boxes(std::vector<HeightBox> boxes, const BoxOrderCallbacks& callbacks,
                           const BoxOrderOptions& options) {
  BoxOrderResult result;
  ConflictGraph graph(std::move(boxes), callbacks);
  result.num_initial_edges = graph.num_edges();

  // Within one split decision the live boxes do not change: cache answers.
  std::map<std::tuple<double, double, double, double, double, double, int>, bool> droppable_cache;
  auto is_droppable = [&](const HeightBox& piece, int parent_id) {
    if (!callbacks.droppable) return false;
    const HeightBox& parent = graph.box(parent_id);
    const auto key = std::make_tuple(piece.box.min.x(), piece.box.min.y(), piece.box.min.z(), piece.box.max.x(),
                                     piece.box.max.y(), piece.box.max.z(), parent_id);
    auto it = droppable_cache.find(key);
    if (it == droppable_cache.end()) it = droppable_cache.emplace(key, callbacks.droppable(piece, parent)).first;
    return it->second;
  };

  const int max_trims = options.max_trims >= 0 ? options.max_trims : 4 * static_cast<int>(graph.num_vertices());
  for (bool first_pass = true;; first_pass = false) {
    const std::vector<int> comp = graph.components();
    // Component sizes; the non-trivial component with the smallest vertex.
    std::vector<int> comp_size(graph.num_vertices() + 1, 0);
    for (std::size_t v = 0; v < comp.size(); ++v)
      if (comp[v] >= 0) ++comp_size[static_cast<std::size_t>(comp[v])];
    int s = -1;
    std::size_t num_cyclic = 0;
    for (std::size_t v = 0; v < comp.size(); ++v)
      if (comp[v] >= 0 && comp_size[static_cast<std::size_t>(comp[v])] > 1) {
        ++num_cyclic;
        if (s < 0) s = static_cast<int>(v);
      }
    if (first_pass) result.num_initial_cyclic = num_cyclic;
    if (s < 0) break;
    if (result.num_splits >= options.max_splits)
      throw AlgorithmError("overlap resolution: the conflict graph still has cycles after " +
                           std::to_string(result.num_splits) + " splits (" + std::to_string(num_cyclic) +
                           " boxes on cycles); raise the split limit or report this model");

    const std::vector<int> cycle = shortest_cycle_through(graph, comp, s);
    if (callbacks.trims && result.num_trims < max_trims) {
      int best_vertex = -1;
      BoxTrim best_trim;
      for (std::size_t k = 0; k < cycle.size(); ++k) {
        const int a = cycle[k];
        const int b = cycle[(k + 1) % cycle.size()];
        for (const BoxTrim& t : callbacks.trims(graph.box(a), graph.box(b)))
          if (best_vertex < 0 || t.removed < best_trim.removed) {
            best_vertex = t.which == 0 ? a : b;
            best_trim = t;
          }
      }
      if (best_vertex >= 0) {
        const HeightBox trimmed{best_trim.box, graph.box(best_vertex).axis, graph.box(best_vertex).seed_face};
        if (callbacks.replaced) callbacks.replaced(graph.box(best_vertex), {trimmed});
        graph.replace(best_vertex, {trimmed});
        ++result.num_trims;
        continue;
      }
    }
    SplitChoice best;
    for (std::size_t k = 0; k < cycle.size(); ++k) {
      const int a = cycle[k];
      const int b = cycle[(k + 1) % cycle.size()];
      const HeightBox& head = graph.box(b);
      for (const auto& dims : kCutOrders) {
        SplitChoice cand;
        cand.head = b;
        cand.score = std::numeric_limits<double>::infinity();
        for (const Box3& piece : box_difference(head.box, graph.box(a).box, dims)) {
          const HeightBox hp{piece, head.axis, -1};
          if (is_droppable(hp, b)) {
            ++cand.num_dropped;
            continue;
          }
          cand.score = std::min(cand.score, callbacks.size(hp));
          cand.kept.push_back(piece);
        }
        // Fewest new boxes first (measured on the bundled models: 10-20%
        // fewer final boxes than ranking by size first), then the largest
        // smallest piece (thesis 4.3.3), then the earlier candidate.
        const bool better = best.head < 0 || cand.kept.size() < best.kept.size() ||
                            (cand.kept.size() == best.kept.size() && cand.score > best.score);
        if (better) best = std::move(cand);
      }
    }
    result.num_dropped_pieces += best.num_dropped;
    droppable_cache.clear();
    std::vector<HeightBox> kept;
    for (const Box3& piece : best.kept) kept.push_back(HeightBox{piece, graph.box(best.head).axis, -1});
    if (callbacks.replaced) callbacks.replaced(graph.box(best.head), kept);
    graph.replace(best.head, kept);
    ++result.num_splits;
  }

  // Kahn's algorithm on the reversed graph: v is ready once every box it
  // points to (which must be carved before it) is out.
  const std::size_t n = graph.num_vertices();
  std::vector<std::size_t> waiting(n, 0);
  std::vector<double> size(n, 0.0);
  using Ready = std::pair<double, int>;
  std::priority_queue<Ready, std::vector<Ready>, std::greater<>> ready;
  std::size_t num_alive = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!graph.alive(static_cast<int>(v))) continue;
    ++num_alive;
    size[v] = callbacks.size(graph.box(static_cast<int>(v)));
    waiting[v] = graph.out(static_cast<int>(v)).size();
    if (waiting[v] == 0) ready.emplace(size[v], static_cast<int>(v));
  }
  result.num_final_edges = graph.num_edges();
  while (!ready.empty()) {
    const int v = ready.top().second;
    ready.pop();
    result.ordered.push_back(graph.box(v));
    for (int u : graph.in(v)) {
      const auto ui = static_cast<std::size_t>(u);
      if (--waiting[ui] == 0) ready.emplace(size[ui], u);
    }
  }
  if (result.ordered.size() != num_alive)
    throw AlgorithmError("overlap resolution: internal error, the conflict graph is not acyclic after splitting");
  return result;
}

}  // namespace subfab::detail
