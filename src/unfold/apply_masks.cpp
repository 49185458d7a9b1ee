// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/apply_masks.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>

#include "mask_catalogue.h"
#include "mc_case_table.h"
#include "subfab/core/error.h"
#include "unfold/fidelity_band.h"

namespace subfab {
namespace {

using Int3 = std::array<int, 3>;

// A triangle of the implicit marching-cubes mesh: its cube and its index in
// the cube's case.
struct TriRef {
  std::size_t cube;  // point index of the cube's lowest corner
  int local;         // index into the case's triangles
};

class MaskEngine {
 public:
  MaskEngine(Lattice& lattice, const MaskOptions& options) : l_(lattice), g_(lattice.grid), opt_(options) {
    stride_ = {1, static_cast<std::size_t>(g_.size[0]),
               static_cast<std::size_t>(g_.size[0]) * static_cast<std::size_t>(g_.size[1])};
    for (int c = 0; c < 8; ++c)
      corner_offset_[static_cast<std::size_t>(c)] =
          ((c & 1) ? stride_[0] : 0) + (((c >> 1) & 1) ? stride_[1] : 0) + (((c >> 2) & 1) ? stride_[2] : 0);
    flips_.assign(g_.num_points(), 0);
    // Fidelity band: only points next to the original surface may flip, so
    // the surface never drifts more than about one cell from where it was.
    band_.assign(g_.num_points(), 0);
    for (std::size_t p = 0; p < g_.num_points(); ++p) band_[p] = on_surface(p);
    if (options.reference)
      fidelity_ = unfold_detail::FidelityBand(*options.reference, g_, l_.inside, options.fidelity_radius);
  }

  std::size_t num_fidelity_constraints() const { return fidelity_.num_constraints(); }

  MaskResult run() {
    MaskResult result;
    const std::size_t n = g_.num_points();
    std::vector<char> queued(n, 0);
    std::deque<std::size_t> queue;
    for (std::size_t p = 0; p < n; ++p)
      if (on_surface(p)) {
        queue.push_back(p);
        queued[p] = 1;
      }
    const std::size_t cap = opt_.max_total_flips > 0 ? opt_.max_total_flips : 4 * std::max<std::size_t>(queue.size(), 1);
    const auto& masks = masks::oriented_masks();
    while (!queue.empty()) {
      const std::size_t a = queue.front();
      queue.pop_front();
      queued[a] = 0;
      const Int3 ac = coords(a);
      for (std::size_t mi = 0; mi <= masks.size(); ++mi) {
        std::vector<std::size_t> best;
        if (mi < masks.size()) {
          if (!matches(masks[mi], ac) || !choose(masks[mi], ac, best, result)) continue;
        } else {
          // After the catalogue: the anchor alone, if flipping it is simple
          // and strictly lowers the local energy (generic single-point move).
          if (!opt_.single_point_moves || !single_point_move(ac, best, result)) continue;
        }
        if (result.num_flips + best.size() > cap) {
          result.hit_flip_cap = true;
          queue.clear();
          break;
        }
        for (std::size_t p : best) {
          l_.inside[p] ^= 1;
          if (++flips_[p] == opt_.max_flips_per_point) ++result.num_frozen_points;
        }
        fidelity_.commit(l_.inside, best);
        result.num_flips += best.size();
        ++result.num_moves;
        // Masks reach 2 points from their anchor: re-examine those anchors.
        for (std::size_t p : best) {
          const Int3 c = coords(p);
          for (int dz = -2; dz <= 2; ++dz)
            for (int dy = -2; dy <= 2; ++dy)
              for (int dx = -2; dx <= 2; ++dx) {
                const Int3 q{c[0] + dx, c[1] + dy, c[2] + dz};
                if (!in_grid(q)) continue;
                const std::size_t qi = index(q);
                if (!queued[qi] && on_surface(qi)) {
                  queued[qi] = 1;
                  queue.push_back(qi);
                }
              }
        }
        break;  // the signs around `a` changed: it is examined again later
      }
    }
    return result;
  }

