// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/exact_normal_signs.h"

#include "geometry/exact_determinant_signs.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {

std::array<std::int8_t, 3> exact_normal_signs(const Vec3& a, const Vec3& b, const Vec3& c) {
  return {static_cast<std::int8_t>(normal_component_sign(a, b, c, 0)),
          static_cast<std::int8_t>(normal_component_sign(a, b, c, 1)),
          static_cast<std::int8_t>(normal_component_sign(a, b, c, 2))};
}

std::array<std::int8_t, 3> facing_signs(const Vec3& a, const Vec3& b, const Vec3& c, double overhang_sine) {
  std::array<std::int8_t, 3> signs = exact_normal_signs(a, b, c);
  if (overhang_sine <= 0.0 || (signs[0] == 0 && signs[1] == 0 && signs[2] == 0)) return signs;
  const Vec3 n = (b - a).cross(c - a).normalized();
  for (int k = 0; k < 3; ++k)
    signs[static_cast<std::size_t>(k)] = n[k] < -overhang_sine ? -1 : (n[k] > overhang_sine ? 1 : 0);
  return signs;
}

std::vector<std::array<std::int8_t, 3>> facing_signs(const Mesh& mesh, double overhang_sine,
                                                     const std::vector<std::uint8_t>* allowed) {
  if (allowed && allowed->size() != mesh.num_faces())
    throw InvalidArgumentError("facing_signs: one allowance per face expected");
  std::vector<std::array<std::int8_t, 3>> signs(mesh.num_faces());
  parallel_for(
      0, mesh.num_faces(),
      [&](std::size_t f) {
        const auto& t = mesh.faces[f];
        signs[f] = facing_signs(mesh.vertices[static_cast<std::size_t>(t[0])],
                                mesh.vertices[static_cast<std::size_t>(t[1])],
                                mesh.vertices[static_cast<std::size_t>(t[2])], overhang_sine);
        if (allowed)
          for (int k = 0; k < 3; ++k)
            if ((*allowed)[f] & (1u << k)) signs[f][static_cast<std::size_t>(k)] = 0;
      },
      1024);
  return signs;
}

std::vector<std::array<std::int8_t, 3>> exact_normal_signs(const Mesh& mesh) { return facing_signs(mesh, 0.0); }

}  // namespace subfab::detail
