// SPDX-License-Identifier: GPL-3.0-or-later
//! \file delete_facets.cpp
//! Facet deletion (thesis Section 3.3.2): explicit ids by connected group,
//! then small facets smallest first, alone or with small neighbours (Figure
//! 3.11); each deletion closes the hole (close_hole.cpp), merges coplanar
//! neighbours and is checked exactly, and undone when any check fails.
#include "subfab/unfold/delete_facets.h"

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>

#include "subfab/core/error.h"
#include "geometry/hausdorff_distance.h"
#include "unfold/check_closed_manifold.h"
#include "unfold/check_no_intersections.h"
#include "unfold/close_hole.h"
#include "unfold/edge_key.h"
#include "unfold/exact_poly_mesh.h"
#include "unfold/merge_coplanar_neighbours.h"

namespace subfab {

using namespace unfold_detail;

namespace {

std::unordered_map<std::uint64_t, int> edge_owners(const ExactPolyMesh& mesh) {
  std::unordered_map<std::uint64_t, int> owner;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    if (!mesh.facets[f].alive) continue;
    for (const auto& loop : mesh.facets[f].loops)
      for (std::size_t i = 0; i < loop.size(); ++i) owner[edge_key(loop[i], loop[(i + 1) % loop.size()])] = int(f);
  }
  return owner;
}

std::vector<int> neighbours_of(const ExactPolyMesh& mesh, const std::unordered_map<std::uint64_t, int>& owner,
                               int f) {
  std::set<int> out;
  for (const auto& loop : mesh.facets[f].loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const auto it = owner.find(edge_key(loop[(i + 1) % loop.size()], loop[i]));
      if (it != owner.end() && it->second != f) out.insert(it->second);
    }
  return {out.begin(), out.end()};
}

// Deletes `region` (facet ids) and validates; restores the mesh on failure.
// On success, `touched` (if given) receives the facets whose loops changed or
// that died.
std::string try_delete(ExactPolyMesh& mesh, const std::unordered_map<std::uint64_t, int>& owner,
                       const std::vector<int>& region, const CloseHoleLimits& limits, std::size_t& num_merged,
                       std::vector<int>* touched = nullptr) {
  const std::vector<QFacet> saved_facets = mesh.facets;
  const std::size_t saved_points = mesh.points.size();
  auto restore = [&] {
    mesh.facets = saved_facets;
    mesh.points.resize(saved_points);
    mesh.approx.resize(saved_points);
  };
  std::string reason = close_hole(mesh, owner, region, limits);
  std::vector<int> changed;
  if (reason.empty()) {
    for (std::size_t f = 0; f < mesh.facets.size(); ++f)
      if (mesh.facets[f].alive && mesh.facets[f].loops != saved_facets[f].loops) changed.push_back(int(f));
    std::size_t alive_before = 0;
    for (const auto& f : mesh.facets) alive_before += f.alive;
    const auto merged = merge_coplanar_neighbours(mesh, changed);
    if (!merged) {
      reason = "merging coplanar neighbours gives a pinched facet";
    } else {
      std::size_t alive_after = 0;
      for (const auto& f : mesh.facets) alive_after += f.alive;
      changed.insert(changed.end(), merged->begin(), merged->end());
      const auto reduced = remove_two_facet_vertices(mesh);
      changed.insert(changed.end(), reduced.begin(), reduced.end());
      std::sort(changed.begin(), changed.end());
      changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
      changed.erase(std::remove_if(changed.begin(), changed.end(), [&](int f) { return !mesh.facets[f].alive; }),
                    changed.end());
      reason = check_closed_manifold(mesh);
      for (std::size_t i = 0; reason.empty() && i < changed.size(); ++i) reason = check_facet_simple(mesh, changed[i]);
      if (reason.empty()) reason = check_no_intersections(mesh, changed);
      if (reason.empty()) num_merged += alive_before - alive_after;
    }
    if (!reason.empty()) reason = "the closed surface would be invalid: " + reason;
  }
  if (!reason.empty()) {
    restore();
  } else if (touched) {
    touched->clear();
    for (std::size_t f = 0; f < mesh.facets.size(); ++f)
      if (mesh.facets[f].alive != saved_facets[f].alive || mesh.facets[f].loops != saved_facets[f].loops)
        touched->push_back(int(f));
  }
  return reason;
}

}  // namespace

