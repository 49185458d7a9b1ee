// SPDX-License-Identifier: GPL-3.0-or-later
// Regression: kitten --max-height 0.05, block 040's machine STL
// self-intersected once rounded to float32 (issue 17); export now cleans it.
#include "decompose/single_precision_cleanup.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "subfab/decompose/export_decomposition.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/mesh/write_mesh.h"
#include "subfab/validate/check_single_precision.h"
#include "subfab/validate/validate_decomposition.h"
#include "support/block_test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using test::float32_frustum;

TEST(SinglePrecisionCleanup, VertexRoundedThroughAFaceIsRoundedTheOtherWay) {
  Mesh machine = float32_frustum(), block = float32_frustum();
  ASSERT_FALSE(check_single_precision(machine).ok());
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.num_collapsed, 0u);
  EXPECT_GE(r.num_nudged, 1u);
  EXPECT_TRUE(check_single_precision(machine).ok());
  // Every machine coordinate is a float within one float spacing of the original.
  const Mesh original = float32_frustum();
  for (std::size_t v = 0; v < machine.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(machine.vertices[v][k], static_cast<double>(static_cast<float>(machine.vertices[v][k])));
      EXPECT_LE(std::abs(machine.vertices[v][k] - original.vertices[v][k]), 1.2e-7);
    }
  EXPECT_EQ(block.faces, machine.faces);  // the block keeps the machine mesh's faces
}

TEST(SinglePrecisionCleanup, SolidMeshIsLeftAlone) {
  Mesh machine = test::box_solid({0, 0, 0}, {1, 2, 3}), block = machine;
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.num_collapsed + r.num_nudged + r.num_faces_removed, 0u);
  EXPECT_EQ(machine.vertices, test::box_solid({0, 0, 0}, {1, 2, 3}).vertices);
}

TEST(SinglePrecisionCleanup, SheetThinnerThanAFloatIsReported) {
  // Issue 17's 4.3 x 2.4 x 1.3e-7 sheet, at z = 1 (thinner than float32's
  // spacing there): it collapses entirely, which no rounding can save.
  Mesh machine = test::box_solid({0, 0, 1}, {4.3, 2.4, 1 + 4e-8}), block = machine;
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.num_collapsed, 4u);
}

TEST(SinglePrecisionCleanup, ClusterOfNearlyCoincidentVerticesIsCollapsedAlongItsEdges) {
  // Regression: pinion.off at the default settings, block 761 (axis -x): box
  // planes cut a cluster of 9 vertices within 2e-8 of each other (edges down
  // to 1e-9) on the plane y = 0.2867; in float32 some of them weld, others
  // stay one float apart, and merging the welded ones left 10 non-manifold
  // edges, 4 zero-area faces and 7 crossing pairs (validate check 8 failed).
  Mesh block = read_mesh(test::data_path("regression/pinion_block_761.obj"));
  Mesh machine = machine_mesh_of(block, Axis::NegX, Eigen::Matrix3d::Identity());
  ASSERT_FALSE(check_single_precision(machine).ok());
  const Mesh original = machine;
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(check_single_precision(machine).ok());
  EXPECT_EQ(block.faces, machine.faces);
  EXPECT_EQ(block.num_vertices(), machine.num_vertices());
  // Only sub-float features went: a handful of vertices and their faces.
  EXPECT_LE(r.num_collapsed, 12u);
  EXPECT_GE(machine.num_faces() + 2 * 12, original.num_faces());
}

