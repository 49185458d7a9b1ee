// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/control_resolution.h"

#include <coin/CbcModel.hpp>
#include <coin/CoinMessageHandler.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <coin/OsiClpSolverInterface.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>

#include "hex/cone_template.h"
#include "hex/hex_splitter.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

constexpr int kOppositeFace[6] = {1, 0, 4, 5, 2, 3};  // kHexFaces pairs (0,1), (2,4), (3,5)

//! Face adjacency: for each hexahedron and face, the other hexahedron
//! sharing it (-1 on the boundary) and that face's index in it.
struct FaceAdjacency {
  std::vector<std::array<int, 6>> hex;
  std::vector<std::array<int, 6>> face;
};

FaceAdjacency face_adjacency(const HexMesh& mesh) {
  FaceAdjacency adj;
  adj.hex.assign(mesh.hexes.size(), {-1, -1, -1, -1, -1, -1});
  adj.face.assign(mesh.hexes.size(), {-1, -1, -1, -1, -1, -1});
  std::map<std::array<int, 4>, std::pair<int, int>> open;
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h)
    for (int f = 0; f < 6; ++f) {
      Quad q = hex_face(mesh.hexes[h], f);
      std::sort(q.begin(), q.end());
      const auto [it, inserted] = open.emplace(q, std::make_pair(static_cast<int>(h), f));
      if (inserted) continue;
      const auto [h2, f2] = it->second;
      adj.hex[h][idx(f)] = h2, adj.face[h][idx(f)] = f2;
      adj.hex[idx(h2)][idx(f2)] = static_cast<int>(h), adj.face[idx(h2)][idx(f2)] = f;
    }
  return adj;
}

double quad_area(const HexMesh& m, const Quad& q) {
  const auto& p = m.vertices;
  return 0.5 * (p[idx(q[2])] - p[idx(q[0])]).cross(p[idx(q[3])] - p[idx(q[1])]).norm();
}

//! The face of h (index) whose vertex set is {a, b, c, d}; -1 if none.
int find_face(const Hex& h, std::array<int, 4> set) {
  std::sort(set.begin(), set.end());
  for (int f = 0; f < 6; ++f) {
    Quad q = hex_face(h, f);
    std::sort(q.begin(), q.end());
    if (q == set) return f;
  }
  return -1;
}

//! In h, the corner joined by an edge to corner vertex v of face f that is
//! not on f (its partner on the opposite face).
int partner(const Hex& h, int f, int v) {
  static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                        {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  const Quad q = hex_face(h, f);
  auto on_face = [&](int w) { return std::find(q.begin(), q.end(), w) != q.end(); };
  for (const auto& e : kEdges) {
    const int a = h[idx(e[0])], b = h[idx(e[1])];
    if (a == v && !on_face(b)) return b;
    if (b == v && !on_face(a)) return a;
  }
  return -1;
}

class SilentHandler : public CoinMessageHandler {
 public:
  CoinMessageHandler* clone() const override { return new SilentHandler(*this); }
  int print() override { return 0; }
};

}  // namespace

