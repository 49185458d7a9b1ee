// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/gauss_seidel_schedule.h"

#include <algorithm>

namespace subfab::detail {

std::vector<std::vector<std::size_t>> gauss_seidel_schedule(const HexMesh& mesh, const HexTopology& topo,
                                                            const std::vector<std::size_t>& order) {
  // per hexahedron: the last wave that visits one of its vertices (0: none yet)
  std::vector<std::size_t> last(mesh.hexes.size(), 0);
  std::vector<std::vector<std::size_t>> waves;
  for (std::size_t v : order) {
    std::size_t wave = 0;
    for (int h : topo.vertex_hexes[v]) wave = std::max(wave, last[static_cast<std::size_t>(h)]);
    // wave numbers start at 1: v goes into the wave after the latest conflict
    for (int h : topo.vertex_hexes[v]) last[static_cast<std::size_t>(h)] = wave + 1;
    if (waves.size() <= wave) waves.resize(wave + 1);
    waves[wave].push_back(v);
  }
  return waves;
}

}  // namespace subfab::detail
