// --settle: an object drawn in the air lands on its support and the scene says how long that
// took; what must hold at rest (`require settled`, the workspace) rejects the scenes that
// break it, naming the object; the settled scene, exported to MJCF and simulated by MuJoCo
// directly for 1 s, stays put; settling is deterministic; a time too short to find rest is
// refused, and a free body without contacts is a located error.
#include "sim/settle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "geometry/rotation.h"
#include "sampling/sampler.h"
#include "sim/mujoco_model.h"
#include "sim/test/stays_put.h"

namespace prs::sim {
namespace {

std::unique_ptr<lang::CompiledProgram> Compile(const std::string& text) {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  const std::string examples = std::string(dir ? dir : PRS_DEFAULT_SOURCE_DIR) + "/examples";
  options.search_path = {examples};
  auto program = lang::CompileText(examples + "/settle_test.prs", text, options, diagnostics);
  EXPECT_FALSE(diagnostics.has_errors()) << text;
  return program;
}

constexpr char kTable[] = "from model import *\nt = Table on V3D(0, 0, 0)\n";
constexpr double kTableTop_m = 0.8;  // the model's Table is 0.8 m tall

TEST(SettleTest, AnObjectDrawnInTheAirLandsOnItsSupport) {
  const auto program = Compile(std::string(kTable) + "c = Cube at V3D(0.1, 0.2, 1.5)\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  EXPECT_FALSE(scene.settled_s.has_value());
  const StabilityReport report = SettleScene(scene, {});
  EXPECT_TRUE(report.at_rest);
  ASSERT_TRUE(scene.settled_s.has_value());
  EXPECT_GT(*scene.settled_s, 0.3);  // a 0.7 m fall alone takes 0.38 s
  const lang::SceneObject& c = scene.objects[1];
  EXPECT_NEAR(c.p_WO.z(), kTableTop_m + c.dimensions.z() / 2, 0.004);
  EXPECT_NEAR(c.p_WO.x(), 0.1, 0.01);
  EXPECT_NEAR(c.p_WO.y(), 0.2, 0.01);
  // Its properties moved with it, and it no longer claims to be the same in every scene.
  const lang::Value* position = c.FindProperty("position");
  ASSERT_NE(position, nullptr);
  EXPECT_EQ(position->As<Eigen::Vector3d>(), c.p_WO);
  EXPECT_EQ(c.fixed_id, 0u);
  EXPECT_FALSE(c.fixed);
  // The static table did not move.
  EXPECT_EQ(scene.objects[0].p_WO, Eigen::Vector3d(0, 0, 0.4));
}

TEST(SettleTest, ATurnedObjectKeepsYawPitchRollConsistentWithItsOrientation) {
  // A cube drawn turned 34° about its x axis lands on an edge and tips over onto a face.
  const auto program =
      Compile(std::string(kTable) + "c = Cube at V3D(0, 0, 0.9), with yaw 0.3, with pitch 0.6\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  SettleScene(scene, {});
  const lang::SceneObject& c = scene.objects[1];
  const auto number = [&](const char* name) { return c.FindProperty(name)->As<double>(); };
  const Eigen::Matrix3d R = geometry::CalcRotationFromYawPitchRoll(
      number("yaw"), number("pitch"), number("roll"));
  EXPECT_LT((R - c.R_WO.toRotationMatrix()).norm(), 1e-9);
  // On a face: its local z axis is vertical, or horizontal.
  const double up = std::abs((c.R_WO * Eigen::Vector3d::UnitZ()).z());
  EXPECT_TRUE(up > 0.99 || up < 0.01) << up;
}

TEST(SettleTest, RequirementsOnTheSettledSceneRejectAndNameTheObject) {
  // The cube falls from above the table's edge region: off the table (to the floor) or on it.
  const auto program = Compile(std::string(kTable) +
                               "c = Cube at V3D(Range(0.85, 0.95), 0, 1.2)\n"
                               "require settled c.z > 0.5\n");
  int on_table = 0, rejected = 0;
  for (uint64_t index = 0; index < 12; ++index) {
    lang::Scene scene = sampling::SampleScene(*program, 3, index).scene;
    const std::optional<lang::Rejection> r = SettleAndCheck(scene, {});
    if (!r) {
      EXPECT_GT(scene.objects[1].p_WO.z(), 0.5);
      ++on_table;
      continue;
    }
    ++rejected;
    EXPECT_EQ(r->kind, lang::RejectionKind::kUnsettled);
    EXPECT_NE(r->culprit.find("require settled at "), std::string::npos) << r->culprit;
    EXPECT_NE(r->detail.find("after settling c rests at ("), std::string::npos) << r->detail;
    EXPECT_LT(scene.objects[1].p_WO.z(), 0.5);
  }
  EXPECT_GT(on_table, 0);
  EXPECT_GT(rejected, 0);
  // Without --settle the requirement is not checked: the drawn cube is at 1.2 m anyway, and
  // the sampler keeps every scene.
  EXPECT_NO_THROW(sampling::SampleScene(*program, 3, 0));
}

TEST(SettleTest, TheSamplerConditionsOnTheSettledChecks) {
  const auto program = Compile(std::string(kTable) +
                               "c = Cube at V3D(Range(0.85, 0.95), 0, 1.2)\n"
                               "require settled c.z > 0.5\n");
  sampling::SampleOptions options;
  options.accept = MakeSettleTest({});
  for (uint64_t index = 0; index < 6; ++index) {
    const sampling::SampledScene s = sampling::SampleScene(*program, 3, index, options);
    ASSERT_TRUE(s.scene.settled_s.has_value());
    EXPECT_GT(s.scene.objects[1].p_WO.z(), 0.5);
  }
}

TEST(SettleTest, AnObjectThatLeavesTheWorkspaceIsUnsettled) {
  // A workspace around the cube's drop only (0.5 to 1.5 m up): the floor it lands on is outside.
  const auto program = Compile(
      "from model import *\n"
      "workspace = Cuboid(V3D(0, 0, 1), V3D(0, 0, 0), 1, 1, 1)\n"
      "c = Cube at V3D(0, 0, 1.2)\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  const std::optional<lang::Rejection> r = SettleAndCheck(scene, {});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->kind, lang::RejectionKind::kUnsettled);
  EXPECT_EQ(r->culprit, "c outside the workspace");
  EXPECT_NE(r->detail.find("c came to rest at ("), std::string::npos) << r->detail;
}

TEST(SettleTest, ASceneNotAtRestInTimeIsUnsettled) {
  const auto program = Compile(std::string(kTable) + "c = Cube at V3D(0, 0, 2.5)\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  SettleOptions short_time;
  short_time.duration_s = kMinSettleDuration_s;  // still falling: 1.2 m in the last 0.5 s
  const std::optional<lang::Rejection> r = SettleAndCheck(scene, short_time);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->culprit, "c not at rest");
  EXPECT_NE(r->detail.find("c was still moving after 0.50 s: it moved 1.2"), std::string::npos)
      << r->detail;
  EXPECT_NE(r->detail.find(" m and turned 0.0° in the last 0.5 s (at rest: under 1.0 cm and 5.7°)"),
            std::string::npos)
      << r->detail;
  for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL, 0.4}) {
    EXPECT_THROW(MakeSettleTest({bad}), std::invalid_argument);
  }
}

// Settling judges rest by where the bodies were 0.5 s before, so nothing is at rest sooner: a
// time below that is refused, naming the least; a cube already at rest is found so within it,
// and settled after the confirmation's second.
TEST(SettleTest, RestIsDecidedWithinTheLeastTime) {
  try {
    CheckSettleOptions({0.4});
    ADD_FAILURE() << "0.4 s accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("at least 0.5 s, not 0.4"), std::string::npos)
        << error.what();
  }
  const auto program = Compile(std::string(kTable) + "c = Cube completely on t\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  EXPECT_FALSE(SettleAndCheck(scene, {kMinSettleDuration_s}).has_value());
  ASSERT_TRUE(scene.settled_s.has_value());
  EXPECT_NEAR(*scene.settled_s, kMinSettleDuration_s + kSettleConfirm_s, 1e-9);
}

// An object with a mass and allowCollisions: True would fall through the table and never come
// to rest ("still moving at 29.43 m/s"): a located error instead.
TEST(SettleTest, AFreeBodyWithoutContactsIsALocatedError) {
  const auto program =
      Compile(std::string(kTable) + "c = Cube completely on t, with allowCollisions True\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  try {
    SettleAndCheck(scene, {});
    ADD_FAILURE() << "no error";
  } catch (const lang::ScenarioError& error) {
    EXPECT_EQ(error.diagnostic().id, "physics-without-contacts");
    EXPECT_EQ(error.diagnostic().span.begin, scene.objects[1].span.begin);
    EXPECT_NE(error.diagnostic().message.find("--settle"), std::string::npos);
  }
}

TEST(SettleTest, ARequirementThatDrawsIsAnError) {
  const auto program =
      Compile(std::string(kTable) + "c = Cube on t\nrequire settled c.z > Range(0, 1)\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  EXPECT_THROW(SettleAndCheck(scene, {}), lang::ScenarioError);
}

// Independently of the stage: the settled scene exported to MJCF and stepped for 1 s by
// MuJoCo here; nothing moves more than 5 mm, and settling twice gives the same poses.
TEST(SettleTest, SettledScenesStayPutAndAreTheSameEveryTime) {
  const auto program = Compile(std::string(kTable) +
                               "for i in range(4):\n"
                               "    Cube at V3D(Range(-0.3, 0.3), Range(-0.3, 0.3), 1.2)\n");
  sampling::SampleOptions options;
  options.accept = MakeSettleTest({});
  const sampling::SampledScene a = sampling::SampleScene(*program, 5, 0, options);
  const sampling::SampledScene b = sampling::SampleScene(*program, 5, 0, options);
  for (size_t i = 0; i < a.scene.objects.size(); ++i) {
    EXPECT_EQ(a.scene.objects[i].p_WO, b.scene.objects[i].p_WO);
    EXPECT_EQ(a.scene.objects[i].R_WO.coeffs(), b.scene.objects[i].R_WO.coeffs());
  }
  testing_scenes::ExpectExportStaysPut(exporting::MakeExportScene(a.scene, "t"), 1.0, 0.005,
                                       "four cubes");
}

// Three cans on their sides stacked like pipes (two on the table touching, one in the groove
// on top) are at rest at once in the real world. MuJoCo 2.2 touches a cylinder at one point and
// nothing resists rolling, so without the export's capsule along each free can's side (and its
// rolling friction) these cans jitter and roll in place and were never at rest in 3 s.
TEST(SettleTest, CansOnTheirSidesComeToRest) {
  const auto program = Compile(std::string(kTable) +
                               "import math\n"
                               "class Can:\n"
                               "    shape: Cylinder()\n"
                               "    width: 0.066\n"
                               "    length: 0.066\n"
                               "    height: 0.12\n"
                               "    mass: 0.3\n"
                               "Can at V3D(0, -0.034, 0.834), with roll math.pi / 2\n"
                               "Can at V3D(0, 0.034, 0.834), with roll math.pi / 2\n"
                               "Can at V3D(0, 0, 0.894), with roll math.pi / 2\n");
  lang::Scene scene = sampling::SampleScene(*program, 1, 0).scene;
  const std::vector<lang::SceneObject> drawn = scene.objects;
  const StabilityReport report = SettleScene(scene, {});
  EXPECT_TRUE(report.at_rest);
  ASSERT_TRUE(scene.settled_s.has_value());
  EXPECT_LE(*scene.settled_s, 1.0 + kSettleConfirm_s);
  for (size_t i = 1; i < scene.objects.size(); ++i) {
    EXPECT_LT((scene.objects[i].p_WO - drawn[i].p_WO).norm(), 0.01) << i;
  }
  EXPECT_GT(scene.objects[3].p_WO.z(), 0.88);  // still on top of the other two
  testing_scenes::ExpectExportStaysPut(exporting::MakeExportScene(scene, "cans"), 1.0, 0.005,
                                       "three cans");
}

// examples/bin_pile.prs settled: 25 objects drawn in the air above a bin end inside it (their
// centres inside the walls, on or above the floor), no two interpenetrating by more than the
// give of soft contacts (8 mm: a can pressed into the mug's convex pieces sinks 5.7 mm, a can
// into the bin's floor 3.6 mm), and at rest: the settled scene exported and stepped 1 s by
// MuJoCo directly moves nothing by more than 1 cm. Scenes 0 to 3 of seed 1: before settling
// confirmed rest from standstill (kSettleConfirm_s), scene 2's pile had a body that moved
// 66 mm in that second (bench/settle_profile --check makes these checks on 100 piles).
TEST(SettleTest, TheBinPileEndsInsideTheBinAtRest) {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  lang::DiagnosticEngine diagnostics;
  const auto program = lang::CompileFile(
      std::string(dir ? dir : PRS_DEFAULT_SOURCE_DIR) + "/examples/bin_pile.prs", {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  sampling::SampleOptions options;
  options.accept = MakeSettleTest({});
  for (uint64_t index = 0; index < 4; ++index) {
    const std::string pile = "scene " + std::to_string(index);
    const lang::Scene scene = sampling::SampleScene(*program, 1, index, options).scene;
    int piled = 0;
    for (const lang::SceneObject& o : scene.objects) {
      const lang::Value* mass = o.FindProperty("mass");
      if (!mass || !mass->Is<double>() || mass->As<double>() <= 0) continue;
      ++piled;
      EXPECT_LT(std::abs(o.p_WO.x()), 0.25) << pile << ": " << o.p_WO.transpose();
      EXPECT_LT(std::abs(o.p_WO.y()), 0.2) << pile << ": " << o.p_WO.transpose();
      EXPECT_GT(o.p_WO.z(), 0.82) << pile << ": " << o.p_WO.transpose();  // the bin's floor
      EXPECT_LT(o.p_WO.z(), 1.02) << pile << ": " << o.p_WO.transpose();
    }
    EXPECT_EQ(piled, 25) << pile;
    const exporting::ExportScene exported = exporting::MakeExportScene(scene, "pile");
    EXPECT_TRUE(exported.settled);
    const ModelPtr model =
        LoadModelFromXml(exporting::WriteScene(exported, exporting::Format::kMjcf));
    const DataPtr data = MakeData(*model);
    mj_forward(model.get(), data.get());
    EXPECT_GT(data->ncon, 25) << pile;  // a pile: the bodies touch
    for (int c = 0; c < data->ncon; ++c) {
      const mjContact& contact = data->contact[c];
      EXPECT_GT(contact.dist, -0.008)
          << pile << ": " << mj_id2name(model.get(), mjOBJ_GEOM, contact.geom1) << " and "
          << mj_id2name(model.get(), mjOBJ_GEOM, contact.geom2);
    }
    testing_scenes::ExpectExportStaysPut(exported, 1.0, 0.01, "the pile of " + pile);
  }
}

// A pile that moves when started again from standstill is described as such when time runs out.
TEST(SettleTest, AFailedConfirmationSaysSo) {
  BodyMotion m;
  m.recent_move_m = 0.019;
  m.recent_turn_rad = 23.3 * M_PI / 180;
  m.recent_from_standstill = true;
  EXPECT_EQ(DescribeUnsettledMotion(m),
            "moved 1.9 cm and turned 23.3° in 1 s when started again from standstill (at rest: "
            "under 1.0 cm and 5.7°)");
  m.recent_from_standstill = false;
  EXPECT_EQ(DescribeUnsettledMotion(m),
            "moved 1.9 cm and turned 23.3° in the last 0.5 s (at rest: under 1.0 cm and 5.7°)");
}

}  // namespace
}  // namespace prs::sim

namespace prs::sim {
namespace {

// Simulations first try little room for contacts (StabilityOptions::first_contacts_per_free_body)
// and run again with the scene's own room when a step ran out of it: a heap of 14 cubes dropped
// on each other (dozens of contacts) simulated with a first room of 1 contact a body (which it
// runs out of) ends bit for bit where it ends with the export's room from the start, and the
// first try's MuJoCo warnings are not printed.
TEST(SettleTest, TooLittleRoomForContactsIsTriedAgainWithTheScenesOwn) {
  const auto program = Compile(std::string(kTable) +
                               "for i in range(14):\n"
                               "    Cube at V3D(Range(-0.06, 0.06), Range(-0.06, 0.06), "
                               "Range(0.9, 1.4))\n");
  const lang::Scene scene = sampling::SampleScene(*program, 3, 0).scene;
  const exporting::ExportScene model = exporting::MakeExportScene(scene, "heap");
  StabilityOptions options;
  options.duration_s = 1.0;
  options.timestep_s = kSettleTimestep_s;
  options.first_contacts_per_free_body = 1;
  testing::internal::CaptureStderr();
  const StabilityReport retried = SimulateUnderGravity(model, options, false);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  options.first_contacts_per_free_body = 0;  // the export's 20 from the start
  const StabilityReport roomy = SimulateUnderGravity(model, options, false);
  // 14 free bodies at 1 contact each leave room for 14; the heap has more.
  exporting::ExportScene tight = model;
  tight.contacts_per_free_body = 1;
  const ModelPtr m = LoadModelFromXml(exporting::WriteScene(tight, exporting::Format::kMjcf));
  EXPECT_EQ(m->nconmax, 14);
  const ModelPtr wide = LoadModelFromXml(exporting::WriteScene(model, exporting::Format::kMjcf));
  const DataPtr d = MakeData(*wide);
  while (d->time < retried.simulated_s / 2) mj_step(wide.get(), d.get());
  EXPECT_GT(d->ncon, 14);
  ASSERT_EQ(retried.free_bodies.size(), 14u);
  EXPECT_EQ(retried.simulated_s, roomy.simulated_s);
  for (size_t k = 0; k < retried.free_bodies.size(); ++k) {
    EXPECT_EQ(retried.free_bodies[k].p_end_WO, roomy.free_bodies[k].p_end_WO) << k;
    EXPECT_EQ(retried.free_bodies[k].R_end_WO.coeffs(), roomy.free_bodies[k].R_end_WO.coeffs());
  }
}

}  // namespace
}  // namespace prs::sim
