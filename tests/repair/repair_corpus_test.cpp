// SPDX-License-Identifier: GPL-3.0-or-later
// The whole crafted bad-input corpus (data/regression/bad_inputs) through what
// `subfab repair FILE` does: read_mesh(), then repair_mesh(), then the result
// checked with analyze_mesh(). Every file is either repaired into a solid that
// passes every check, or refused with a subfab::Error whose message says what
// is wrong; never a crash. `make test` runs this under AddressSanitizer and
// UndefinedBehaviorSanitizer (SUBFAB_REPAIR_ONLY + SUBFAB_SANITIZE, build-asan/).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "subfab/checks/analyze_mesh.h"
#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/repair/repair_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

enum class Outcome { Repaired, RefusedByReader, RefusedByRepair };

struct Expected {
  Outcome outcome;
  std::string message_part;  // refusals: a part of the message
};

//! Every file of the corpus and what `subfab repair` (default options) does with it.
const std::map<std::string, Expected>& corpus() {
  static const std::map<std::string, Expected> files = {
      {"cube_flipped_face.obj", {Outcome::Repaired, ""}},
      {"cube_duplicated_face.obj", {Outcome::Repaired, ""}},
      {"cube_zero_area_sliver.obj", {Outcome::Repaired, ""}},
      {"sphere_inward.obj", {Outcome::Repaired, ""}},
      {"two_cubes_touching_at_vertex.obj", {Outcome::Repaired, ""}},
      {"two_overlapping_cubes.obj", {Outcome::RefusedByRepair, "--max-deviation"}},
      {"cube_hole.obj", {Outcome::RefusedByRepair, "--max-deviation"}},
      {"open_triangle.obj", {Outcome::RefusedByRepair, "encloses no volume"}},
      {"empty.obj", {Outcome::RefusedByReader, "empty"}},
      {"random_bytes.stl", {Outcome::RefusedByReader, "truncated"}},
      {"nan_coordinates.obj", {Outcome::RefusedByReader, "non-finite"}},
  };
  return files;
}

TEST(RepairCorpus, EveryFileOfTheCorpusIsListed) {
  // A file added to the corpus must get its expected outcome here.
  std::vector<std::string> on_disk;
  for (const auto& entry : std::filesystem::directory_iterator(test::data_path("regression/bad_inputs")))
    if (entry.path().extension() != ".py") on_disk.push_back(entry.path().filename().string());
  std::sort(on_disk.begin(), on_disk.end());
  std::vector<std::string> listed;
  for (const auto& [name, expected] : corpus()) listed.push_back(name);
  EXPECT_EQ(on_disk, listed);
}

TEST(RepairCorpus, EachFileIsRepairedOrRefusedWithTheReason) {
  for (const auto& [name, expected] : corpus()) {
    SCOPED_TRACE(name);
    Mesh input;
    try {
      input = read_mesh(test::data_path("regression/bad_inputs/" + name));
    } catch (const Error& e) {
      EXPECT_EQ(expected.outcome, Outcome::RefusedByReader) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected.message_part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << "the message names the file: " << e.what();
      continue;
    }
    ASSERT_NE(expected.outcome, Outcome::RefusedByReader);
    try {
      const MeshRepairResult r = repair_mesh(input);
      EXPECT_EQ(expected.outcome, Outcome::Repaired) << "repaired: " << r.report.applied_steps();
      const MeshReport after = analyze_mesh(r.mesh);
      for (const auto& c : after.checks) EXPECT_FALSE(c.failed()) << c.name << ": " << c.message;
      EXPECT_GT(signed_volume(r.mesh), 0.0);
      EXPECT_TRUE(r.report.changed());
      EXPECT_LE(r.report.max_deviation_fraction(), MeshRepairOptions{}.max_deviation);
    } catch (const InvalidMeshError& e) {
      EXPECT_EQ(expected.outcome, Outcome::RefusedByRepair) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected.message_part), std::string::npos) << e.what();
    }
  }
}
// (With --max-deviation 0.5 the two refused for their deviation are repaired:
// repair_mesh_test.cpp, OverlappingCubesBecomeTheirUnion, HoleIsClosedFlatWhenAllowed.)

}  // namespace
}  // namespace subfab
