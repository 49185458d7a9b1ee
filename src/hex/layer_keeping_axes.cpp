// SPDX-License-Identifier: GPL-3.0-or-later
#include <array>
#include <cstddef>
#include <vector>

#include "subfab/hex/control_resolution.h"
#include "subfab/hex/hex_sheets.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

}  // namespace

std::vector<std::array<bool, 3>> layer_keeping_axes(const HexMesh& mesh, const RefinementSchedule& schedule, int level,
                                                    double min_share, std::size_t* num_kept) {
  const HexSheets sheets = hex_sheets(mesh);
  const SheetIrregularity irr = sheet_irregularity(mesh, sheets);
  std::vector<bool> keep(irr.size.size());
  for (std::size_t s = 0; s < keep.size(); ++s)
    keep[s] = irr.size[s] > 0 && static_cast<double>(irr.along[s]) >= min_share * static_cast<double>(irr.size[s]);
  // only sheets whose hexahedra all split regularly now: a cone template, or
  // a hexahedron not due yet, keeps its faces as they are
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    const bool regular_now = h < schedule.cone_slot.size() && schedule.cone_slot[h] < 0 &&
                             schedule.first_level[h] <= level;
    if (!regular_now)
      for (int s : sheets.of_hex[h]) keep[idx(s)] = false;
  }
  std::vector<std::array<bool, 3>> axes(mesh.hexes.size());
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h)
    for (int a = 0; a < 3; ++a) axes[h][idx(a)] = !keep[idx(sheets.of_hex[h][idx(a)])];
  if (num_kept) {
    *num_kept = 0;
    for (bool k : keep) *num_kept += k ? 1 : 0;
  }
  return axes;
}

std::size_t num_hexes_keeping_layers(const HexMesh& padded, const ResolutionPlan& plan, int offset, double min_share) {
  int levels = 0;
  RefinementSchedule schedule = schedule_refinement(plan, offset, levels);
  HexMesh mesh = padded;
  for (int level = 1; level <= levels; ++level) {
    if (level < levels) {
      mesh = refine_hex_mesh(mesh, schedule, level);
    } else {
      const auto axes = layer_keeping_axes(mesh, schedule, level, min_share);
      mesh = refine_hex_mesh(mesh, schedule, level, &axes);
    }
  }
  return mesh.hexes.size();
}

}  // namespace subfab
