// SPDX-License-Identifier: GPL-3.0-or-later
// Connected surface pieces inside a box: the block count the cover pays for.
#include "decompose/box_pieces.h"

#include <gtest/gtest.h>

#include "support/block_test_shapes.h"
#include "subfab/decompose/grow_boxes.h"

namespace subfab {
namespace {

using test::make_height_box;

//! A U in xy (prongs at x in [0,1] and [2,3] up to y = 2, notch floor at
//! y = 1), extruded over z in [0, 1]. Area 5.
Mesh u_solid() {
  return test::extrude_polygon({{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
                               {{0, 1, 4}, {0, 4, 5}, {1, 2, 4}, {2, 3, 4}, {0, 5, 7}, {5, 6, 7}}, 0.0, 1.0);
}

TEST(BoxPieces, FaceNeighboursOfAClosedMeshArePaired) {
  const Mesh u = u_solid();
  const std::vector<int> nb = detail::face_neighbours(u);
  ASSERT_EQ(nb.size(), 3 * u.faces.size());
  for (std::size_t s = 0; s < nb.size(); ++s) {
    ASSERT_GE(nb[s], 0);
    const auto f = s / 3;
    const auto g = static_cast<std::size_t>(nb[s]);
    EXPECT_NE(f, g);
    bool back = false;
    for (int k = 0; k < 3; ++k) back = back || nb[3 * g + static_cast<std::size_t>(k)] == static_cast<int>(f);
    EXPECT_TRUE(back) << "face " << f;
  }
}

TEST(BoxPieces, BoxOverBothProngsOfAUHasTwoPieces) {
  const Mesh u = u_solid();
  const detail::SolidIndex index(u);
  const std::vector<int> nb = detail::face_neighbours(u);
  // Above the notch floor: the two prongs are apart.
  const HeightBox tops = make_height_box({-1, 1.5, -1}, {4, 2.5, 2}, Axis::PosY);
  ASSERT_TRUE(index.box_is_valid(tops));
  const auto pieces = detail::surface_pieces(index, nb, tops);
  EXPECT_EQ(pieces.size(), 2u);
  // Down to below the notch floor: one piece (the floor joins the prongs).
  const HeightBox whole = make_height_box({-1, 0.5, -1}, {4, 2.5, 2}, Axis::PosY);
  ASSERT_TRUE(index.box_is_valid(whole));
  EXPECT_EQ(detail::surface_pieces(index, nb, whole).size(), 1u);
  // Over one prong only.
  const HeightBox left = make_height_box({-1, 1.5, -1}, {1.5, 2.5, 2}, Axis::PosY);
  EXPECT_EQ(detail::surface_pieces(index, nb, left).size(), 1u);
}

TEST(BoxPieces, BoxEqualToACubeIsOnePieceAndAnInteriorBoxNone) {
  const Mesh cube = test::box_solid({0, 0, 0}, {1, 1, 1});
  const detail::SolidIndex index(cube);
  const std::vector<int> nb = detail::face_neighbours(cube);
  // No face meets the open box; all twelve lie on its boundary, covered.
  const auto pieces = detail::surface_pieces(index, nb, make_height_box({0, 0, 0}, {1, 1, 1}, Axis::PosZ));
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].size(), 12u);
  EXPECT_TRUE(detail::surface_pieces(index, nb, make_height_box({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}, Axis::PosZ)).empty());
}

TEST(BoxPieces, GrowReportsPiecesPerBox) {
  const GrowResult grown = grow_boxes(u_solid(), GrowOptions{});
  ASSERT_EQ(grown.num_pieces.size(), grown.boxes.size());
  const detail::SolidIndex index(grown.mesh);
  const std::vector<int> nb = detail::face_neighbours(grown.mesh);
  for (std::size_t i = 0; i < grown.boxes.size(); ++i) {
    EXPECT_GE(grown.num_pieces[i], 1);
    const auto n = detail::surface_pieces(index, nb, grown.boxes[i]).size();
    EXPECT_EQ(grown.num_pieces[i], std::max<int>(1, static_cast<int>(n)));
  }
}

}  // namespace
}  // namespace subfab
