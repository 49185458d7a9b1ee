// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/read_mill_info.h"

#include <nlohmann/json.hpp>

#include <fstream>

#include "subfab/core/error.h"

namespace subfab {

MillInfo read_mill_info(const std::filesystem::path& gcode_dir) {
  MillInfo info;
  info.path = gcode_dir / "mill.json";
  std::ifstream in(info.path);
  if (!in) throw IoError(info.path.string() + ": cannot read; run `subfab mill` first, or leave out --mill");
  try {
    const nlohmann::json doc = nlohmann::json::parse(in);
    info.mm_per_unit = doc.value("scale_mm_per_unit", 0.0);
    for (const nlohmann::json& b : doc.at("blocks")) {
      const std::size_t id = b.contains("id") ? b.at("id").get<std::size_t>() : b.at("index").get<std::size_t>();
      MilledBlockInfo m;
      if (b.contains("stock_mm")) {
        const nlohmann::json& s = b.at("stock_mm");
        m.stock_mm = Vec3(s.at(0).get<double>(), s.at(1).get<double>(), s.at(2).get<double>());
      }
      m.time_s = b.contains("time_s") ? b.at("time_s").get<double>() : b.value("machining_time_s", -1.0);
      m.gcode = b.value("gcode", "");
      info.blocks[id] = m;
    }
  } catch (const nlohmann::json::exception& e) {
    throw IoError(info.path.string() + ": not a mill.json of `subfab mill` (" + e.what() + ")");
  }
  return info;
}

}  // namespace subfab