 private:
  Int3 coords(std::size_t p) const {
    const std::size_t nx = static_cast<std::size_t>(g_.size[0]), ny = static_cast<std::size_t>(g_.size[1]);
    return {static_cast<int>(p % nx), static_cast<int>((p / nx) % ny), static_cast<int>(p / (nx * ny))};
  }
  bool in_grid(const Int3& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < g_.size[0] && c[1] < g_.size[1] && c[2] < g_.size[2];
  }
  bool interior(const Int3& c) const {
    return c[0] > 0 && c[1] > 0 && c[2] > 0 && c[0] + 1 < g_.size[0] && c[1] + 1 < g_.size[1] && c[2] + 1 < g_.size[2];
  }
  std::size_t index(const Int3& c) const { return g_.index(c[0], c[1], c[2]); }
  bool inside(const Int3& c) const { return in_grid(c) && l_.inside[index(c)] != 0; }

  bool on_surface(std::size_t p) const {
    const Int3 c = coords(p);
    for (int a = 0; a < 3; ++a)
      for (int s : {-1, 1}) {
        Int3 q = c;
        q[static_cast<std::size_t>(a)] += s;
        if (in_grid(q) && l_.inside[index(q)] != l_.inside[p]) return true;
      }
    return false;
  }

  bool matches(const masks::Mask& m, const Int3& a) const {
    for (const auto& [o, v] : m.signs) {
      const Int3 q{a[0] + o[0], a[1] + o[1], a[2] + o[2]};
      if (!in_grid(q) || (l_.inside[index(q)] != 0) != v) return false;
    }
    return true;
  }

  // Topology-preserving flip of the point at c, for inside 6-connected and
  // outside 18-connected (the adjacencies of the table's face rule): the
  // inside points of N18*(c) 6-adjacent to c form one 6-component, and the
  // outside points of N18*(c) one 18-component.
  bool is_simple(const Int3& c) const {
    // Local 3x3x3 block, index (x + 1) + 3 (y + 1) + 9 (z + 1).
    std::array<int, 27> sign{};
    for (int z = -1; z <= 1; ++z)
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
          sign[static_cast<std::size_t>((x + 1) + 3 * (y + 1) + 9 * (z + 1))] = inside({c[0] + x, c[1] + y, c[2] + z});
    auto count_components = [&](int value, bool eighteen) {
      std::array<int, 27> label{};
      label.fill(-1);
      int components = 0;
      for (int s = 0; s < 27; ++s) {
        const int sx = s % 3 - 1, sy = (s / 3) % 3 - 1, sz = s / 9 - 1;
        const int dist = std::abs(sx) + std::abs(sy) + std::abs(sz);
        if (s == 13 || dist == 3 || sign[static_cast<std::size_t>(s)] != value || label[static_cast<std::size_t>(s)] >= 0)
          continue;
        if (!eighteen && dist != 1) continue;  // 6-components are seeded at the 6-neighbours
        std::vector<int> stack{s};
        label[static_cast<std::size_t>(s)] = components;
        while (!stack.empty()) {
          const int u = stack.back();
          stack.pop_back();
          const int ux = u % 3 - 1, uy = (u / 3) % 3 - 1, uz = u / 9 - 1;
          for (int v = 0; v < 27; ++v) {
            const int vx = v % 3 - 1, vy = (v / 3) % 3 - 1, vz = v / 9 - 1;
            const int vdist = std::abs(vx) + std::abs(vy) + std::abs(vz);
            if (v == 13 || vdist == 3 || sign[static_cast<std::size_t>(v)] != value || label[static_cast<std::size_t>(v)] >= 0)
              continue;
            const int d = std::abs(ux - vx) + std::abs(uy - vy) + std::abs(uz - vz);
            const int cheb = std::max({std::abs(ux - vx), std::abs(uy - vy), std::abs(uz - vz)});
            const bool adjacent = eighteen ? (cheb == 1 && d <= 2) : d == 1;
            if (!adjacent) continue;
            label[static_cast<std::size_t>(v)] = components;
            stack.push_back(v);
          }
        }
        ++components;
      }
      return components;
    };
    return count_components(1, false) == 1 && count_components(0, true) == 1;
  }

