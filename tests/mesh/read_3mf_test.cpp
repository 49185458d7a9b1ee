// SPDX-License-Identifier: GPL-3.0-or-later
// read_mesh() on 3MF files (read_3mf.cpp). The test writes each file itself
// with libzip: a cube, two build items of one object with transforms, an
// object made of components (one in another model part), units, a mirror;
// and bad inputs: not a zip, a zip without the model, a triangle index out of
// range, malformed XML, a missing object.
#include <gtest/gtest.h>
#include <zip.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using Entries = std::vector<std::pair<std::string, std::string>>;  // name in the zip, content

//! Writes a zip holding `entries` at `path`.
void write_zip(const std::filesystem::path& path, const Entries& entries) {
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  ASSERT_NE(z, nullptr) << error;
  for (const auto& [name, content] : entries) {
    // libzip copies nothing until zip_close: keep the buffers alive (they are in `entries`).
    zip_source_t* s = zip_source_buffer(z, content.data(), content.size(), 0);
    ASSERT_NE(s, nullptr);
    ASSERT_GE(zip_file_add(z, name.c_str(), s, ZIP_FL_OVERWRITE), 0) << zip_strerror(z);
  }
  ASSERT_EQ(zip_close(z), 0);
}

const char* kRels =
    R"(<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>)";

//! The unit cube [0,1]^3, outward, as a 3MF <object> with id `id`.
std::string cube_object(int id) {
  return "<object id=\"" + std::to_string(id) +
         R"(" type="model"><mesh><vertices>
<vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="1" y="1" z="0"/><vertex x="0" y="1" z="0"/>
<vertex x="0" y="0" z="1"/><vertex x="1" y="0" z="1"/><vertex x="1" y="1" z="1"/><vertex x="0" y="1" z="1"/>
</vertices><triangles>
<triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="3" v3="2"/><triangle v1="4" v2="5" v3="6"/>
<triangle v1="4" v2="6" v3="7"/><triangle v1="0" v2="1" v3="5"/><triangle v1="0" v2="5" v3="4"/>
<triangle v1="1" v2="2" v3="6"/><triangle v1="1" v2="6" v3="5"/><triangle v1="2" v2="3" v3="7"/>
<triangle v1="2" v2="7" v3="6"/><triangle v1="3" v2="0" v3="4"/><triangle v1="3" v2="4" v3="7"/>
</triangles></mesh></object>
)";
}

std::string model(const std::string& resources, const std::string& build, const std::string& unit = "millimeter") {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit=")" + unit +
         R"(" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
 xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06">
<resources>
)" + resources + "</resources>\n<build>" +
         build + "</build>\n</model>\n";
}

std::filesystem::path write_3mf(const std::string& file, const std::string& root_model, Entries more = {}) {
  const auto path = test::temp_dir() / file;
  Entries entries = {{"_rels/.rels", kRels}, {"3D/3dmodel.model", root_model}};
  for (auto& e : more) entries.push_back(std::move(e));
  write_zip(path, entries);
  return path;
}

std::string read_error(const std::filesystem::path& path) {
  try {
    read_mesh(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Read3mf, Cube) {
  ReadInfo info;
  const Mesh m = read_mesh(write_3mf("cube.3mf", model(cube_object(1), R"(<item objectid="1"/>)")), &info);
  EXPECT_EQ(info.format, MeshFormat::ThreeMf);
  EXPECT_EQ(format_name(info.format), "3mf");
  EXPECT_EQ(m.num_vertices(), 8u);
  EXPECT_EQ(m.num_faces(), 12u);
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0);
}

TEST(Read3mf, TwoItemsWithTransforms) {
  // The cube placed twice: as is, and scaled 2x in z then moved by (3, 0, 0).
  const Mesh m = read_mesh(write_3mf(
      "two.3mf", model(cube_object(5), R"(<item objectid="5"/><item objectid="5" transform="1 0 0 0 1 0 0 0 2 3 0 0"/>)")));
  EXPECT_EQ(m.num_faces(), 24u);
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0 + 2.0);
  const BoundingBox box = bounding_box(m);
  EXPECT_EQ(box.max.x(), 4.0);
  EXPECT_EQ(box.max.z(), 2.0);
}

TEST(Read3mf, ComponentsAreTransformedThroughEveryLevel) {
  // Object 2 = the cube moved by (0, 5, 0) + the cube scaled 2; the item moves object 2 by (10, 0, 0).
  const std::string resources = cube_object(1) + R"(<object id="2" type="model"><components>
<component objectid="1" transform="1 0 0 0 1 0 0 0 1 0 5 0"/>
<component objectid="1" transform="2 0 0 0 2 0 0 0 2 0 0 0"/>
</components></object>
)";
  const Mesh m = read_mesh(write_3mf("components.3mf", model(resources, R"(<item objectid="2" transform="1 0 0 0 1 0 0 0 1 10 0 0"/>)")));
  EXPECT_EQ(m.num_faces(), 24u);
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0 + 8.0);
  const BoundingBox box = bounding_box(m);
  EXPECT_EQ(box.min.x(), 10.0);
  EXPECT_EQ(box.max.y(), 6.0);
}

