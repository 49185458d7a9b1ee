// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hex_sheets.h"

#include <gtest/gtest.h>

#include <set>

#include "hex/hex_splitter.h"
#include "subfab/hex/pillow_hex_mesh.h"
#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

// A 2 x 3 x 4 grid has 2 + 3 + 4 sheets (the layers of hexahedra across
// each axis), each hexahedron in three different ones; no irregular edge.
TEST(HexSheets, GridHasOneSheetPerLayer) {
  const HexMesh m = test::hex_grid(2, 3, 4);
  const HexSheets s = hex_sheets(m);
  EXPECT_EQ(s.num_sheets, 9);
  std::set<int> per_axis[3];
  for (const auto& sh : s.of_hex)
    for (int a = 0; a < 3; ++a) per_axis[a].insert(sh[static_cast<std::size_t>(a)]);
  EXPECT_EQ(per_axis[0].size(), 2u);
  EXPECT_EQ(per_axis[1].size(), 3u);
  EXPECT_EQ(per_axis[2].size(), 4u);
  const SheetIrregularity irr = sheet_irregularity(m, s);
  for (int k = 0; k < s.num_sheets; ++k) {
    EXPECT_EQ(irr.along[static_cast<std::size_t>(k)], 0u);
    EXPECT_EQ(irr.freed[static_cast<std::size_t>(k)], 0u);
  }
  EXPECT_EQ(irr.size[0], 12u);  // a layer across axis 0: 3 x 4 hexahedra
}

// A pillowed 1 x 1 x 3 core (the padded tube of D.6): 3 layer sheets (the
// core hexahedron and its 4 side padding hexahedra, all touching the
// valence-3 edges at the core's corners, which run along the layer's axis),
// 2 chords and the pillow: 6 sheets. The chord across x holds the 3 cores,
// the 6 side hexahedra facing +-y and the 2 end caps.
TEST(HexSheets, PaddedTubeHasLayersChordsAndThePillow) {
  HexMesh m = test::hex_grid(1, 1, 3);
  pillow_hex_mesh(m);
  ASSERT_EQ(m.hexes.size(), 3u + 12u + 2u);
  const HexSheets s = hex_sheets(m);
  EXPECT_EQ(s.num_sheets, 6);
  const SheetIrregularity irr = sheet_irregularity(m, s);
  int layers = 0, chords = 0, pillow = 0;
  for (std::size_t k = 0; k < irr.size.size(); ++k) {
    if (irr.size[k] == 5 && irr.along[k] == 5) ++layers;
    if (irr.size[k] == 11) ++chords;
    if (irr.size[k] == 14) ++pillow;  // the 12 side hexahedra and 2 caps, radially
  }
  EXPECT_EQ(layers, 3);
  EXPECT_EQ(chords, 2);
  EXPECT_EQ(pillow, 1);
}

// The split along some axes: 1, 2, 4 or 8 children filling the hexahedron
// (a unit cube: volumes 1/n, every child a box), all three axes = split().
TEST(HexSheets, SplitterSplitsAlongTheGivenAxes) {
  const HexMesh cube = test::hex_grid(1, 1, 1);
  for (int mask = 0; mask < 8; ++mask) {
    const std::array<bool, 3> axes{(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0};
    HexMesh out;
    detail::HexSplitter splitter(cube, out);
    splitter.split(cube.hexes[0], axes);
    const std::size_t n = std::size_t{1} << (axes[0] + axes[1] + axes[2]);
    ASSERT_EQ(out.hexes.size(), n) << mask;
    EXPECT_TRUE(check_hex_mesh(out).valid());
    for (double q : scaled_jacobians(out)) EXPECT_NEAR(q, 1.0, 1e-12);
  }
  HexMesh all, regular;
  detail::HexSplitter a(cube, all), b(cube, regular);
  a.split(cube.hexes[0], {true, true, true});
  b.split(cube.hexes[0]);
  EXPECT_EQ(all.hexes, regular.hexes);
  EXPECT_EQ(all.vertices, regular.vertices);
}

}  // namespace
}  // namespace subfab