DeleteFacetsResult delete_facets(const PolyMesh& input, const DeleteFacetsOptions& options) {
  StageScope scope(options.progress, "delete facets");
  ExactPolyMesh mesh = to_exact(input, LatticeFrame{options.grid_origin, options.grid_step});
  if (std::string r = check_closed_manifold(mesh); !r.empty())
    throw InvalidMeshError("polygonal mesh given to facet deletion is invalid: " + r);
  DeleteFacetsResult result;
  const std::size_t num_input = mesh.facets.size();

  // Explicit ids: connected groups.
  if (!options.facet_ids.empty()) {
    std::set<int> ids;
    for (int id : options.facet_ids) {
      if (id < 0 || static_cast<std::size_t>(id) >= num_input)
        throw InvalidArgumentError("facet id " + std::to_string(id) + " does not exist (the mesh has " +
                                   std::to_string(num_input) + " facets)");
      ids.insert(id);
    }
    const auto owner = edge_owners(mesh);
    std::set<int> left = ids;
    while (!left.empty()) {
      std::vector<int> group{*left.begin()};
      left.erase(left.begin());
      for (std::size_t g = 0; g < group.size(); ++g)
        for (int n : neighbours_of(mesh, owner, group[g]))
          if (left.erase(n)) group.push_back(n);
      std::sort(group.begin(), group.end());
      bool alive = std::all_of(group.begin(), group.end(), [&](int f) { return mesh.facets[f].alive; });
      std::string reason = alive ? try_delete(mesh, edge_owners(mesh), group, CloseHoleLimits{}, result.num_merged)
                                 : "a facet of the group was merged away by an earlier deletion";
      if (reason.empty()) {
        result.num_deleted += group.size();
      } else {
        result.failures.push_back({group, reason});
        if (options.progress) options.progress->warn("cannot delete facet(s) " + std::to_string(group[0]) + "...: " + reason);
      }
    }
  }

  if (options.min_facet_area > 0) {
    std::unique_ptr<detail::SurfaceDistance> reference;
    if (options.reference) reference = std::make_unique<detail::SurfaceDistance>(*options.reference);
    const CloseHoleLimits limits{options.max_extension, reference.get(), options.max_distance_to_reference};
    // A failed attempt is retried only when a facet of the group or around
    // it has changed since (versions bumped by every successful deletion).
    std::vector<int> version(mesh.facets.size(), 0);
    std::map<std::vector<int>, std::vector<int>> failed;  // group -> versions seen
    std::map<int, std::string> last_failure;
    auto owner = edge_owners(mesh);
    auto stamp = [&](const std::vector<int>& group) {
      std::set<int> around(group.begin(), group.end());
      for (int h : group)
        for (int n : neighbours_of(mesh, owner, h)) around.insert(n);
      std::vector<int> st;
      for (int h : around) {
        st.push_back(h);
        st.push_back(version[h]);
      }
      return st;
    };
    std::vector<int> touched;
    auto attempt = [&](const std::vector<int>& group, std::string* why) {
      auto st = stamp(group);
      const auto it = failed.find(group);
      if (it != failed.end() && it->second == st) return false;
      const std::string r = try_delete(mesh, owner, group, limits, result.num_merged, &touched);
      if (r.empty()) {
        for (int t : touched) ++version[t];
        owner = edge_owners(mesh);
        result.num_deleted += group.size();
        for (int h : group) last_failure.erase(h);
        return true;
      }
      failed[group] = std::move(st);
      if (why) *why = r;
      return false;
    };
    bool progress_made = true;
    while (progress_made) {
      progress_made = false;
      std::vector<std::pair<double, int>> small;
      for (std::size_t f = 0; f < mesh.facets.size(); ++f)
        if (mesh.facets[f].alive) {
          const double a = facet_area(mesh, int(f));
          if (a < options.min_facet_area) small.emplace_back(a, int(f));
        }
      std::sort(small.begin(), small.end());
      for (std::size_t idx = 0; idx < small.size(); ++idx) {
        const int f = small[idx].second;
        if (!mesh.facets[f].alive || facet_area(mesh, f) >= options.min_facet_area) continue;
        if (options.progress) options.progress->update(idx, small.size());
        std::string reason;
        if (attempt({f}, &reason)) {
          progress_made = true;
          continue;
        }
        if (!reason.empty()) last_failure[f] = reason;
        // Groups with small neighbours (Figure 3.11), breadth first.
        const double group_limit = options.group_area_factor * options.min_facet_area;
        std::vector<std::vector<int>> frontier{{f}};
        bool deleted = false;
        for (int size = 2; size <= options.max_group_size && !deleted; ++size) {
          std::vector<std::vector<int>> grown;
          for (const auto& g : frontier) {
            std::set<int> cand;
            for (int h : g)
              for (int n : neighbours_of(mesh, owner, h))
                if (!std::count(g.begin(), g.end(), n) && facet_area(mesh, n) < group_limit) cand.insert(n);
            for (int n : cand) {
              auto ng = g;
              ng.push_back(n);
              std::sort(ng.begin(), ng.end());
              if (std::find(grown.begin(), grown.end(), ng) == grown.end()) grown.push_back(ng);
            }
          }
          for (const auto& g : grown)
            if (attempt(g, nullptr)) {
              progress_made = deleted = true;
              break;
            }
          frontier = std::move(grown);
          if (frontier.size() > 16) frontier.resize(16);
        }
      }
    }
    for (const auto& [f, reason] : last_failure)
      if (mesh.facets[f].alive && facet_area(mesh, f) < options.min_facet_area)
        result.failures.push_back({{f}, reason});
  }
  result.mesh = to_poly_mesh(mesh);
  if (options.progress)
    options.progress->info(std::to_string(result.num_deleted) + " facets deleted, " +
                           std::to_string(result.num_merged) + " merged, " +
                           std::to_string(result.mesh.num_facets()) + " left");
  return result;
}

}  // namespace subfab