TEST(Read3mf, ComponentInAnotherModelPart) {
  // Production extension: the component's object is in 3D/Objects/cube.model.
  const std::string resources = R"(<object id="3" type="model"><components>
<component p:path="/3D/Objects/cube.model" objectid="1" transform="1 0 0 0 1 0 0 0 1 0 0 7"/>
</components></object>
)";
  const Mesh m = read_mesh(write_3mf("production.3mf", model(resources, R"(<item objectid="3"/>)"),
                                     {{"3D/Objects/cube.model", model(cube_object(1), "")}}));
  EXPECT_EQ(m.num_faces(), 12u);
  EXPECT_EQ(bounding_box(m).min.z(), 7.0);
}

TEST(Read3mf, UnitIsConvertedToMillimetres) {
  ReadInfo info;
  const Mesh m = read_mesh(write_3mf("inch.3mf", model(cube_object(1), R"(<item objectid="1"/>)", "inch")), &info);
  EXPECT_DOUBLE_EQ(bounding_box(m).max.x(), 25.4);
  ASSERT_FALSE(info.notes.empty());
  EXPECT_NE(info.notes[0].find("inch"), std::string::npos);
}

TEST(Read3mf, MirrorKeepsTheFacesOutward) {
  const Mesh m = read_mesh(
      write_3mf("mirror.3mf", model(cube_object(1), R"(<item objectid="1" transform="-1 0 0 0 1 0 0 0 1 0 0 0"/>)")));
  EXPECT_DOUBLE_EQ(bounding_box(m).min.x(), -1.0);
  EXPECT_DOUBLE_EQ(signed_volume(m), 1.0);
}

TEST(Read3mf, UnknownExtensionIsRecognisedAsAZip) {
  const auto path = write_3mf("cube.bin", model(cube_object(1), R"(<item objectid="1"/>)"));
  ReadInfo info;
  EXPECT_EQ(read_mesh(path, &info).num_faces(), 12u);
  EXPECT_EQ(info.format, MeshFormat::ThreeMf);
}

TEST(Read3mf, NotAZipIsRefused) {
  const auto path = test::temp_dir() / "text.3mf";
  std::ofstream(path) << "solid cube\nendsolid cube\n";
  const std::string e = read_error(path);
  EXPECT_NE(e.find("not a readable zip"), std::string::npos) << e;
  EXPECT_NE(e.find("text.3mf"), std::string::npos) << e;
  EXPECT_THROW(read_mesh(path), IoError);
}

TEST(Read3mf, ZipWithoutTheModelIsRefused) {
  const auto path = test::temp_dir() / "nomodel.3mf";
  write_zip(path, {{"_rels/.rels", kRels}, {"readme.txt", "hello"}});
  const std::string e = read_error(path);
  EXPECT_NE(e.find("no 3D model"), std::string::npos) << e;
  EXPECT_NE(e.find("3D/3dmodel.model"), std::string::npos) << e;
  EXPECT_THROW(read_mesh(path), IoError);
}

TEST(Read3mf, TriangleIndexOutOfRangeIsRefusedWithTheLine) {
  const std::string resources = R"(<object id="1"><mesh><vertices>
<vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/>
</vertices><triangles>
<triangle v1="0" v2="1" v3="3"/>
</triangles></mesh></object>
)";
  const auto path = write_3mf("range.3mf", model(resources, R"(<item objectid="1"/>)"));
  const std::string e = read_error(path);
  EXPECT_NE(e.find("range.3mf (3D/3dmodel.model):8:"), std::string::npos) << e;
  EXPECT_NE(e.find("v3 = 3 is out of range (the object has 3 vertices"), std::string::npos) << e;
  EXPECT_THROW(read_mesh(path), InvalidMeshError);
}

TEST(Read3mf, MalformedXmlAndMissingReferencesAreRefused) {
  const std::string bad_xml = read_error(write_3mf("xml.3mf", "<model><resources><object id=\"1\">"));
  EXPECT_NE(bad_xml.find("malformed XML"), std::string::npos) << bad_xml;
  const std::string missing = read_error(write_3mf("missing.3mf", model(cube_object(1), R"(<item objectid="9"/>)")));
  EXPECT_NE(missing.find("object 9"), std::string::npos) << missing;
  const std::string no_build = read_error(write_3mf("nobuild.3mf", model(cube_object(1), "")));
  EXPECT_NE(no_build.find("no <build> item"), std::string::npos) << no_build;
  const std::string nan = read_error(write_3mf(
      "nan.3mf", model(R"(<object id="1"><mesh><vertices><vertex x="nan" y="0" z="0"/></vertices></mesh></object>)",
                       R"(<item objectid="1"/>)")));
  EXPECT_NE(nan.find("not finite"), std::string::npos) << nan;
  const std::string cycle = read_error(write_3mf(
      "cycle.3mf", model(R"(<object id="1"><components><component objectid="1"/></components></object>)",
                         R"(<item objectid="1"/>)")));
  EXPECT_NE(cycle.find("cycle"), std::string::npos) << cycle;
}

}  // namespace
}  // namespace subfab
