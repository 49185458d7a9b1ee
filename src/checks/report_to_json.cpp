// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/report_to_json.h"

#include <nlohmann/json.hpp>

namespace subfab {

namespace {
template <typename T>
nlohmann::json optional_json(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json vec_json(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }
}  // namespace

nlohmann::json check_to_json(const CheckResult& check) {
  return {{"name", check.name},
          {"status", status_name(check.status)},
          {"count", check.num_offending},
          {"groups", check.num_groups},
          {"element", element_name(check.element)},
          {"examples", check.examples},
          {"message", check.message}};
}

nlohmann::json report_to_json(const MeshReport& report) {
  nlohmann::json json;
  json["vertices"] = report.num_vertices;
  json["faces"] = report.num_faces;
  json["edges"] = report.num_edges;
  json["closed"] = optional_json(report.closed);
  json["manifold"] = optional_json(report.manifold);
  json["oriented"] = optional_json(report.oriented);
  json["outward"] = optional_json(report.outward);
  json["self_intersecting"] = optional_json(report.self_intersecting);
  json["components"] = report.num_components;
  json["genus"] = optional_json(report.genus);
  json["boundary_edges"] = report.num_boundary_edges;
  json["holes"] = report.num_holes;
  if (report.bbox && !report.bbox->is_empty())
    json["bbox"] = {{"min", vec_json(report.bbox->min)}, {"max", vec_json(report.bbox->max)}};
  else
    json["bbox"] = nullptr;
  json["diagonal"] = optional_json(report.diagonal);
  json["average_edge_length"] = optional_json(report.average_edge_length);
  json["area"] = optional_json(report.area);
  json["volume"] = optional_json(report.volume);
  json["checks"] = nlohmann::json::array();
  for (const auto& check : report.checks) json["checks"].push_back(check_to_json(check));
  return json;
}

}  // namespace subfab
