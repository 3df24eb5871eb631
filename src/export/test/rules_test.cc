// The export rules: static and free bodies, shapes, colours, inertia, names, warnings, and
// reading a scene back from its JSON line to the same bodies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "export/test/example_scenes.h"
#include "output/scene_json.h"

namespace prs::exporting {
namespace {

using testing_scenes::ExampleScenes;
using testing_scenes::SampleText;

const Body* FindByClass(const ExportScene& scene, const std::string& cls) {
  for (const Body& body : scene.bodies) {
    if (body.class_name == cls) return &body;
  }
  return nullptr;
}

TEST(RulesTest, TableCubeHasStaticFurnitureAndAFreeCube) {
  const auto& scenes = ExampleScenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& example : scenes) {
    if (example.label.rfind("table_cube.prs", 0) != 0) continue;
    const ExportScene& scene = example.exported;
    ASSERT_EQ(scene.bodies.size(), 7u) << example.label;  // table, 2 robots, 2 trays, cube, camera
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    for (const char* cls : {"Table", "Robot", "Tray", "Camera"}) {
      ASSERT_NE(FindByClass(scene, cls), nullptr);
      EXPECT_FALSE(FindByClass(scene, cls)->is_free()) << cls;
    }
    const Body& cube = *FindByClass(scene, "Cube");
    EXPECT_EQ(cube.name, "Cube_5");
    EXPECT_DOUBLE_EQ(cube.mass_kg, 0.1);
    EXPECT_NEAR(cube.inertia_diag.x(), 0.1 * (2 * 0.05 * 0.05) / 12, 1e-15);
    EXPECT_EQ(cube.color.b, 1.0);
    EXPECT_EQ(cube.shape, Shape::kBox);
    EXPECT_FALSE(FindByClass(scene, "Camera")->collides);         // allowCollisions: True
    EXPECT_DOUBLE_EQ(FindByClass(scene, "Table")->color.r, 0.5);  // color "0.5"
  }
}

TEST(RulesTest, BodiesKeepTheScenesPosesExactly) {
  for (const auto& example : ExampleScenes()) {
    ASSERT_EQ(example.exported.bodies.size(), example.scene->objects.size());
    for (size_t i = 0; i < example.scene->objects.size(); ++i) {
      const lang::SceneObject& object = example.scene->objects[i];
      const Body& body = example.exported.bodies[i];
      EXPECT_EQ(body.p_WO, object.p_WO) << example.label << " " << body.name;
      EXPECT_EQ(body.size, object.dimensions);
      EXPECT_TRUE(testing_scenes::SameRotation(body.R_WO, object.R_WO, 1e-15));
    }
  }
}

TEST(RulesTest, ShapeTypeMassAndColourForms) {
  const lang::Scene& scene = SampleText(
      "from model import *\n"
      "a = Cup at V3D(0, 0, 0.05)\n"
      "b = Gear at V3D(0.5, 0, 0.01), with color V3D(1, 0, 0)\n"
      "c = Chair at V3D(-1, 0, 0.45), with mass 5, with shape_type \"box\"\n");
  const ExportScene exported = MakeExportScene(scene, "t");
  ASSERT_EQ(exported.bodies.size(), 3u);
  const Body& cup = exported.bodies[0];
  EXPECT_EQ(cup.shape, Shape::kCylinder);
  EXPECT_NEAR(cup.inertia_diag.z(), 0.2 * 0.04 * 0.04 / 2, 1e-15);
  EXPECT_NEAR(cup.inertia_diag.x(), 0.2 * (3 * 0.04 * 0.04 + 0.1 * 0.1) / 12, 1e-15);
  EXPECT_EQ(exported.bodies[1].color.r, 1.0);
  EXPECT_EQ(exported.bodies[1].color.g, 0.0);
  EXPECT_TRUE(exported.bodies[2].is_free());
  EXPECT_TRUE(exported.warnings.empty());
}

// The original tool's Cube has no mass: static by the rules. SetMass makes it free with the
// inertia the rules give the same cube with that `mass` written in the program.
TEST(RulesTest, SetMassGivesTheRulesFreeBody) {
  const lang::Scene& scene = SampleText(
      "from paper_model import *\n"
      "a = Cube at V3D(0, 0, 0.02)\n"
      "b = Cube at V3D(0.5, 0, 0.02), with mass 0.064\n"
      "class Can:\n    width: 0.08\n    length: 0.08\n    height: 0.1\n"
      "    shape_type: \"cylinder\"\n"
      "c = Can at V3D(1, 0, 0.05)\n");
  ExportScene exported = MakeExportScene(scene, "t");
  ASSERT_EQ(exported.bodies.size(), 3u);
  Body& massless = exported.bodies[0];
  EXPECT_FALSE(massless.is_free());
  EXPECT_NEAR(CalcVolume(massless), 0.04 * 0.04 * 0.04, 1e-18);
  SetMass(massless, 0.064);
  EXPECT_TRUE(massless.is_free());
  EXPECT_EQ(massless.mass_kg, exported.bodies[1].mass_kg);
  EXPECT_EQ(massless.inertia_diag, exported.bodies[1].inertia_diag);
  EXPECT_NEAR(massless.inertia_diag.x(), 0.064 * 2 * 0.04 * 0.04 / 12, 1e-18);
  EXPECT_NEAR(CalcVolume(exported.bodies[2]), M_PI * 0.04 * 0.04 * 0.1, 1e-15);  // a cylinder
  EXPECT_THROW(SetMass(massless, 0), std::invalid_argument);
  EXPECT_THROW(SetMass(massless, std::nan("")), std::invalid_argument);
  Body point = exported.bodies[0];
  point.shape = Shape::kNone;
  EXPECT_EQ(CalcVolume(point), 0);
  EXPECT_THROW(SetMass(point, 1), std::invalid_argument);
}

// Built-in shapes go out natively when round, else as their polytope (a mesh without a file).
TEST(RulesTest, BuiltInShapesAreNativeWhenRound) {
  const lang::Scene& scene = SampleText(
      "from model import *\n"
      "class S:\n"
      "    width: 0.1\n"
      "    length: 0.1\n"
      "    height: 0.1\n"
      "    mass: 1\n"
      "a = S at V3D(-0.75, 0, 0.2), with shape Cylinder()\n"
      "b = S at V3D(-0.45, 0, 0.2), with shape Cylinder(), with width 0.2\n"
      "c = S at V3D(-0.15, 0, 0.2), with shape Sphere()\n"
      "d = S at V3D(0.15, 0, 0.2), with shape Sphere(), with height 0.05\n"
      "e = S at V3D(0.45, 0, 0.2), with shape Capsule(), with height 0.3\n"
      "f = S at V3D(0.75, 0, 0.2), with shape Capsule(), with height 0.05\n");
  const ExportScene exported = MakeExportScene(scene, "t");
  ASSERT_EQ(exported.bodies.size(), 6u);
  const Shape expected[] = {Shape::kCylinder, Shape::kMesh,    Shape::kSphere,
                            Shape::kMesh,     Shape::kCapsule, Shape::kMesh};
  for (size_t i = 0; i < 6; ++i) {
    const Body& body = exported.bodies[i];
    EXPECT_EQ(body.shape, expected[i]) << body.name;
    ASSERT_TRUE(body.primitive) << body.name;
    ASSERT_NE(body.mesh, nullptr) << body.name;
    EXPECT_FALSE(body.has_mesh_file());
    EXPECT_EQ(body.mesh->extents, body.size) << body.name;
  }
  EXPECT_NEAR(exported.bodies[2].inertia_diag.x(), 1 * 0.05 * 0.05 * 2 / 5, 1e-15);
  // The capsule (radius 0.05, height 0.3) against a sum over a fine grid of its volume.
  const double r = 0.05, s = 0.2, step = 0.0025;
  double mass = 0, axial = 0, across = 0;
  for (double x = -r + step / 2; x < r; x += step) {
    for (double y = -r + step / 2; y < r; y += step) {
      for (double z = -0.15 + step / 2; z < 0.15; z += step) {
        const double t = std::clamp(z, -s / 2, s / 2);
        if (x * x + y * y + (z - t) * (z - t) > r * r) continue;
        mass += 1, axial += x * x + y * y, across += y * y + z * z;
      }
    }
  }
  const Eigen::Vector3d& inertia = exported.bodies[4].inertia_diag;
  EXPECT_NEAR(inertia.z(), axial / mass, 0.01 * inertia.z());
  EXPECT_NEAR(inertia.x(), across / mass, 0.01 * inertia.x());
  EXPECT_EQ(inertia.x(), inertia.y());
}

TEST(RulesTest, UnreadablePropertiesWarnAndFallBack) {
  const lang::Scene& scene = SampleText(
      "from model import *\n"
      "Cube at V3D(0, 0, 0.5), with color \"bleu\", with mass \"heavy\", with shape_type "
      "\"cone\"\n");
  const ExportScene exported = MakeExportScene(scene, "t");
  ASSERT_EQ(exported.bodies.size(), 1u);
  ASSERT_EQ(exported.warnings.size(), 3u);
  EXPECT_NE(exported.warnings[0].find("cone"), std::string::npos) << exported.warnings[0];
  EXPECT_NE(exported.warnings[1].find("'bleu'"), std::string::npos) << exported.warnings[1];
  EXPECT_NE(exported.warnings[2].find("Cube_0"), std::string::npos) << exported.warnings[2];
  EXPECT_FALSE(exported.bodies[0].is_free());
  EXPECT_EQ(exported.bodies[0].shape, Shape::kBox);
}

TEST(RulesTest, NamesAreUniqueIdentifiers) {
  const lang::Scene& scene = SampleText(
      "from model import *\n"
      "world = Cube at V3D(0, 0, 0.5)\n"
      "Cube at V3D(1, 0, 0.5)\n"
      "Cube_2 = Cube at V3D(0, 1, 0.5)\n"
      "Cube at V3D(1, 1, 0.5)\n");
  const ExportScene exported = MakeExportScene(scene, "t");
  ASSERT_EQ(exported.bodies.size(), 4u);
  EXPECT_EQ(exported.bodies[0].name, "world_2");  // "world" is the URDF root link
  EXPECT_EQ(exported.bodies[1].name, "Cube_1");
  EXPECT_EQ(exported.bodies[2].name, "Cube_2");
  EXPECT_EQ(exported.bodies[3].name, "Cube_3");
}

TEST(RulesTest, ReadingTheJsonLineGivesTheSameBodies) {
  for (const auto& example : ExampleScenes()) {
    sampling::SampledScene sampled;
    sampled.scene = *example.scene;
    const ExportScene read = ReadSceneJson(output::FormatSceneJson(sampled));
    ASSERT_EQ(read.bodies.size(), example.exported.bodies.size()) << example.label;
    for (size_t i = 0; i < read.bodies.size(); ++i) {
      const Body& a = read.bodies[i];
      const Body& b = example.exported.bodies[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.class_name, b.class_name);
      EXPECT_EQ(a.p_WO, b.p_WO) << a.name;  // shortest round-trip digits: exact
      // The writer goes through the rotation matrix (CanonicalQuaternion): a few ulps of 1
      // (1.2e-15 rad for a yawed cube of bin_clutter.prs).
      EXPECT_TRUE(testing_scenes::SameRotation(a.R_WO, b.R_WO, 4e-15)) << example.label;
      EXPECT_EQ(a.size, b.size);
      EXPECT_EQ(a.shape, b.shape);
      EXPECT_EQ(a.primitive, b.primitive) << a.name;
      EXPECT_EQ(a.mass_kg, b.mass_kg);
      EXPECT_EQ(a.collides, b.collides);
      EXPECT_EQ(a.color.r, b.color.r);
    }
  }
}

TEST(RulesTest, MalformedJsonLinesAreRefusedWithTheField) {
  auto message = [](const std::string& line) {
    try {
      ReadSceneJson(line);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("{"), "not valid JSON");
  EXPECT_NE(message("{\"format\":\"other\"}").find("prs-scene/1"), std::string::npos);
  EXPECT_EQ(message("{\"format\":\"prs-scene/1\",\"objects\":[{\"name\":null,\"class\":\"A\","
                    "\"position\":[0,0],\"orientation\":{\"quaternion\":[1,0,0,0]},"
                    "\"dimensions\":[1,1,1]}]}"),
            "object 0: \"position\" is not 3 numbers");
  EXPECT_EQ(message("{\"format\":\"prs-scene/1\",\"objects\":[{\"name\":null,\"class\":\"A\","
                    "\"position\":[0,0,0],\"dimensions\":[1,1,1]}]}"),
            "object 0 has no \"orientation\"");
}

TEST(RulesTest, FormatNamesRoundTrip) {
  for (const char* name : {"mjcf", "urdf", "sdf", "usda", "gltf", "glb"}) {
    const auto format = ParseFormat(name);
    ASSERT_TRUE(format.has_value()) << name;
    EXPECT_STREQ(FormatName(*format), name);
  }
  EXPECT_FALSE(ParseFormat("MJCF"));
  EXPECT_EQ(std::string(FileExtension(Format::kMjcf)), ".xml");
}

}  // namespace
}  // namespace prs::exporting