std::vector<Cone> detect_cones(const TubularStructure& structure, const Skeleton& skeleton,
                               const ResolutionControlOptions& options) {
  const HexMesh& m = structure.mesh;
  if (structure.hex_arc.size() != m.hexes.size())
    throw InvalidArgumentError("detect_cones: " + std::to_string(structure.hex_arc.size()) + " arc labels for " +
                               std::to_string(m.hexes.size()) + " hexahedra");
  const auto arcs = skeleton_arcs(skeleton);
  std::vector<bool> terminal(arcs.size(), false);
  for (std::size_t a = 0; a < arcs.size(); ++a) {
    const auto& n = arcs[a].nodes;
    terminal[a] = !arcs[a].closed && (skeleton.neighbors[idx(n.front())].size() == 1 ||
                                      skeleton.neighbors[idx(n.back())].size() == 1);
  }
  const FaceAdjacency adj = face_adjacency(m);
  // candidates per arc: the tube hexahedra whose neighbours' opposite facets differ enough
  std::map<int, std::vector<Cone>> per_arc;
  for (std::size_t h = 0; h < m.hexes.size(); ++h) {
    const int a = structure.hex_arc[h];
    if (a < 0 || idx(a) >= arcs.size() || !terminal[idx(a)]) continue;
    const int p = adj.hex[h][0], n = adj.hex[h][1];  // tube convention: face 0 towards the previous section
    if (p < 0 || n < 0) continue;
    const double ap = quad_area(m, hex_face(m.hexes[idx(p)], kOppositeFace[adj.face[h][0]]));
    const double an = quad_area(m, hex_face(m.hexes[idx(n)], kOppositeFace[adj.face[h][1]]));
    if (!(std::min(ap, an) > 0)) continue;
    const double ratio = std::max(ap, an) / std::min(ap, an);
    if (ratio > options.cone_ratio) per_arc[a].push_back({static_cast<int>(h), a, ratio, an > ap});
  }
  std::vector<Cone> cones;
  for (auto& [arc, list] : per_arc) {
    std::sort(list.begin(), list.end(), [](const Cone& x, const Cone& y) {
      return x.ratio > y.ratio || (x.ratio == y.ratio && x.hex < y.hex);
    });
    std::vector<int> chosen;
    for (const Cone& c : list) {
      if (static_cast<int>(chosen.size()) >= options.max_cones_per_branch) break;
      const bool touches = std::any_of(chosen.begin(), chosen.end(), [&](int o) {
        return adj.hex[idx(o)][0] == c.hex || adj.hex[idx(o)][1] == c.hex;
      });
      if (touches) continue;  // two cones side by side would leave no regular layer between them
      chosen.push_back(c.hex);
      cones.push_back(c);
    }
  }
  std::sort(cones.begin(), cones.end(), [](const Cone& x, const Cone& y) { return x.hex < y.hex; });
  return cones;
}

