// SPDX-License-Identifier: GPL-3.0-or-later
//! \file layout_sheets.cpp
//! Sheet layout of the unfolding export (stage 7; nets of thesis Section
//! 3.3.3): each net turned to its smallest bounding box (landscape), then
//! the nets packed in rows on sheets, first fit by decreasing height.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "subfab/unfold/export_unfolding.h"

namespace subfab {

SheetLayout layout_sheets(const Unfolding& unfolding, const ExportUnfoldingOptions& options) {
  SheetLayout layout;
  layout.positions = unfolding.positions;
  const std::size_t num_nets = unfolding.nets.size();
  layout.net_sheet.assign(num_nets, 0);
  std::vector<Vec2> size(num_nets);
  double sum_area = 0, max_w = 0;
  for (std::size_t n = 0; n < num_nets; ++n) {
    const Net& net = unfolding.nets[n];
    // candidate rotations: align an edge with x
    std::vector<double> angles{0.0};
    for (int f : net.facets)
      for (const auto& loop : unfolding.positions[f])
        for (std::size_t i = 0; i < loop.size() && angles.size() < 64; ++i) {
          const Vec2 d = loop[(i + 1) % loop.size()] - loop[i];
          angles.push_back(-std::atan2(d.y(), d.x()));
        }
    double best_area = std::numeric_limits<double>::infinity(), best_angle = 0;
    for (double a : angles) {
      const double c = std::cos(a), s = std::sin(a);
      Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
      for (int f : net.facets)
        for (const auto& loop : unfolding.positions[f])
          for (const Vec2& p : loop) {
            const Vec2 q(c * p.x() - s * p.y(), s * p.x() + c * p.y());
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
          }
      Vec2 ext = hi - lo;
      if (ext.y() > ext.x()) ext = Vec2(ext.y(), ext.x());  // prefer landscape (rotated below)
      const double area = ext.x() * ext.y();
      if (area < best_area * (1 - 1e-9)) {
        best_area = area;
        best_angle = a;
      }
    }
    const double c = std::cos(best_angle), s = std::sin(best_angle);
    Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
    for (int f : net.facets)
      for (auto& loop : layout.positions[f])
        for (Vec2& p : loop) {
          p = Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
          lo = lo.cwiseMin(p);
          hi = hi.cwiseMax(p);
        }
    if (hi.y() - lo.y() > hi.x() - lo.x()) {  // landscape: rotate by -90 degrees
      for (int f : net.facets)
        for (auto& loop : layout.positions[f])
          for (Vec2& p : loop) p = Vec2(p.y(), -p.x());
      lo = Vec2::Constant(1e300);
      hi = Vec2::Constant(-1e300);
      for (int f : net.facets)
        for (const auto& loop : layout.positions[f])
          for (const Vec2& p : loop) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
          }
    }
    for (int f : net.facets)
      for (auto& loop : layout.positions[f])
        for (Vec2& p : loop) p -= lo;
    size[n] = hi - lo;
    sum_area += size[n].x() * size[n].y();
    max_w = std::max(max_w, size[n].x());
  }
  layout.gap = 0.03 * std::sqrt(std::max(sum_area, 1e-300));
  const double g = layout.gap;
  double W = options.sheet_width, H = options.sheet_height;
  if (W <= 0) W = std::max(max_w + 2 * g, 1.4 * std::sqrt(sum_area) + 2 * g);
  const bool unbounded = H <= 0;
  std::vector<std::size_t> order(num_nets);
  for (std::size_t i = 0; i < num_nets; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return size[a].y() > size[b].y(); });
  std::vector<Vec2> offset(num_nets);
  int sheet = 0;
  double x = g, y = g, row_h = 0, max_y = 0;
  for (std::size_t n : order) {
    const Vec2 e = size[n];
    if (e.x() + 2 * g > W || (!unbounded && e.y() + 2 * g > H)) layout.oversized_nets.push_back(int(n));
    if (x > g && x + e.x() + g > W) {  // next row
      x = g;
      y += row_h + g;
      row_h = 0;
    }
    if (!unbounded && y > g && y + e.y() + g > H) {  // next sheet
      ++sheet;
      x = g;
      y = g;
      row_h = 0;
    }
    offset[n] = Vec2(sheet * (W + g) + x, y);
    layout.net_sheet[n] = sheet;
    x += e.x() + g;
    row_h = std::max(row_h, e.y());
    max_y = std::max(max_y, y + e.y() + g);
  }
  layout.num_sheets = num_nets ? sheet + 1 : 0;
  layout.sheet_width = W;
  layout.sheet_height = unbounded ? max_y : H;
  for (std::size_t n = 0; n < num_nets; ++n)
    for (int f : unfolding.nets[n].facets)
      for (auto& loop : layout.positions[f])
        for (Vec2& p : loop) p += offset[n];
  return layout;
}

}  // namespace subfab
