// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/extract_charts.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <unordered_map>

#include "subfab/core/error.h"
#include "unfold/edge_key.h"

namespace subfab {

using unfold_detail::edge_key;

namespace {

int find_root(std::vector<int>& parent, int x) {
  while (parent[static_cast<std::size_t>(x)] != x) {
    parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    x = parent[static_cast<std::size_t>(x)];
  }
  return x;
}

}  // namespace

std::size_t count_unpaired_edges(const PolyMesh& poly) {
  std::unordered_map<std::uint64_t, int> count;
  for (const Facet& f : poly.facets)
    for (const auto& loop : f.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) ++count[edge_key(loop[i], loop[(i + 1) % loop.size()])];
  std::size_t bad = 0;
  for (const auto& [key, n] : count) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    const auto it = count.find(edge_key(b, a));
    if (n != 1 || it == count.end() || it->second != 1) bad += static_cast<std::size_t>(n);
  }
  return bad;
}

Charts extract_charts(const Mesh& mesh, const std::vector<int>& normals, const ChartOptions& options) {
  if (normals.size() != mesh.faces.size())
    throw InvalidArgumentError("extract_charts: one normal index per triangle is needed");
  StageScope stage(options.progress, "charts");
  const std::size_t num_faces = mesh.faces.size();
  const std::size_t num_half = 3 * num_faces;
  // Half-edge h = 3 f + s goes from faces[f][s] to faces[f][s + 1].
  auto from = [&](std::size_t h) { return mesh.faces[h / 3][h % 3]; };
  auto to = [&](std::size_t h) { return mesh.faces[h / 3][(h % 3 + 1) % 3]; };
  std::unordered_map<std::uint64_t, std::size_t> half_of;
  half_of.reserve(num_half);
  for (std::size_t h = 0; h < num_half; ++h)
    if (!half_of.emplace(edge_key(from(h), to(h)), h).second)
      throw AlgorithmError("extract_charts: a directed edge is used twice (mesh not 2-manifold or not oriented)");
  std::vector<std::size_t> twin(num_half);
  for (std::size_t h = 0; h < num_half; ++h) {
    const auto it = half_of.find(edge_key(to(h), from(h)));
    if (it == half_of.end()) throw AlgorithmError("extract_charts: the mesh is not closed");
    twin[h] = it->second;
  }

  // Charts: union of edge-adjacent triangles with the same normal.
  std::vector<int> parent(num_faces);
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t h = 0; h < num_half; ++h) {
    const std::size_t f = h / 3, g = twin[h] / 3;
    if (normals[f] != normals[g]) continue;
    const int a = find_root(parent, static_cast<int>(f)), b = find_root(parent, static_cast<int>(g));
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  Charts out;
  out.face_chart.assign(num_faces, -1);
  std::vector<int> root_chart(num_faces, -1);
  int num_charts = 0;
  for (std::size_t f = 0; f < num_faces; ++f) {
    const int r = find_root(parent, static_cast<int>(f));
    if (root_chart[static_cast<std::size_t>(r)] < 0) root_chart[static_cast<std::size_t>(r)] = num_charts++;
    out.face_chart[f] = root_chart[static_cast<std::size_t>(r)];
  }
  auto chart_of_half = [&](std::size_t h) { return out.face_chart[h / 3]; };

  // Boundary loops: walk boundary half-edges; the next one after (a -> v)
  // is found by turning around v inside the chart.
  std::vector<std::vector<std::vector<int>>> loops(static_cast<std::size_t>(num_charts));
  std::vector<char> visited(num_half, 0);
  for (std::size_t h0 = 0; h0 < num_half; ++h0) {
    if (visited[h0] || chart_of_half(h0) == chart_of_half(twin[h0])) continue;
    const int chart = chart_of_half(h0);
    std::vector<int> loop;
    std::size_t h = h0;
    do {
      visited[h] = 1;
      loop.push_back(from(h));
      std::size_t next = 3 * (h / 3) + (h % 3 + 1) % 3;
      std::size_t guard = 0;
      while (chart_of_half(twin[next]) == chart) {
        const std::size_t t = twin[next];
        next = 3 * (t / 3) + (t % 3 + 1) % 3;
        if (++guard > num_half) throw AlgorithmError("extract_charts: cannot walk around a vertex");
      }
      h = next;
      if (visited[h] && h != h0) throw AlgorithmError("extract_charts: boundary walk does not close");
    } while (h != h0);
    loops[static_cast<std::size_t>(chart)].push_back(std::move(loop));
  }

  // Facets: outer loop (positive area about the normal) first.
  std::vector<int> chart_normal(static_cast<std::size_t>(num_charts), -1);
  for (std::size_t f = 0; f < num_faces; ++f) chart_normal[static_cast<std::size_t>(out.face_chart[f])] = normals[f];
  PolyMesh& poly = out.poly;
  poly.facets.resize(static_cast<std::size_t>(num_charts));
  std::vector<Vec3> chart_area(static_cast<std::size_t>(num_charts), Vec3::Zero());
  for (std::size_t f = 0; f < num_faces; ++f)
    chart_area[static_cast<std::size_t>(out.face_chart[f])] += face_normal_scaled(mesh, f);
  for (int c = 0; c < num_charts; ++c) {
    auto& cl = loops[static_cast<std::size_t>(c)];
    const Vec3 n = chart_area[static_cast<std::size_t>(c)];
    std::vector<std::pair<double, std::size_t>> order;
    int num_outer = 0;
    for (std::size_t l = 0; l < cl.size(); ++l) {
      Vec3 area = Vec3::Zero();
      const auto& loop = cl[l];
      for (std::size_t i = 0; i < loop.size(); ++i)
        area += mesh.vertices[static_cast<std::size_t>(loop[i])].cross(
            mesh.vertices[static_cast<std::size_t>(loop[(i + 1) % loop.size()])]);
      const double signed_area = area.dot(n);
      num_outer += signed_area > 0;
      order.push_back({-signed_area, l});
    }
    if (num_outer != 1)
      throw AlgorithmError("extract_charts: chart " + std::to_string(c) + " has " + std::to_string(num_outer) +
                           " outer boundaries");
    std::stable_sort(order.begin(), order.end());
    Facet& facet = poly.facets[static_cast<std::size_t>(c)];
    facet.normal = chart_normal[static_cast<std::size_t>(c)];
    for (const auto& [key, l] : order) facet.loops.push_back(std::move(cl[l]));
  }

  // Straight vertices: on exactly two loop positions of two different facets.
  std::vector<int> uses(mesh.vertices.size(), 0), first_facet(mesh.vertices.size(), -1);
  std::vector<char> two_facets(mesh.vertices.size(), 0);
  for (std::size_t c = 0; c < poly.facets.size(); ++c)
    for (const auto& loop : poly.facets[c].loops)
      for (int v : loop) {
        const auto vi = static_cast<std::size_t>(v);
        if (uses[vi]++ == 0)
          first_facet[vi] = static_cast<int>(c);
        else
          two_facets[vi] = first_facet[vi] != static_cast<int>(c);
      }
  std::vector<int> remap(mesh.vertices.size(), -1);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const bool straight = options.remove_straight_vertices && uses[v] == 2 && two_facets[v];
    if (uses[v] > 0 && !straight) {
      remap[v] = static_cast<int>(poly.vertices.size());
      poly.vertices.push_back(mesh.vertices[v]);
    }
  }
  for (Facet& facet : poly.facets)
    for (auto& loop : facet.loops) {
      std::vector<int> kept;
      for (int v : loop)
        if (remap[static_cast<std::size_t>(v)] >= 0) kept.push_back(remap[static_cast<std::size_t>(v)]);
      if (kept.size() < 3) throw AlgorithmError("extract_charts: a facet loop collapsed below three corners");
      loop = std::move(kept);
    }
  if (options.progress) options.progress->info(std::to_string(poly.facets.size()) + " facets");
  return out;
}

}  // namespace subfab