  // Triangles of a cube as global vertex ids (lattice edge 3 p + axis).
  int cube_config(std::size_t cube) const {
    int config = 0;
    for (int c = 0; c < 8; ++c)
      if (l_.inside[cube + corner_offset_[static_cast<std::size_t>(c)]]) config |= 1 << c;
    return config;
  }
  std::array<std::size_t, 3> global_triangle(std::size_t cube, const std::array<int, 3>& local) const {
    std::array<std::size_t, 3> t{};
    for (int s = 0; s < 3; ++s) {
      const mc::CubeEdge& e = mc::cube_edges()[static_cast<std::size_t>(local[static_cast<std::size_t>(s)])];
      t[static_cast<std::size_t>(s)] = 3 * (cube + corner_offset_[static_cast<std::size_t>(e.corners[0])]) +
                                       static_cast<std::size_t>(e.axis);
    }
    return t;
  }
  bool valid_cube(const Int3& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] + 1 < g_.size[0] && c[1] + 1 < g_.size[1] && c[2] + 1 < g_.size[2];
  }
  // The cubes around a set of points (each point is a corner of 8 cubes).
  std::vector<std::size_t> cubes_around(const std::vector<std::size_t>& points) const {
    std::vector<std::size_t> out;
    for (std::size_t p : points) {
      const Int3 c = coords(p);
      for (int dz = -1; dz <= 0; ++dz)
        for (int dy = -1; dy <= 0; ++dy)
          for (int dx = -1; dx <= 0; ++dx) {
            const Int3 q{c[0] + dx, c[1] + dy, c[2] + dz};
            if (valid_cube(q)) out.push_back(index(q));
          }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // `cubes` and the cubes sharing a face with one of them, sorted.
  std::vector<std::size_t> with_face_neighbours(const std::vector<std::size_t>& cubes) const {
    std::vector<std::size_t> ring = cubes;
    for (std::size_t cube : cubes) {
      const Int3 c = coords(cube);
      for (int a = 0; a < 3; ++a)
        for (int s : {-1, 1}) {
          Int3 q = c;
          q[static_cast<std::size_t>(a)] += s;
          if (valid_cube(q)) ring.push_back(index(q));
        }
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    return ring;
  }

  struct HalfEdge {
    std::size_t from, to;
    int normal;
    bool in_region;
    bool operator<(const HalfEdge& o) const { return std::tie(from, to) < std::tie(o.from, o.to); }
  };

  // E over the triangles of `cubes`: triangle edges whose neighbour (in the
  // cube or a face-adjacent one) has a different normal.
  long local_energy(const std::vector<std::size_t>& cubes) const {
    const std::vector<std::size_t> ring = with_face_neighbours(cubes);
    std::vector<HalfEdge> half;
    for (std::size_t cube : ring) {
      const bool in_region = std::binary_search(cubes.begin(), cubes.end(), cube);
      const mc::CubeCase& cc = mc::case_table()[static_cast<std::size_t>(cube_config(cube))];
      for (std::size_t t = 0; t < cc.triangles.size(); ++t) {
        const auto g = global_triangle(cube, cc.triangles[t]);
        for (int s = 0; s < 3; ++s)
          half.push_back({g[static_cast<std::size_t>(s)], g[static_cast<std::size_t>((s + 1) % 3)], cc.normals[t], in_region});
      }
    }
    std::sort(half.begin(), half.end());
    long energy = 0;
    for (const HalfEdge& h : half) {
      if (!h.in_region) continue;
      const auto it = std::lower_bound(half.begin(), half.end(), HalfEdge{h.to, h.from, 0, false});
      if (it != half.end() && it->from == h.to && it->to == h.from && it->normal != h.normal) ++energy;
    }
    return energy;
  }

  // Number of lattice faces on which two neighbouring cubes use the two
  // crossing "parallel" face diagonals (rule 4 of mc_case_table.h): the
  // surface would touch itself at the face centre. Counted over the faces of
  // `cubes`; flips must not increase it.
  std::size_t count_touchings(const std::vector<std::size_t>& cubes) const {
    // (global face key, diagonal axis) for every parallel face diagonal.
    std::vector<std::pair<std::size_t, std::size_t>> chords;
    const std::vector<std::size_t> ring = with_face_neighbours(cubes);
    for (std::size_t cube : ring) {
      const mc::CubeCase& cc = mc::case_table()[static_cast<std::size_t>(cube_config(cube))];
      for (const auto& t : cc.triangles)
        for (int s = 0; s < 3; ++s) {
          const int e0 = t[static_cast<std::size_t>(s)], e1 = t[static_cast<std::size_t>((s + 1) % 3)];
          if (e0 > e1) continue;  // each diagonal once (interior diagonals appear in both directions)
          const mc::CubeEdge& a = mc::cube_edges()[static_cast<std::size_t>(e0)];
          const mc::CubeEdge& b = mc::cube_edges()[static_cast<std::size_t>(e1)];
          if (a.axis != b.axis) continue;  // parallel chords join two edges of the same axis
          // The face both edges lie on: the axis (other than theirs) along
          // which their corners agree.
          for (int f = 0; f < 3; ++f) {
            if (f == a.axis) continue;
            const int sa = (a.corners[0] >> f) & 1, sb = (b.corners[0] >> f) & 1;
            if (sa != sb) continue;
            const std::size_t face_point = cube + (sa ? stride_[static_cast<std::size_t>(f)] : 0);
            chords.push_back({3 * face_point + static_cast<std::size_t>(f), static_cast<std::size_t>(a.axis)});
          }
        }
    }
    std::sort(chords.begin(), chords.end());
    chords.erase(std::unique(chords.begin(), chords.end()), chords.end());
    std::size_t touchings = 0;
    for (std::size_t i = 0; i + 1 < chords.size(); ++i) touchings += chords[i].first == chords[i + 1].first;
    return touchings;
  }

  // Doubled position of a global vertex (lattice edge id).
  Vec3 vertex_position2(std::size_t edge) const {
    const Int3 c = coords(edge / 3);
    Vec3 p(2 * c[0], 2 * c[1], 2 * c[2]);
    p[static_cast<int>(edge % 3)] += 1;
    return p;
  }

  // Area (lattice units, capped flood fill) of the largest chart touching
  // the triangles of `cubes`.
  double largest_adjacent_chart(const std::vector<std::size_t>& cubes) const {
    std::vector<std::pair<std::size_t, int>> visited;  // (cube, local), sorted on insert
    auto seen = [&](std::size_t cube, int local) {
      return std::binary_search(visited.begin(), visited.end(), std::make_pair(cube, local));
    };
    auto mark = [&](std::size_t cube, int local) {
      visited.insert(std::upper_bound(visited.begin(), visited.end(), std::make_pair(cube, local)), {cube, local});
    };
    double best = 0;
    for (std::size_t cube : cubes) {
      const mc::CubeCase& cc = mc::case_table()[static_cast<std::size_t>(cube_config(cube))];
      for (std::size_t t0 = 0; t0 < cc.triangles.size(); ++t0) {
        if (seen(cube, static_cast<int>(t0))) continue;
        const int normal = cc.normals[t0];
        double area = 0;
        int count = 0;
        std::vector<TriRef> stack{{cube, static_cast<int>(t0)}};
        mark(cube, static_cast<int>(t0));
        while (!stack.empty() && count < opt_.chart_probe_triangles) {
          const TriRef t = stack.back();
          stack.pop_back();
          ++count;
          const mc::CubeCase& tc = mc::case_table()[static_cast<std::size_t>(cube_config(t.cube))];
          const auto g = global_triangle(t.cube, tc.triangles[static_cast<std::size_t>(t.local)]);
          const Vec3 a = vertex_position2(g[0]), b = vertex_position2(g[1]), c = vertex_position2(g[2]);
          area += 0.125 * (b - a).cross(c - a).norm();  // doubled coordinates: / 2 / 4
          // Neighbours with the same normal, in this cube or a face-adjacent one.
          const Int3 cc3 = coords(t.cube);
          for (int s = 0; s < 3; ++s) {
            const std::size_t u = g[static_cast<std::size_t>(s)], v = g[static_cast<std::size_t>((s + 1) % 3)];
            for (int k = 0; k < 7; ++k) {
              Int3 q = cc3;
              if (k > 0) q[static_cast<std::size_t>((k - 1) / 2)] += (k % 2) ? -1 : 1;
              if (!valid_cube(q)) continue;
              const std::size_t qc = index(q);
              const mc::CubeCase& qcase = mc::case_table()[static_cast<std::size_t>(cube_config(qc))];
              for (std::size_t r = 0; r < qcase.triangles.size(); ++r) {
                if (qcase.normals[r] != normal || seen(qc, static_cast<int>(r))) continue;
                const auto h = global_triangle(qc, qcase.triangles[r]);
                bool adjacent = false;
                for (int w = 0; w < 3; ++w)
                  adjacent |= h[static_cast<std::size_t>(w)] == v && h[static_cast<std::size_t>((w + 1) % 3)] == u;
                if (!adjacent) continue;
                mark(qc, static_cast<int>(r));
                stack.push_back({qc, static_cast<int>(r)});
              }
            }
          }
        }
        best = std::max(best, area);
      }
    }
    return best;
  }

  bool single_point_move(const Int3& c, std::vector<std::size_t>& chosen, MaskResult& result) {
    if (!interior(c)) return false;
    const std::size_t p = index(c);
    if (!band_[p] || flips_[p] >= opt_.max_flips_per_point || !is_simple(c)) return false;
    const std::vector<std::size_t> cubes = cubes_around({p});
    const long before = local_energy(cubes);
    const std::size_t touch_before = count_touchings(cubes);
    l_.inside[p] ^= 1;
    const long after = local_energy(cubes);
    const bool touches = count_touchings(cubes) > touch_before;
    // Energy-neutral moves only when they grow the biggest adjacent chart.
    const bool worse = opt_.neutral_single_point_moves ? after > before : after >= before;
    const double chart_after = (!worse && after == before && !touches) ? largest_adjacent_chart(cubes) : 0;
    const bool faithful = worse || touches || fidelity_.allows(l_.inside, {p});
    l_.inside[p] ^= 1;
    if (worse || touches) return false;
    if (after == before && !(chart_after > largest_adjacent_chart(cubes))) return false;
    if (!faithful) {
      ++result.num_rejected_fidelity;
      return false;
    }
    chosen = {p};
    return true;
  }

  // Evaluates the POI sets of a matching mask; true (and the points) if one is applied.
  bool choose(const masks::Mask& m, const Int3& anchor, std::vector<std::size_t>& chosen, MaskResult& result) {
    struct Option {
      std::vector<std::size_t> points;
      long delta;
      double chart;
    };
    std::vector<Option> options;
    for (const auto& set : m.poi_sets) {
      std::vector<std::size_t> points;
      bool ok = true;
      for (const auto& o : set) {
        const Int3 q{anchor[0] + o[0], anchor[1] + o[1], anchor[2] + o[2]};
        if (!interior(q) || !band_[index(q)] || flips_[index(q)] >= opt_.max_flips_per_point) ok = false;
        else points.push_back(index(q));
      }
      if (!ok) continue;
      const std::vector<std::size_t> cubes = cubes_around(points);
      const long before = local_energy(cubes);
      const std::size_t touch_before = count_touchings(cubes);
      // Flip one point at a time, each must be simple when flipped.
      std::size_t done = 0;
      for (; done < points.size(); ++done) {
        if (!is_simple(coords(points[done]))) break;
        l_.inside[points[done]] ^= 1;
      }
      if (done == points.size() && count_touchings(cubes) > touch_before) {
        ++result.num_rejected_topology;
      } else if (done == points.size() && !fidelity_.allows(l_.inside, points)) {
        ++result.num_rejected_fidelity;
      } else if (done == points.size()) {
        const long after = local_energy(cubes);
        const double chart = m.poi_sets.size() > 1 ? largest_adjacent_chart(cubes) : 0;
        options.push_back({points, after - before, chart});
      } else {
        ++result.num_rejected_topology;
      }
      for (std::size_t k = 0; k < done; ++k) l_.inside[points[k]] ^= 1;
    }
    if (options.empty()) return false;
    // Several POI sets: favour the move that grows the bigger chart.
    const Option* best = nullptr;
    for (const Option& o : options) {
      if (o.delta > 0) continue;
      if (!best || o.chart > best->chart || (o.chart == best->chart && o.delta < best->delta)) best = &o;
    }
    if (!best) return false;
    if (best->delta == 0) {
      // A sideways move: only for masks with several POI sets, and only if
      // it grows the biggest adjacent chart.
      if (m.poi_sets.size() < 2) return false;
      if (!(best->chart > largest_adjacent_chart(cubes_around(best->points)))) return false;
    }
    chosen = best->points;
    return true;
  }

  Lattice& l_;
  const GridPoints& g_;
  const MaskOptions& opt_;
  std::array<std::size_t, 3> stride_{};
  std::array<std::size_t, 8> corner_offset_{};
  std::vector<int> flips_;
  std::vector<char> band_;
  unfold_detail::FidelityBand fidelity_;  // empty without options.reference
};

}  // namespace

MaskResult apply_masks(const Lattice& lattice, const MaskOptions& options) {
  if (!(options.fidelity_radius > 0) || !std::isfinite(options.fidelity_radius))
    throw InvalidArgumentError("the fidelity radius of the mask stage must be a positive number of grid spacings");
  StageScope stage(options.progress, "masks");
  Lattice work = lattice;
  MaskResult result;
  if (work.grid.size[0] >= 3 && work.grid.size[1] >= 3 && work.grid.size[2] >= 3) {
    MaskEngine engine(work, options);
    result = engine.run();
    result.num_fidelity_constraints = engine.num_fidelity_constraints();
  }
  result.lattice = std::move(work);
  result.surface = marching_cubes(result.lattice);
  result.charts = extract_charts(result.surface.mesh, result.surface.normals);
  if (options.progress) {
    options.progress->info(std::to_string(result.num_moves) + " mask moves (" + std::to_string(result.num_flips) +
                           " sign flips), " + std::to_string(result.charts.poly.num_facets()) + " facets after masks");
    if (options.reference)
      options.progress->info(std::to_string(result.num_rejected_fidelity) +
                             " moves refused by the fidelity band (input farther than " +
                             std::to_string(options.fidelity_radius) + " spacings from the surface)");
    if (result.num_frozen_points > 0)
      options.progress->info(std::to_string(result.num_frozen_points) +
                             " lattice points reached the flip limit (loops cut)");
    if (result.hit_flip_cap) options.progress->warn("mask stage stopped at its flip cap");
  }
  return result;
}

}  // namespace subfab
