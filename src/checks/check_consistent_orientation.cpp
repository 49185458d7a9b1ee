// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_consistent_orientation.h"

#include <algorithm>
#include <deque>
#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {
namespace checks_detail {

namespace {
//! A neighbour of a face across a manifold edge.
struct Link {
  int face;
  bool same_direction;  // both faces traverse the shared edge the same way
};

//! Faces that disagree with the majority of their piece: faces are given a
//! flip bit by walking across manifold edges (a neighbour traversing the
//! shared edge in the same direction gets the other bit); in each piece the
//! faces with the less common bit are the ones to flip.
std::vector<int> minority_faces(const Mesh& mesh, const EdgeTopology& topology) {
  const std::size_t num_faces = mesh.num_faces();
  std::vector<std::size_t> offsets(num_faces + 1, 0);
  for (std::size_t e = 0; e < topology.num_edges(); ++e)
    if (topology.num_uses(e) == 2) {
      ++offsets[static_cast<std::size_t>(topology.use(e, 0).face) + 1];
      ++offsets[static_cast<std::size_t>(topology.use(e, 1).face) + 1];
    }
  for (std::size_t f = 0; f < num_faces; ++f) offsets[f + 1] += offsets[f];
  std::vector<Link> links(offsets.back());
  std::vector<std::size_t> fill(offsets.begin(), offsets.end() - 1);
  for (std::size_t e = 0; e < topology.num_edges(); ++e)
    if (topology.num_uses(e) == 2) {
      const EdgeUse& x = topology.use(e, 0);
      const EdgeUse& y = topology.use(e, 1);
      const bool same = x.forward == y.forward;
      links[fill[static_cast<std::size_t>(x.face)]++] = {y.face, same};
      links[fill[static_cast<std::size_t>(y.face)]++] = {x.face, same};
    }

  std::vector<signed char> bit(num_faces, -1);
  std::vector<int> result;
  std::vector<int> piece;
  std::deque<int> queue;
  for (std::size_t seed = 0; seed < num_faces; ++seed) {
    if (bit[seed] >= 0 || has_repeated_index(mesh.faces[seed])) continue;
    piece.clear();
    bit[seed] = 0;
    queue.push_back(static_cast<int>(seed));
    std::size_t ones = 0;
    while (!queue.empty()) {
      const auto f = static_cast<std::size_t>(queue.front());
      queue.pop_front();
      piece.push_back(static_cast<int>(f));
      ones += static_cast<std::size_t>(bit[f]);
      for (std::size_t k = offsets[f]; k < offsets[f + 1]; ++k) {
        const auto g = static_cast<std::size_t>(links[k].face);
        if (bit[g] >= 0) continue;
        bit[g] = static_cast<signed char>(links[k].same_direction ? 1 - bit[f] : bit[f]);
        queue.push_back(static_cast<int>(g));
      }
    }
    const signed char minority = ones * 2 <= piece.size() ? 1 : 0;
    for (int f : piece)
      if (bit[static_cast<std::size_t>(f)] == minority) result.push_back(f);
  }
  std::sort(result.begin(), result.end());
  return result;
}
}  // namespace

CheckResult check_consistent_orientation(const Mesh& mesh, const EdgeTopology& topology,
                                         const CheckOptions& options) {
  std::size_t num_bad_edges = 0;
  std::vector<int> faces_on_bad_edges;
  for (std::size_t e = 0; e < topology.num_edges(); ++e) {
    const std::size_t n = topology.num_uses(e);
    if (n < 2) continue;
    std::size_t forward = 0;
    for (std::size_t k = 0; k < n; ++k) forward += topology.use(e, k).forward ? 1 : 0;
    if (2 * forward == n) continue;
    ++num_bad_edges;
    for (std::size_t k = 0; k < n; ++k) faces_on_bad_edges.push_back(topology.use(e, k).face);
  }
  if (num_bad_edges == 0)
    return passed_result("consistent_orientation", CheckElement::Face,
                         "neighbouring faces are consistently oriented");
  std::vector<int> flipped = minority_faces(mesh, topology);
  if (flipped.empty()) {  // only non-manifold edges disagree
    std::sort(faces_on_bad_edges.begin(), faces_on_bad_edges.end());
    faces_on_bad_edges.erase(std::unique(faces_on_bad_edges.begin(), faces_on_bad_edges.end()),
                             faces_on_bad_edges.end());
    flipped = std::move(faces_on_bad_edges);
  }
  std::ostringstream message;
  message << "the faces are not consistently oriented: "
          << count_of(num_bad_edges, "edge is", "edges are")
          << " used twice in the same direction; "
          << count_of(flipped.size(), "face disagrees", "faces disagree")
          << " with its neighbours, e.g. face " << flipped.front()
          << "; reorient the faces consistently (e.g. MeshLab: Re-Orient all faces coherently)";
  return failed_result("consistent_orientation", CheckElement::Face, num_bad_edges,
                       first_ids(flipped, options.max_examples), message.str());
}

}  // namespace checks_detail

CheckResult check_consistent_orientation(const Mesh& mesh, const CheckOptions& options) {
  checks_detail::require_valid_indices(mesh, "consistent_orientation");
  return checks_detail::check_consistent_orientation(mesh, checks_detail::EdgeTopology(mesh),
                                                     options);
}

}  // namespace subfab
