// SPDX-License-Identifier: GPL-3.0-or-later
//! \file read_mill_info.h
//! What the assembly sheet takes from `subfab mill`'s GCODE_DIR/mill.json:
//! the scale and, per block, the stock size in millimetres, the estimated
//! machining time and the G-code file. Read leniently (only these keys;
//! anything else in the file is ignored).
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! The milling facts of one block.
struct MilledBlockInfo {
  Vec3 stock_mm = Vec3::Zero();  // stock size x, y, z (z along the milling direction), mm; zero when not given
  double time_s = -1;            // estimated machining time, seconds; < 0 when not given
  std::string gcode;             // G-code file name in GCODE_DIR ("" when not given)
};

//! GCODE_DIR/mill.json.
struct MillInfo {
  std::filesystem::path path;  // the file read
  double mm_per_unit = 0;      // "scale_mm_per_unit"; 0 when not given
  std::map<std::size_t, MilledBlockInfo> blocks;  // by block number ("id", or "index")
};

//! Reads GCODE_DIR/mill.json (keys: scale_mm_per_unit; blocks[] with id or
//! index, stock_mm [x, y, z], time_s, gcode).
//! \throw IoError when the file is missing or is not such a JSON document.
MillInfo read_mill_info(const std::filesystem::path& gcode_dir);

}  // namespace subfab