//! A block cleaned for float32 is still the block: closed solid, height
//! field along `axis`, same volume within `rel`, the machine mesh its
//! rigid move (same faces), and its STL a solid.
void expect_same_block(const Mesh& original, const Mesh& block, const Mesh& machine, Axis axis,
                       const Eigen::Matrix3d& to_machine, double rel) {
  EXPECT_TRUE(check_single_precision(machine).ok());
  // what the STL file really holds, read back
  const std::filesystem::path stl = test::temp_dir() / "machine.stl";
  write_mesh(machine, stl);
  EXPECT_TRUE(check_single_precision(read_mesh(stl)).ok());
  EXPECT_TRUE(check_closed_solid(block).ok());
  EXPECT_TRUE(check_height_field(block, axis_direction(axis)).ok());
  EXPECT_EQ(block_defect(block, axis_direction(axis), bounding_box(original).diagonal()), "");
  EXPECT_NEAR(signed_volume(block), signed_volume(original), rel * signed_volume(original));
  EXPECT_EQ(block.faces, machine.faces);
  ASSERT_EQ(block.num_vertices(), machine.num_vertices());
  // the float rounding (and a nudge to the other float) moves a vertex by
  // at most one float spacing per coordinate: at least 1e-7 here
  const double spacing = std::max(1e-7, std::ldexp(largest_coordinate(machine), -23));
  const Vec3 shift = machine.vertices.front() - to_machine * block.vertices.front();
  for (std::size_t v = 0; v < block.num_vertices(); ++v)
    EXPECT_LE((to_machine * block.vertices[v] + shift - machine.vertices[v]).norm(), std::sqrt(3.0) * spacing);
  // every vertex stays within a few float spacings of the original block's box
  BoundingBox box = bounding_box(original);
  for (const Vec3& v : block.vertices)
    EXPECT_TRUE((v.array() >= box.min.array() - spacing).all() && (v.array() <= box.max.array() + spacing).all());
}

//! A regression block of data/regression read, put in its machine frame
//! (not a solid in float32 there) and cleaned with the frame.
struct CleanedBlock {
  Mesh original, block, machine;
  Eigen::Matrix3d to_machine;
  detail::SinglePrecisionCleanup result;
};

//! With `checked`, the cleanup is export's own (clean_block_for_stl(): a
//! repair kept only when the block passes block_defect()), the one decompose's
//! merge checks call too.
CleanedBlock clean_regression_block(const std::string& file, Axis axis, bool checked = false) {
  CleanedBlock c;
  c.original = read_mesh(test::data_path("regression/" + file));
  c.block = c.original;
  c.to_machine = axis_to_machine(axis);
  c.machine = machine_mesh_of(c.block, axis, Eigen::Matrix3d::Identity());
  EXPECT_FALSE(check_single_precision(c.machine).ok()) << file << " is already a solid in float32";
  const double diagonal = bounding_box(c.original).diagonal();
  c.result = checked ? detail::clean_block_for_stl(c.machine, c.block, c.to_machine, axis_direction(axis), diagonal,
                                                   FinalizeOptions{})
                     : detail::clean_single_precision(c.machine, c.block, &c.to_machine);
  return c;
}

TEST(SinglePrecisionCleanup, NoisyCoordinatesAreSnappedToTheirPlaneAndNeedlesSplit) {
  // Regression: couplingdown.off at the default settings, block 082 (axis
  // +x): the input's plane y = 0 has vertices at y = -1.5e-8 .. 2.6e-9 (CAD
  // noise); shifted to the machine frame (y + 0.077) they round to one
  // float, faces between them lose their area or cross (validate check 8).
  // Merging equal floats and collapsing short edges could not repair it; the
  // coordinates within 4 float spacings of each other are now snapped to one
  // value first, and the needles that leaves are split.
  const CleanedBlock c = clean_regression_block("couplingdown_block_082.obj", Axis::PosX);
  EXPECT_TRUE(c.result.ok);
  expect_same_block(c.original, c.block, c.machine, Axis::PosX, c.to_machine, 1e-6);
  Mesh block = c.original, machine = machine_mesh_of(block, Axis::PosX, Eigen::Matrix3d::Identity());
  // Without the frame (no snap), the needles the rounding flattens are now
  // split after it (the bimba regression below), which repairs this block too.
  EXPECT_TRUE(detail::clean_single_precision(machine, block).ok);
  expect_same_block(c.original, block, machine, Axis::PosX, c.to_machine, 1e-6);
}

TEST(SinglePrecisionCleanup, AFlattenedBumpIsRemovedNotFolded) {
  // Regression: couplingdown.off at the default (within the fallback 5e-4),
  // block 024 (axis -x): a vertex 1e-8 off the plane y = 0 with three faces
  // (a bump a float high). Snapped onto the plane, its three faces folded
  // over each other (4 crossing pairs); now the vertex goes and its faces
  // become one triangle.
  const CleanedBlock c = clean_regression_block("couplingdown_tol_block_024.obj", Axis::NegX);
  EXPECT_TRUE(c.result.ok);
  expect_same_block(c.original, c.block, c.machine, Axis::NegX, c.to_machine, 1e-6);
}

