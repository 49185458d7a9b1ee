// SPDX-License-Identifier: GPL-3.0-or-later
//! \file report_to_json.h
//! The machine-readable form of a MeshReport (`subfab info --json`).
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "subfab/checks/analyze_mesh.h"

namespace subfab {

//! JSON object with `vertices`, `faces`, `edges`, `closed`, `manifold`,
//! `oriented`, `outward`, `self_intersecting`, `components`, `genus`,
//! `boundary_edges`, `holes`, `bbox` ({min: [x,y,z], max: [x,y,z]}),
//! `diagonal`, `average_edge_length`, `area`, `volume` (null when unknown)
//! and `checks`: [{name, status, count, groups, element, examples, message}].
nlohmann::json report_to_json(const MeshReport& report);

//! One check result as JSON (the elements of `checks` above).
nlohmann::json check_to_json(const CheckResult& check);

}  // namespace subfab