ResolutionPlan control_resolution(const HexMesh& padded, const std::vector<Cone>& cones,
                                  const ResolutionControlOptions& options) {
  ResolutionPlan plan;
  const std::size_t n = padded.hexes.size();
  plan.num_cones_found = cones.size();
  plan.splits.assign(n, 0);
  plan.layer_of.assign(n, -1);
  const FaceAdjacency adj = face_adjacency(padded);
  // the layers
  for (const Cone& cone : cones) {
    if (cone.hex < 0 || idx(cone.hex) >= n)
      throw InvalidArgumentError("control_resolution: cone hexahedron " + std::to_string(cone.hex) + " out of range");
    const Hex& h = padded.hexes[idx(cone.hex)];
    ConeLayer L;
    L.hexes[0] = cone.hex;
    for (std::size_t i = 0; i < 4; ++i) {
      L.tip[i] = cone.base_at_front ? h[i] : h[i + 4];
      L.base[i] = cone.base_at_front ? h[i + 4] : h[i];
    }
    for (std::size_t i = 0; i < 4; ++i) {
      const std::size_t j = (i + 1) % 4;
      const int f = find_face(h, {L.tip[i], L.tip[j], L.base[j], L.base[i]});
      const int r = f < 0 ? -1 : adj.hex[idx(cone.hex)][idx(f)];
      if (r < 0)
        throw InvalidArgumentError("control_resolution: cone hexahedron " + std::to_string(cone.hex) +
                                   " has a side without a padding hexahedron");
      L.hexes[i + 1] = r;
      const Hex& R = padded.hexes[idx(r)];
      const int inner = adj.face[idx(cone.hex)][idx(f)];
      L.outer_tip[i] = partner(R, inner, L.tip[i]);
      L.outer_base[i] = partner(R, inner, L.base[i]);
    }
    for (int k : L.hexes)
      if (plan.layer_of[idx(k)] >= 0)
        throw InvalidArgumentError("control_resolution: two cones share hexahedron " + std::to_string(k));
    for (int k : L.hexes) plan.layer_of[idx(k)] = static_cast<int>(plan.layers.size());
    plan.layers.push_back(L);
  }
  // tip and base neighbours of each layer hexahedron: across its faces that
  // hold only tip (base) vertices of the layer
  std::vector<std::pair<int, int>> steps;  // (tip neighbour, base neighbour)
  for (const ConeLayer& L : plan.layers) {
    std::vector<int> tip_side(L.tip.begin(), L.tip.end()), base_side(L.base.begin(), L.base.end());
    tip_side.insert(tip_side.end(), L.outer_tip.begin(), L.outer_tip.end());
    base_side.insert(base_side.end(), L.outer_base.begin(), L.outer_base.end());
    for (int k : L.hexes) {
      int t = -1, b = -1;
      for (int f = 0; f < 6; ++f) {
        const Quad q = hex_face(padded.hexes[idx(k)], f);
        auto all_in = [&](const std::vector<int>& s) {
          return std::all_of(q.begin(), q.end(), [&](int v) { return std::find(s.begin(), s.end(), v) != s.end(); });
        };
        if (all_in(tip_side)) t = adj.hex[idx(k)][idx(f)];
        if (all_in(base_side)) b = adj.hex[idx(k)][idx(f)];
      }
      if (t < 0 || b < 0 || plan.layer_of[idx(t)] >= 0 || plan.layer_of[idx(b)] >= 0)
        throw InvalidArgumentError("control_resolution: a cone layer's tip or base is on the boundary or on another cone");
      steps.emplace_back(t, b);
    }
  }
  // the integer programme: one variable per regular hexahedron
  std::vector<int> var(n, -1);
  int num_vars = 0;
  for (std::size_t h = 0; h < n; ++h)
    if (plan.layer_of[h] < 0) var[h] = num_vars++;
  plan.num_variables = idx(num_vars);
  CoinPackedMatrix matrix(false, 0, 0);
  matrix.setDimensions(0, num_vars);
  std::vector<double> row_lb, row_ub;
  auto add_row = [&](int plus, int minus, double rhs) {
    const int cols[2] = {var[idx(plus)], var[idx(minus)]};
    const double vals[2] = {1.0, -1.0};
    matrix.appendRow(2, cols, vals);
    row_lb.push_back(rhs), row_ub.push_back(rhs);
  };
  for (std::size_t h = 0; h < n; ++h)
    for (int f = 0; f < 6; ++f) {
      const int o = adj.hex[h][idx(f)];
      if (o > static_cast<int>(h) && var[h] >= 0 && var[idx(o)] >= 0) add_row(static_cast<int>(h), o, 0.0);
    }
  for (const auto& [t, b] : steps) add_row(b, t, 1.0);
  plan.num_constraints = row_lb.size();
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> x(idx(num_vars), 0.0);
  if (num_vars > 0) {
    const std::vector<double> col_lb(idx(num_vars), 0.0), col_ub(idx(num_vars), 1000.0), cost(idx(num_vars), 1.0);
    OsiClpSolverInterface solver;
    SilentHandler handler;
    solver.passInMessageHandler(&handler);
    solver.messageHandler()->setLogLevel(0);
    solver.loadProblem(matrix, col_lb.data(), col_ub.data(), cost.data(), row_lb.data(), row_ub.data());
    for (int j = 0; j < num_vars; ++j) solver.setInteger(j);
    CbcModel model(solver);
    model.passInMessageHandler(&handler);
    model.setLogLevel(0);
    model.setNumberThreads(0);
    model.setRandomSeed(12345);
    model.setMaximumSeconds(options.time_limit_s);
    model.initialSolve();
    model.branchAndBound();
    const double* sol = model.bestSolution();
    plan.solved = sol != nullptr;
    if (sol) std::copy(sol, sol + num_vars, x.begin());
  }
  plan.ilp_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // the solution, checked: every equality must hold exactly
  for (std::size_t h = 0; h < n; ++h)
    if (var[h] >= 0) plan.splits[h] = static_cast<int>(std::lround(x[idx(var[h])]));
  const auto& s = plan.splits;
  bool ok = plan.solved;
  for (std::size_t h = 0; h < n && ok; ++h)
    for (int f = 0; f < 6; ++f) {
      const int o = adj.hex[h][idx(f)];
      if (o >= 0 && var[h] >= 0 && var[idx(o)] >= 0 && s[h] != s[idx(o)]) ok = false;
    }
  for (const auto& [t, b] : steps) ok = ok && s[idx(b)] == s[idx(t)] + 1 && s[idx(t)] >= 0;
  if (!ok) {  // no solution: no cone (cannot happen with cones on terminal branches only)
    plan.solved = false;
    plan.layers.clear();
    plan.layer_of.assign(n, -1);
    plan.splits.assign(n, 0);
    return plan;
  }
  for (std::size_t l = 0; l < plan.layers.size(); ++l)
    for (int k : plan.layers[l].hexes) plan.splits[idx(k)] = s[idx(steps[5 * l].first)];
  return plan;
}

