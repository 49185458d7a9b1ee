// SPDX-License-Identifier: GPL-3.0-or-later
//! \file unfold_summary_to_json.h
//! The machine-readable form of an UnfoldSummary: unfold.json's `summary`
//! and the same keys in `subfab unfold --json`.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "subfab/unfold/export_unfolding.h"

namespace subfab {

//! JSON object with `facets_mc`, `facets_after_masks`, `facets_final`,
//! `nets` and `hausdorff` (model units), in that order.
nlohmann::ordered_json unfold_summary_to_json(const UnfoldSummary& summary);

}  // namespace subfab
