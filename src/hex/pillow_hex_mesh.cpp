// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/pillow_hex_mesh.h"

namespace subfab {

std::vector<int> pillow_hex_mesh(HexMesh& mesh) {
  const std::vector<Quad> boundary = boundary_quads(mesh);
  std::vector<int> outer(mesh.vertices.size(), -1);
  for (const Quad& q : boundary)
    for (int v : q) {
      int& o = outer[static_cast<std::size_t>(v)];
      if (o < 0) {
        o = static_cast<int>(mesh.vertices.size());
        mesh.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
      }
    }
  for (const Quad& q : boundary) {
    auto o = [&](int k) { return outer[static_cast<std::size_t>(q[static_cast<std::size_t>(k)])]; };
    mesh.hexes.push_back({q[0], q[1], q[2], q[3], o(0), o(1), o(2), o(3)});
  }
  return outer;
}

}  // namespace subfab