std::size_t planned_num_hexes(const ResolutionPlan& plan, int offset) {
  std::size_t total = 0;
  for (std::size_t h = 0; h < plan.splits.size(); ++h) {
    const int l = plan.layer_of[h];
    if (l >= 0 && plan.layers[idx(l)].hexes[0] != static_cast<int>(h)) continue;
    const std::size_t per = l >= 0 ? detail::kConeTemplateHexes : 1;
    total += per << (3 * idx(plan.splits[h] + offset));
  }
  return total;
}

RefinementSchedule schedule_refinement(const ResolutionPlan& plan, int offset, int& num_levels) {
  RefinementSchedule s;
  const std::size_t n = plan.splits.size();
  num_levels = 0;
  for (std::size_t h = 0; h < n; ++h)
    num_levels = std::max(num_levels, plan.splits[h] + offset + (plan.layer_of[h] >= 0 ? 1 : 0));
  s.first_level.resize(n);
  s.cone_slot.assign(n, -1);
  s.template_of.assign(n, -1);
  s.layers = plan.layers;
  for (std::size_t h = 0; h < n; ++h) {
    const int l = plan.layer_of[h];
    // a regular hexahedron splits at the last x levels; a cone layer gets its
    // template when its base side first splits
    s.first_level[h] = num_levels - (plan.splits[h] + offset) + (l >= 0 ? 0 : 1);
    if (l >= 0) {
      const auto& hx = plan.layers[idx(l)].hexes;
      s.cone_slot[h] = 5 * l + static_cast<int>(std::find(hx.begin(), hx.end(), static_cast<int>(h)) - hx.begin());
    }
  }
  return s;
}

HexMesh refine_hex_mesh(const HexMesh& mesh, RefinementSchedule& schedule, int level,
                        const std::vector<std::array<bool, 3>>* axes) {
  if (schedule.first_level.size() != mesh.hexes.size() || schedule.cone_slot.size() != mesh.hexes.size() ||
      schedule.template_of.size() != mesh.hexes.size())
    throw InvalidArgumentError("refine_hex_mesh: the schedule has " + std::to_string(schedule.first_level.size()) +
                               " entries for " + std::to_string(mesh.hexes.size()) + " hexahedra");
  if (axes && axes->size() != mesh.hexes.size())
    throw InvalidArgumentError("refine_hex_mesh: " + std::to_string(axes->size()) + " axis flags for " +
                               std::to_string(mesh.hexes.size()) + " hexahedra");
  // the current hexahedra of the layers that get their template now
  std::map<int, std::array<Hex, 5>> cells;
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    const int slot = schedule.cone_slot[h];
    if (slot >= 0 && schedule.first_level[h] == level) cells[slot / 5][idx(slot % 5)] = mesh.hexes[h];
  }
  HexMesh out;
  detail::HexSplitter splitter(mesh, out);
  RefinementSchedule next;
  next.layers = schedule.layers;
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    const int first = schedule.first_level[h], slot = schedule.cone_slot[h];
    const std::size_t before = out.hexes.size();
    int child_first = first, child_slot = -1, child_template = schedule.template_of[h];
    if (slot >= 0 && first == level) {
      child_template = slot / 5;
      if (slot % 5 == 0) detail::add_cone_template(mesh, schedule.layers[idx(slot / 5)], cells.at(slot / 5), splitter, out);
      child_first = level + 1;  // the pieces split with the tip side
    } else if (slot < 0 && first <= level) {
      if (axes) splitter.split(mesh.hexes[h], (*axes)[h]);
      else splitter.split(mesh.hexes[h]);
    } else {
      out.hexes.push_back(mesh.hexes[h]);
      child_slot = slot;
    }
    for (std::size_t c = before; c < out.hexes.size(); ++c) {
      next.first_level.push_back(child_first);
      next.cone_slot.push_back(child_slot);
      next.template_of.push_back(child_template);
    }
  }
  schedule = std::move(next);
  return out;
}

}  // namespace subfab
