// End-to-end scenario tests: programs compile, sample, and every relation they state holds on
// the sampled values, checked here with plain arithmetic independent of the sampler's regions.
#include <gtest/gtest.h>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using Eigen::Vector3d;
using lang::Scene;
using lang::SceneObject;
using namespace testing_checks;

TEST(ScenarioTest, PaperFigureOneHoldsInEveryScene) {
  auto program = CompileOrDie(R"(from model import *

t = Table on V3D(0,0,0)
r1 = Robot on (top back t) - V3D(0.4, 0, 0)
r2 = Robot on (top back t) + V3D(0.4, 0, 0)

tr_1 = Tray completely on t, 
            ahead of r1,
            left of t
            
tr_2 = Tray completely on t,
            ahead of r2,
            right of t

Cube completely on tr_1

Camera at V3D((-0.1, 0.1),
              (-0.1, 0.1), 
              (1.9, 2.1)),
       facing V3D(0, 0, -1)
)");
  ASSERT_NE(program, nullptr);
  for (uint64_t i = 0; i < 200; ++i) {
    const Scene scene = SampleScene(*program, 1, i).scene;
    ASSERT_EQ(scene.objects.size(), 7u);
    const SceneObject& t = Find(scene, "t");
    const SceneObject& r1 = Find(scene, "r1");
    const SceneObject& tr_1 = Find(scene, "tr_1");
    const SceneObject& tr_2 = Find(scene, "tr_2");
    EXPECT_NEAR(t.p_WO.z(), t.dimensions.z() / 2, kTol);  // on V3D(0,0,0)
    EXPECT_NEAR(r1.p_WO.x(), -0.4, kTol);
    EXPECT_NEAR(r1.p_WO.y(), -t.dimensions.y() / 2, kTol);
    EXPECT_NEAR(r1.p_WO.z(), t.dimensions.z() + r1.dimensions.z() / 2, kTol);
    ExpectCompletelyOn(tr_1, t);
    ExpectCompletelyOn(tr_2, t);
    ExpectBeyond(tr_1, r1.p_WO, Vector3d::UnitY());   // ahead of r1
    ExpectBeyond(tr_1, t.p_WO, -Vector3d::UnitX());   // left of t
    ExpectBeyond(tr_2, t.p_WO, Vector3d::UnitX());    // right of t
    const SceneObject& cube = FindClass(scene, "Cube");
    EXPECT_FALSE(cube.name.has_value());
    ExpectCompletelyOn(cube, tr_1);
    const SceneObject& camera = FindClass(scene, "Camera");
    EXPECT_LE(std::abs(camera.p_WO.x()), 0.1 + kTol);
    EXPECT_LE(std::abs(camera.p_WO.y()), 0.1 + kTol);
    EXPECT_GE(camera.p_WO.z(), 1.9 - kTol);
    EXPECT_LE(camera.p_WO.z(), 2.1 + kTol);
    EXPECT_TRUE((camera.R_WO * Vector3d::UnitY()).isApprox(-Vector3d::UnitZ(), 1e-9));
    for (size_t a = 0; a < scene.objects.size(); ++a) {
      for (size_t b = a + 1; b < scene.objects.size(); ++b) {
        if (scene.objects[a].allow_collisions || scene.objects[b].allow_collisions) continue;
        EXPECT_FALSE(BoxesOverlapByPoints(scene.objects[a], scene.objects[b])) << a << " " << b;
      }
    }
  }
}

TEST(ScenarioTest, RotatedTrayCompletelyOnTableNeverOverhangs) {
  auto program = CompileOrDie(R"(from model import *
table = Table on floor
tray = Tray completely on table, facing V3D(1, 1, 0)
)");
  ASSERT_NE(program, nullptr);
  for (uint64_t i = 0; i < 1000; ++i) {
    const Scene scene = SampleScene(*program, 7, i).scene;
    const SceneObject& tray = Find(scene, "tray");
    const SceneObject& table = Find(scene, "table");
    EXPECT_TRUE((tray.R_WO * Vector3d::UnitY()).isApprox(Vector3d(1, 1, 0).normalized(), 1e-9));
    ExpectCompletelyOn(tray, table);
  }
}

