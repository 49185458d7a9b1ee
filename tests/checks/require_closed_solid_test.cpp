// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/require_closed_solid.h"

#include <gtest/gtest.h>

#include <string>

#include "support/test_shapes.h"
#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! Records what require_closed_solid reports.
class RecordingProgress : public Progress {
 public:
  void info(std::string_view text) override { infos.emplace_back(text); }
  void warn(std::string_view text) override { warnings.emplace_back(text); }
  std::vector<std::string> infos, warnings;
};

//! The message require_closed_solid throws ("" if it accepts the mesh).
std::string refusal(Mesh mesh) {
  try {
    require_closed_solid(mesh);
  } catch (const InvalidMeshError& e) {
    return e.what();
  }
  return "";
}

TEST(RequireClosedSolid, AcceptsCubeUnchanged) {
  Mesh m = test::cube();
  RecordingProgress progress;
  EXPECT_NO_THROW(require_closed_solid(m, &progress));
  EXPECT_EQ(m.faces, test::cube().faces);
  EXPECT_TRUE(progress.warnings.empty());
  EXPECT_TRUE(progress.infos.empty());
}

TEST(RequireClosedSolid, FlipsInwardMeshWithAWarning) {
  Mesh m = test::flipped(test::cube());
  RecordingProgress progress;
  require_closed_solid(m, &progress);
  EXPECT_GT(signed_volume(m), 0);
  ASSERT_EQ(progress.warnings.size(), 1u);
  EXPECT_NE(progress.warnings[0].find("inward"), std::string::npos);
}

TEST(RequireClosedSolid, RefusesAnInsideOutPartBesideTheSolid) {
  // Inward as a whole (big inward cube): flipped, and then the small cube
  // beside it is inside out: refused.
  const Mesh m = test::append(test::flipped(test::cube(Vec3::Zero(), 3.0)),
                              test::cube(Vec3(5, 0, 0), 1.0));
  EXPECT_NE(refusal(m).find("1 component is oriented inward"), std::string::npos) << refusal(m);
}

TEST(RequireClosedSolid, AcceptsACavity) {
  Mesh m = test::append(test::cube(Vec3::Zero(), 3.0),
                        test::flipped(test::cube(Vec3(1, 1, 1), 1.0)));
  RecordingProgress progress;
  EXPECT_NO_THROW(require_closed_solid(m, &progress));
  EXPECT_TRUE(progress.warnings.empty());
}

TEST(RequireClosedSolid, ReportsSeveralComponents) {
  Mesh m = test::append(test::cube(), test::cube(Vec3(5, 0, 0)));
  RecordingProgress progress;
  require_closed_solid(m, &progress);
  ASSERT_EQ(progress.infos.size(), 1u);
  EXPECT_NE(progress.infos[0].find("2 connected components"), std::string::npos);
}

TEST(RequireClosedSolid, RefusesEachBadInputClass) {
  EXPECT_NE(refusal(Mesh{}).find("no faces"), std::string::npos);
  Mesh nan = test::cube();
  nan.vertices[1].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(refusal(nan).find("NaN"), std::string::npos);
  Mesh index = test::cube();
  index.faces[3][0] = 9;
  EXPECT_NE(refusal(index).find("do not exist"), std::string::npos);
  Mesh open = test::cube();
  open.faces.pop_back();
  EXPECT_NE(refusal(open).find("not closed: 3 boundary edges in 1 hole"), std::string::npos);
  Mesh pinched = test::append(test::cube(), test::cube(Vec3(1, 1, 1)));
  weld_identical_vertices(pinched);
  EXPECT_NE(refusal(pinched).find("pinched vertex"), std::string::npos);
  Mesh flipped_face = test::cube();
  std::swap(flipped_face.faces[0][0], flipped_face.faces[0][1]);
  EXPECT_NE(refusal(flipped_face).find("not consistently oriented"), std::string::npos);
  const Mesh overlapping = test::append(test::cube(), test::cube(Vec3(0.5, 0.5, 0.5)));
  EXPECT_NE(refusal(overlapping).find("intersects itself"), std::string::npos);
  Mesh duplicate = test::cube();
  duplicate.faces.push_back(duplicate.faces[0]);
  const std::string message = refusal(duplicate);
  EXPECT_EQ(message.find("1 face repeats"), 0u) << message;  // first failure first...
  EXPECT_NE(message.find("also failing: non_manifold_edges"), std::string::npos)  // ...others named
      << message;
}

TEST(RequireClosedSolid, AcceptsTheClosedBundledModels) {
  for (const char* name : {"bunny_lowres.off", "fandisk.obj", "decimated_knight.off", "part.off"}) {
    Mesh m = read_mesh(test::data_path(name));
    EXPECT_NO_THROW(require_closed_solid(m)) << name;
  }
}

TEST(RequireClosedSolid, RefusesTeapotAsNotClosed) {
  const std::string message = refusal(read_mesh(test::data_path("teapot.obj")));
  EXPECT_EQ(message.find("the mesh is not closed: 1036 boundary edges"), 0u) << message;
}

TEST(RequireClosedSolid, RefusesCowPinchedVertex) {
  const std::string message = refusal(read_mesh(test::data_path("cow.obj")));
  EXPECT_NE(message.find("e.g. vertex 253"), std::string::npos) << message;
}

TEST(RequireClosedSolid, RefusesOpenStanfordBunny) {
  if (!test::have_shared_models()) GTEST_SKIP() << "../shared/models not present";
  const std::string message = refusal(read_mesh(test::models_path("stanford_bunny_open.obj")));
  EXPECT_EQ(message.find("the mesh is not closed: 223 boundary edges in "), 0u) << message;
}

}  // namespace
}  // namespace subfab
