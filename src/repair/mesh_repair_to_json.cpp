// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/repair/mesh_repair_to_json.h"

namespace subfab {

nlohmann::ordered_json mesh_repair_to_json(const MeshRepairReport& r) {
  nlohmann::ordered_json steps = nlohmann::ordered_json::array();
  for (const auto& s : r.steps) {
    if (!s.applied()) continue;
    nlohmann::ordered_json where = nullptr;
    if (s.where) where = {s.where->x(), s.where->y(), s.where->z()};
    steps.push_back({{"name", s.name},
                     {"found", s.num_found},
                     {"faces_removed", s.num_faces_removed},
                     {"faces_added", s.num_faces_added},
                     {"where", where},
                     {"message", s.message}});
  }
  nlohmann::ordered_json j;
  j["problems"] = r.problems;
  j["steps"] = steps;
  j["applied_steps"] = r.applied_steps();
  j["input"] = {{"vertices", r.input_vertices}, {"faces", r.input_faces}};
  j["output"] = {{"vertices", r.output_vertices}, {"faces", r.output_faces}};
  j["bbox_diagonal"] = r.bbox_diagonal;
  j["max_deviation"] = r.max_deviation;
  j["max_deviation_fraction"] = r.max_deviation_fraction();
  j["mean_deviation"] = r.mean_deviation;
  j["mean_deviation_fraction"] = r.bbox_diagonal > 0 ? r.mean_deviation / r.bbox_diagonal : 0.0;
  j["hausdorff_error"] = r.hausdorff_error;
  j["max_deviation_cap_fraction"] = r.max_deviation_cap;
  return j;
}

}  // namespace subfab
