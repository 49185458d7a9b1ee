// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/mill_block.h"

#include <cmath>
#include <cstdio>

#include "subfab/core/error.h"
#include "subfab/mill/read_gcode.h"

namespace subfab {

StockSetup place_in_stock(const Mesh& machine_mesh, double scale, double margin) {
  if (!(scale > 0.0) || !std::isfinite(scale)) throw InvalidArgumentError("the scale must be a positive number of mm per model unit");
  if (!(margin >= 0.0) || !std::isfinite(margin)) throw InvalidArgumentError("--stock-margin must be zero or positive (mm)");
  StockSetup s;
  s.part = machine_mesh;
  const BoundingBox box = bounding_box(machine_mesh);
  for (Vec3& v : s.part.vertices) {
    v = (v - Vec3(box.min.x(), box.min.y(), 0.0)) * scale;
    v.x() += margin;
    v.y() += margin;
    v.z() = std::max(v.z(), 0.0);  // the base is on z = 0 (float STL rounding aside)
  }
  const Vec3 size = box.size() * scale;
  s.stock = {size.x() + 2.0 * margin, size.y() + 2.0 * margin, box.max.z() * scale + margin};
  return s;
}

MilledBlock mill_block(const StockSetup& setup, const std::vector<std::string>& header, const MillOptions& o) {
  MilledBlock out;
  out.stock = setup.stock;
  const TriangleGrid grid(setup.part, std::max(1.0, o.finishing.tool.radius()));
  std::vector<Toolpath> paths;
  std::vector<Tool> tools;
  if (o.rough) {
    paths.push_back(rough_toolpath(grid, setup.stock, o.roughing));
    out.rough = path_lengths(paths.back());
    out.rough_time = machining_time(paths.back(), o.gcode.feeds, o.motion);
    out.time_no_accel += machining_time(out.rough, o.gcode.feeds);
    tools.push_back(o.roughing.tool);
  }
  paths.push_back(finish_toolpath(grid, setup.stock, o.finishing));
  out.finish = path_lengths(paths.back());
  out.finish_time = machining_time(paths.back(), o.gcode.feeds, o.motion);
  out.time_no_accel += machining_time(out.finish, o.gcode.feeds);
  tools.push_back(o.finishing.tool);

  GcodeOptions go = o.gcode;
  go.header = header;
  char buf[160];
  std::snprintf(buf, sizeof buf, "estimated time %.1f min: roughing %.1f, finishing %.1f",
                (out.rough_time + out.finish_time) / 60.0, out.rough_time / 60.0, out.finish_time / 60.0);
  go.header.push_back(buf);
  std::snprintf(buf, sizeof buf, "rapids at %g mm/min, acceleration %g mm/s^2, junction deviation %g mm",
                o.gcode.feeds.rapid, o.motion.accel, o.motion.junction_deviation);
  go.header.push_back(buf);
  out.gcode = write_gcode(paths, setup.stock, go);

  // Check what was written: read it back, simulate it, compare.
  const GcodeRead program = read_gcode(out.gcode);
  out.num_gcode_lines = program.num_lines;
  HeightMap milled = make_height_map(setup.stock, o.resolution, setup.stock.z);
  out.simulation = simulate_dexels(program, tools, milled);
  std::vector<unsigned char> footprint;
  const HeightMap target = target_heights(setup.part, milled, footprint);
  const HeightMap ideal = ideal_surface(grid, o.finishing.tool, milled);
  out.check = check_milling(milled, target, footprint, ideal, o.check);
  if (o.picture) out.picture = draw_milling_map(milled, target, footprint, ideal, o.check);
  return out;
}

}  // namespace subfab
