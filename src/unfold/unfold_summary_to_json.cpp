// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/unfold_summary_to_json.h"

#include <nlohmann/json.hpp>

namespace subfab {

nlohmann::ordered_json unfold_summary_to_json(const UnfoldSummary& summary) {
  nlohmann::ordered_json s;
  s["facets_mc"] = summary.facets_mc;
  s["facets_after_masks"] = summary.facets_after_masks;
  s["facets_final"] = summary.facets_final;
  s["nets"] = summary.nets;
  s["hausdorff"] = summary.hausdorff;
  return s;
}

}  // namespace subfab
