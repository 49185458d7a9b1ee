// SPDX-License-Identifier: GPL-3.0-or-later
#include "checks/edge_topology.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <tuple>

#include "subfab/core/error.h"

namespace subfab {

const char* status_name(CheckStatus status) {
  switch (status) {
    case CheckStatus::Passed: return "passed";
    case CheckStatus::Failed: return "failed";
    case CheckStatus::Skipped: return "skipped";
  }
  return "?";
}

const char* element_name(CheckElement element) {
  return element == CheckElement::Vertex ? "vertex" : "face";
}

namespace checks_detail {

EdgeTopology::EdgeTopology(const Mesh& mesh) {
  uses.reserve(3 * mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Triangle& t = mesh.faces[f];
    if (has_repeated_index(t)) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const int from = t[k];
      const int to = t[(k + 1) % 3];
      uses.push_back({std::min(from, to), std::max(from, to), static_cast<int>(f), from < to});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.a, x.b, x.face) < std::tie(y.a, y.b, y.face);
  });
  offsets.push_back(0);
  for (std::size_t i = 1; i <= uses.size(); ++i)
    if (i == uses.size() || uses[i].a != uses[i - 1].a || uses[i].b != uses[i - 1].b)
      offsets.push_back(i);
}

UnionFind::UnionFind(std::size_t n) : parent_(n) {
  std::iota(parent_.begin(), parent_.end(), 0);
}

int UnionFind::find(int x) {
  while (parent_[static_cast<std::size_t>(x)] != x) {
    auto& p = parent_[static_cast<std::size_t>(x)];
    p = parent_[static_cast<std::size_t>(p)];
    x = p;
  }
  return x;
}

void UnionFind::unite(int x, int y) {
  x = find(x);
  y = find(y);
  if (x == y) return;
  if (x < y) std::swap(x, y);
  parent_[static_cast<std::size_t>(x)] = y;
}

FaceComponents label_face_components(const Mesh& mesh) {
  UnionFind sets(mesh.num_vertices());
  for (const auto& t : mesh.faces) {
    sets.unite(t[0], t[1]);
    sets.unite(t[1], t[2]);
  }
  FaceComponents result;
  result.face_component.resize(mesh.num_faces());
  std::vector<int> label(mesh.num_vertices(), -1);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    int& l = label[static_cast<std::size_t>(sets.find(mesh.faces[f][0]))];
    if (l < 0) l = static_cast<int>(result.num_components++);
    result.face_component[f] = l;
  }
  return result;
}

void require_valid_indices(const Mesh& mesh, std::string_view check) {
  const auto n = static_cast<long long>(mesh.num_vertices());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || v >= n) {
        std::ostringstream message;
        message << "cannot run the " << check << " check: face " << f << " refers to vertex " << v
                << " but the mesh has " << n << " vertices; run check_face_indices first";
        throw InvalidMeshError(message.str());
      }
}

void require_finite_coordinates(const Mesh& mesh, std::string_view check) {
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    if (!mesh.vertices[v].allFinite()) {
      std::ostringstream message;
      message << "cannot run the " << check << " check: vertex " << v
              << " has a NaN or infinite coordinate; run check_finite_coordinates first";
      throw InvalidMeshError(message.str());
    }
}

std::vector<int> first_ids(const std::vector<int>& ids, std::size_t max) {
  return {ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(std::min(max, ids.size()))};
}

std::string join_ids(const std::vector<int>& ids) {
  std::ostringstream out;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i > 0) out << (i + 1 == ids.size() ? " and " : ", ");
    out << ids[i];
  }
  return out.str();
}

std::string count_of(std::size_t n, std::string_view singular, std::string_view plural) {
  std::ostringstream out;
  out << n << " " << (n == 1 ? singular : plural);
  return out.str();
}

CheckResult passed_result(std::string name, CheckElement element, std::string message) {
  CheckResult result;
  result.name = std::move(name);
  result.status = CheckStatus::Passed;
  result.element = element;
  result.message = std::move(message);
  return result;
}

CheckResult failed_result(std::string name, CheckElement element, std::size_t num_offending,
                          std::vector<int> examples, std::string message) {
  CheckResult result;
  result.name = std::move(name);
  result.status = CheckStatus::Failed;
  result.element = element;
  result.num_offending = num_offending;
  result.examples = std::move(examples);
  result.message = std::move(message);
  return result;
}

}  // namespace checks_detail
}  // namespace subfab