TEST(SinglePrecisionCleanup, SubFloatFinOnABlocksSideIsRemoved) {
  // Regression: couplingdown.off at the default settings, block 013 (axis
  // -x): a box plane through a vertex at y = -2.6e-9 left a fin 2.6e-9
  // thick between it and the plane y = 0 on the block's side. It was first
  // clipped off; since the rounding is right for every coordinate (float32.h),
  // merging what rounds to the same float welds it (2 vertices).
  const CleanedBlock c = clean_regression_block("couplingdown_block_013.obj", Axis::NegX, true);
  EXPECT_TRUE(c.result.ok);
  EXPECT_LE(c.result.num_collapsed, 4u);
  expect_same_block(c.original, c.block, c.machine, Axis::NegX, c.to_machine, 1e-6);
}

TEST(SinglePrecisionCleanup, AWeldThatIsASolidInFloat32ButNotWhenWrittenIsRefused) {
  // Regression: couplingdown.off at --tolerance 1e-3 (2026-12-05), block 053
  // (axis +z): the cleanup's own rounding left x and y unrounded (GCC 12.2
  // -O3, see float32.h), so it saw a solid where the STL written had 2
  // zero-area faces and 5 non-manifold edges (validate check 8).
  const CleanedBlock c = clean_regression_block("couplingdown_tol_block_053.obj", Axis::PosZ, true);
  EXPECT_TRUE(c.result.ok);
  expect_same_block(c.original, c.block, c.machine, Axis::PosZ, c.to_machine, 1e-6);
}

TEST(SinglePrecisionCleanup, ARepairThatFoldsTheBlockInDoublesIsNotKept) {
  // Regression: couplingdown.off at --tolerance 1e-3 (2026-12-05), block 049
  // (axis +y, top on the noisy plane y = -8.9e-9): merging two vertices that
  // round to one float moved the block's vertex too, and one face of its top
  // turned over (cosine -1) and crossed its neighbours (validate checks 1, 2),
  // though the STL was a solid. That repair is refused now; the next one
  // (coordinates snapped to their plane first) keeps the block valid.
  Mesh block = read_mesh(test::data_path("regression/couplingdown_tol_block_049.obj"));
  const double diagonal = bounding_box(block).diagonal();
  Mesh machine = machine_mesh_of(block, Axis::PosY, Eigen::Matrix3d::Identity());
  const Eigen::Matrix3d to_machine = axis_to_machine(Axis::PosY);
  const detail::SinglePrecisionCleanup unchecked = detail::clean_single_precision(machine, block, &to_machine);
  ASSERT_TRUE(unchecked.ok);                                                     // the float32 mesh alone is fine,
  EXPECT_NE(block_defect(block, axis_direction(Axis::PosY), diagonal), "");  // not the block
  const CleanedBlock c = clean_regression_block("couplingdown_tol_block_049.obj", Axis::PosY, true);
  EXPECT_TRUE(c.result.ok);
  EXPECT_FALSE(c.result.block_invalid);
  expect_same_block(c.original, c.block, c.machine, Axis::PosY, c.to_machine, 1e-6);
}

TEST(SinglePrecisionCleanup, ANeedleOnlyTheRoundingFlattensIsSplit) {
  // Regression: bimba.obj at --tolerance 7.5e-3 (2026-12-05), block 027
  // (axis +y, 13228 faces): a sliver triangle of its base's triangulation,
  // corners 4e-4 to 9e-4 apart but less than a float spacing off one line,
  // became a zero-area face in float32, crossing 3 neighbours (validate
  // check 8). Nothing short to collapse, no plane noise to snap: the needle
  // is now split across its long edge after the rounding.
  const CleanedBlock c = clean_regression_block("bimba_tol_block_027.obj", Axis::PosY);
  EXPECT_TRUE(c.result.ok);
  EXPECT_GE(c.result.num_faces_removed, 1u);
  expect_same_block(c.original, c.block, c.machine, Axis::PosY, c.to_machine, 1e-6);
}

}  // namespace
}  // namespace subfab

