// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mesh_repair_to_json.h
//! The JSON record of a repair_mesh() report, shared by `subfab repair
//! --json`, decomposition.json and unfold.json (`decompose --repair`,
//! `unfold --repair`).
#pragma once

#include <nlohmann/json.hpp>

#include "subfab/repair/repair_mesh.h"

namespace subfab {

//! {"problems": [...], "steps": [{"name", "found", "faces_removed",
//! "faces_added", "where" ([x,y,z] or null), "message"}] (applied steps only),
//! "applied_steps", "input" {"vertices", "faces"}, "output" {"vertices",
//! "faces"}, "bbox_diagonal", "max_deviation", "max_deviation_fraction",
//! "mean_deviation", "hausdorff_error", "max_deviation_cap_fraction"} (no timing: the
//! record is the same on every run).
nlohmann::ordered_json mesh_repair_to_json(const MeshRepairReport& report);

}  // namespace subfab
