// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/read_skeleton.h"

#include <gtest/gtest.h>

#include <sstream>

#include "subfab/core/error.h"
#include "subfab/hex/write_skeleton.h"
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

std::string error_of(const std::string& text) {
  std::istringstream in(text);
  try {
    read_skeleton(in, "t.skel");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadSkeleton, RoundTripIsExact) {
  Skeleton s = test::y_skeleton(4);
  s.points[3] = Vec3(0.1, 1.0 / 3.0, -2e-7);
  std::stringstream io;
  write_skeleton(s, io);
  const Skeleton back = read_skeleton(io, "mem");
  ASSERT_EQ(back.num_nodes(), s.num_nodes());
  for (std::size_t v = 0; v < s.num_nodes(); ++v) {
    EXPECT_EQ(back.points[v], s.points[v]);
    EXPECT_EQ(back.radii[v], s.radii[v]);
    EXPECT_EQ(back.neighbors[v], s.neighbors[v]);
  }
}

TEST(ReadSkeleton, ReadsTheLivesuFormat) {
  std::istringstream in(
      "ID Cx Cy Cz RADIUS #NEIGHBORS NEIGHBORS_LIST\n3\n0 0 0 0 1 1 1\n1 1 0 0 1 2 0 2\n2 2 0 0 0.5 1 1\n");
  const Skeleton s = read_skeleton(in, "mem");
  ASSERT_EQ(s.num_nodes(), 3u);
  EXPECT_EQ(s.radii[2], 0.5);
  EXPECT_EQ(s.neighbors[1], (std::vector<int>{0, 2}));
}

TEST(ReadSkeleton, BadIndexNamesTheLine) {
  const std::string e = error_of("ID Cx Cy Cz RADIUS #NEIGHBORS NEIGHBORS_LIST\n2\n0 0 0 0 1 1 1\n1 1 0 0 1 1 7\n");
  EXPECT_NE(e.find("t.skel:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("out of range"), std::string::npos) << e;
}

TEST(ReadSkeleton, MissingNodeCountNamesTheLine) {
  const std::string e = error_of("ID Cx Cy Cz RADIUS #NEIGHBORS NEIGHBORS_LIST\n0 0 0 0 1 1 1\n");
  EXPECT_NE(e.find("t.skel:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("node count"), std::string::npos) << e;
}

TEST(ReadSkeleton, AsymmetricAndTruncatedFilesAreRejected) {
  EXPECT_NE(error_of("2\n0 0 0 0 1 1 1\n1 1 0 0 1 0\n").find("does not list it back"), std::string::npos);
  EXPECT_NE(error_of("3\n0 0 0 0 1 0\n").find("ends after 1 of 3"), std::string::npos);
  EXPECT_NE(error_of("1\n0 0 0 0 -1 0\n").find("radius"), std::string::npos);
}

}  // namespace
}  // namespace subfab