TEST(ScenarioTest, SameSeedAndIndexGiveTheSameScene) {
  auto program = CompileOrDie("from model import *\n"
                              "t = Table on floor\nc = Cube completely on t\n"
                              "x = Normal(0, 1)\nparam p = x\n");
  ASSERT_NE(program, nullptr);
  const Scene a = SampleScene(*program, 5, 17).scene;
  const Scene b = SampleScene(*program, 5, 17).scene;
  const Scene c = SampleScene(*program, 5, 18).scene;
  EXPECT_EQ(Find(a, "c").p_WO, Find(b, "c").p_WO);
  EXPECT_NE(Find(a, "c").p_WO, Find(c, "c").p_WO);
  EXPECT_EQ(a.params[0].second.As<double>(), b.params[0].second.As<double>());
}

TEST(ScenarioTest, ParamOverrideForAnUndeclaredNameIsAnError) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.param_overrides = {{"clutter", "3"}, {"lable", "x"}};
  lang::CompileText(RepoPath("examples/test.prs"), "param clutter = 2, label = \"a\"\n", options,
                    diagnostics);
  ASSERT_EQ(diagnostics.diagnostics().size(), 1u);
  EXPECT_EQ(diagnostics.diagnostics()[0].id, "unknown-param");
  EXPECT_EQ(diagnostics.diagnostics()[0].message,
            "-p lable=x: the program declares no param 'lable'; did you mean 'label'?");
}

TEST(ScenarioTest, ConstructsExampleRuns) {
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileFile(RepoPath("examples/constructs.prs"), {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors()) << (diagnostics.diagnostics().empty()
                                       ? ""
                                       : diagnostics.diagnostics()[0].message);
  for (uint64_t i = 0; i < 50; ++i) {
    const Scene scene = SampleScene(*program, 3, i).scene;
    const SceneObject& cup_1 = Find(scene, "cup_1");
    const SceneObject& cup_2 = Find(scene, "cup_2");
    const SceneObject& table = Find(scene, "table");
    ExpectCompletelyOn(cup_1, table);
    EXPECT_NEAR(cup_1.p_WO.y(), cup_2.p_WO.y(), kTol);  // aligned with cup_1 by "y"
    ExpectBeyond(cup_1, table.p_WO, -Vector3d::UnitX(), 0.2);  // left of table by 0.2
    const SceneObject& c1 = Find(scene, "c1");
    const SceneObject& c2 = Find(scene, "c2");
    EXPECT_NEAR(c1.dimensions.x(), 0.3, 0);
    ExpectBeyond(c1, Vector3d(0, 0, 2.5), -Vector3d::UnitZ());  // below V
    ExpectBeyond(c2, c1.p_WO, Vector3d::UnitX(), 0.2);           // right of c1 by 0.2
    ExpectBeyond(c2, c1.p_WO, Vector3d::UnitZ(), 0.2);           // above c1 by 0.2
    ExpectBeyond(c2, c1.p_WO, Vector3d::UnitY(), 0.1);           // ahead of c1 by 0.1
    const SceneObject& cube_2 = Find(scene, "cube_2");
    EXPECT_NEAR(cube_2.p_WO.z(), c2.p_WO.z() + 0.05, kTol);      // a stack: cube_2 on c2
    const SceneObject& plate = Find(scene, "plate");
    EXPECT_NEAR(plate.p_WO.y(), table.p_WO.y() - 0.75, kTol);
    EXPECT_LT(cup_1.p_WO.x() + 0.04 + 0.01, cup_2.p_WO.x());    // the require holds
    const SceneObject& chair = Find(scene, "chair");
    EXPECT_TRUE((chair.R_WO * Vector3d::UnitY()).isApprox(Vector3d::UnitX(), 1e-9));
    int gears = 0;
    for (const SceneObject& o : scene.objects) gears += o.cls->name == "Gear";
    EXPECT_GE(gears, 1);
    EXPECT_LE(gears, 3);
  }
}

}  // namespace
}  // namespace prs::sampling
