// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/check_single_precision.h"

#include "subfab/checks/check_self_intersections.h"
#include "subfab/mesh/float32.h"

namespace subfab {

Mesh round_to_single_precision(const Mesh& mesh, std::size_t* num_welded) {
  Mesh out = mesh;
  for (Vec3& v : out.vertices) v = round_to_float32(v);
  const std::size_t welded = weld_identical_vertices(out);
  if (num_welded) *num_welded = welded;
  return out;
}

SinglePrecisionReport check_single_precision(const Mesh& mesh) {
  SinglePrecisionReport r;
  const Mesh rounded = round_to_single_precision(mesh, &r.num_welded);
  r.solid = check_closed_solid(rounded);
  r.num_self_intersections = check_self_intersections(rounded).num_offending;
  return r;
}

}  // namespace subfab
