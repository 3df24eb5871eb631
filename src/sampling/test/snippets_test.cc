// One test per construct the language issue lists: each snippet, written as users of the
// original tool write it, compiles and samples, and its relation is checked on the sampled
// values with plain arithmetic (scene_checks.h), over many scenes.
#include <gtest/gtest.h>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using Eigen::Vector3d;
using lang::Scene;
using lang::SceneObject;
using namespace testing_checks;

constexpr int kScenes = 200;

// Samples `count` scenes of `text` (seed 11) and calls `check` on each.
template <typename Check>
void ForEachScene(const std::string& text, Check check, int count = kScenes) {
  auto program = CompileOrDie(text);
  ASSERT_NE(program, nullptr);
  for (int i = 0; i < count; ++i) {
    SCOPED_TRACE("scene " + std::to_string(i));
    check(SampleScene(*program, 11, i).scene);
  }
}

std::string StringProperty(const SceneObject& o, const std::string& name) {
  const lang::Value* v = o.FindProperty(name);
  using String = std::shared_ptr<const std::string>;
  return v && v->Is<String>() ? *v->As<String>() : "<missing>";
}

TEST(SnippetTest, ModelFileInTheOriginalToolsStyle) {
  ForEachScene(R"("""A model file: docstring, math, module-level numbers, classes."""
import math

width = 2
length = 1.5
height = 1.2
workspace = Cuboid(Vector3D(0, 0, height / 2.0), Vector3D(0, 0, 0), width, length, height)
floor = Rectangle3D(width, length, Vector3D(0, 0, 0), Vector3D(0, 0, 0))

class Crate:
    width: 0.3
    length: 0.2
    height: 0.1 * math.sqrt(4)
    color: "0.25"
    model_name: 'crate'

crate = Crate on floor
)",
               [](const Scene& scene) {
                 const SceneObject& crate = Find(scene, "crate");
                 EXPECT_EQ(crate.dimensions, Vector3d(0.3, 0.2, 0.2));
                 EXPECT_EQ(StringProperty(crate, "color"), "0.25");
                 EXPECT_EQ(StringProperty(crate, "model_name"), "crate");
                 EXPECT_NEAR(crate.p_WO.z(), 0.1, kTol);  // on the floor at z = 0
                 // The workspace keeps the whole box inside 2 m x 1.5 m.
                 EXPECT_LE(std::abs(crate.p_WO.x()), 1.0 - 0.15 + kTol);
                 EXPECT_LE(std::abs(crate.p_WO.y()), 0.75 - 0.1 + kTol);
               });
}

TEST(SnippetTest, RobotOnTopBackOfTableMinusOffset) {
  ForEachScene(R"(from model import *
table = Table on floor
r = Robot on (top back table).position - Vector3D(0.4, 0, 0), with color "0.5"
)",
               [](const Scene& scene) {
                 const SceneObject& table = Find(scene, "table");
                 const SceneObject& r = Find(scene, "r");
                 EXPECT_NEAR(r.p_WO.x(), table.p_WO.x() - 0.4, kTol);
                 EXPECT_NEAR(r.p_WO.y(), table.p_WO.y() - table.dimensions.y() / 2, kTol);
                 EXPECT_NEAR(r.p_WO.z(), table.dimensions.z() + r.dimensions.z() / 2, kTol);
                 EXPECT_EQ(StringProperty(r, "color"), "0.5");
               });
}

TEST(SnippetTest, CameraAtVectorOfTableCoordinatesPlusRanges) {
  double min_dx = 1, max_dx = -1;
  ForEachScene(R"(from model import *
table = Table on floor
Camera at Vector3D(table.x + (-0.1, 0.1), table.y + (-0.1, 0.1), (1.9, 2.1))
)",
               [&](const Scene& scene) {
                 const SceneObject& table = Find(scene, "table");
                 const SceneObject& camera = FindClass(scene, "Camera");
                 const Vector3d d = camera.p_WO - table.p_WO;
                 EXPECT_LE(std::abs(d.x()), 0.1);
                 EXPECT_LE(std::abs(d.y()), 0.1);
                 EXPECT_GE(camera.p_WO.z(), 1.9);
                 EXPECT_LE(camera.p_WO.z(), 2.1);
                 min_dx = std::min(min_dx, d.x());
                 max_dx = std::max(max_dx, d.x());
               });
  // The ranges are drawn afresh per scene and cover their interval.
  EXPECT_LT(min_dx, -0.09);
  EXPECT_GT(max_dx, 0.09);
}

TEST(SnippetTest, CupCompletelyOnTableAlignedWithAnotherCup) {
  ForEachScene(R"(from model import *
table_1 = Table on floor
cup_1 = Cup completely on table_1
cup_2 = Cup completely on table_1, aligned with cup_1 by "y"
)",
               [](const Scene& scene) {
                 const SceneObject& table = Find(scene, "table_1");
                 const SceneObject& cup_1 = Find(scene, "cup_1");
                 const SceneObject& cup_2 = Find(scene, "cup_2");
                 ExpectCompletelyOn(cup_2, table);
                 EXPECT_NEAR(cup_2.p_WO.y(), cup_1.p_WO.y(), kTol);
                 EXPECT_GE(std::abs(cup_2.p_WO.x() - cup_1.p_WO.x()), cup_1.dimensions.x() - kTol);
               });
}

TEST(SnippetTest, CubeBelowAPointThenCubeRightAboveAndAheadOfIt) {
  ForEachScene(R"(from model import *
c1 = Cube below Vector3D(0.0, 0.0, 2.5), with width 0.3
c2 = Cube right of c1 by 0.2, above c1 by 0.2, ahead of c1 by 0.1
)",
               [](const Scene& scene) {
                 const SceneObject& c1 = Find(scene, "c1");
                 const SceneObject& c2 = Find(scene, "c2");
                 EXPECT_EQ(c1.dimensions.x(), 0.3);
                 ExpectBeyond(c1, Vector3d(0, 0, 2.5), -Vector3d::UnitZ());
                 ExpectBeyond(c2, c1.p_WO, Vector3d::UnitX(), 0.2);
                 ExpectBeyond(c2, c1.p_WO, Vector3d::UnitZ(), 0.2);
                 ExpectBeyond(c2, c1.p_WO, Vector3d::UnitY(), 0.1);
               });
}

TEST(SnippetTest, PlateOnAVectorBuiltFromTheBelt) {
  ForEachScene(R"(from model import *
belt = Belt on floor
plate = Plate on Vector3D(belt.x, belt.y - 0.75, belt.z + 0.081)
)",
               [](const Scene& scene) {
                 const SceneObject& belt = Find(scene, "belt");
                 const SceneObject& plate = Find(scene, "plate");
                 const Vector3d bottom = belt.p_WO + Vector3d(0, -0.75, 0.081);
                 EXPECT_TRUE(plate.p_WO.isApprox(
                     bottom + Vector3d(0, 0, plate.dimensions.z() / 2), 1e-12));
               });
}

TEST(SnippetTest, CubeStackedOnACube) {
  ForEachScene(R"(from model import *
table = Table on floor
cube_1 = Cube completely on table
cube_2 = Cube on cube_1
)",
               [](const Scene& scene) {
                 const SceneObject& cube_1 = Find(scene, "cube_1");
                 const SceneObject& cube_2 = Find(scene, "cube_2");
                 EXPECT_NEAR(cube_2.p_WO.z(), cube_1.p_WO.z() + 0.05, kTol);
                 // `on` keeps the centre over the lower cube's top face.
                 EXPECT_LE(std::abs(cube_2.p_WO.x() - cube_1.p_WO.x()), 0.025 + kTol);
                 EXPECT_LE(std::abs(cube_2.p_WO.y() - cube_1.p_WO.y()), 0.025 + kTol);
               });
}

TEST(SnippetTest, ChairFacingAVector) {
  ForEachScene(R"(from model import *
chair = Chair on floor, facing Vector3D(1, 0, 0)
)",
               [](const Scene& scene) {
                 const SceneObject& chair = Find(scene, "chair");
                 const Eigen::Matrix3d R = chair.R_WO.toRotationMatrix();
                 EXPECT_TRUE(R.col(1).isApprox(Vector3d::UnitX(), 1e-12));  // forward
                 EXPECT_TRUE(R.col(2).isApprox(Vector3d::UnitZ(), 1e-12));  // still upright
                 EXPECT_NEAR(chair.p_WO.z(), chair.dimensions.z() / 2, kTol);
               });
}

TEST(SnippetTest, RequireOnTheRightSideOfATray) {
  int far_left_trays = 0;
  ForEachScene(R"(from model import *
table = Table on floor
tr_1 = Tray completely on table
require (right tr_1).x + 0.2 < table.x
)",
               [&](const Scene& scene) {
                 const SceneObject& table = Find(scene, "table");
                 const SceneObject& tr_1 = Find(scene, "tr_1");
                 // `right tr_1` is the centre of its right face (the tray is unrotated).
                 EXPECT_LT(tr_1.p_WO.x() + tr_1.dimensions.x() / 2 + 0.2, table.p_WO.x());
                 far_left_trays += tr_1.p_WO.x() < table.p_WO.x() - 0.5;
               });
  EXPECT_GT(far_left_trays, 0);  // the requirement filters, it does not pin the tray
}

TEST(SnippetTest, BooleanBoundsOfDiscreteRangeCountAsZeroAndOne) {
  // Found by the fuzzer: a comparison as a bound used to abort (a bool read as a number).
  ForEachScene(
      "n = DiscreteRange(1.0 >= 5, 4)\nm = DiscreteRange(True, 1)\nrequire n >= 0 and n <= 4 and m == 1\n",
      [](const lang::Scene&) {}, 20);
}

}  // namespace
}  // namespace prs::sampling
