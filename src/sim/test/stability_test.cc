// The physics check of --stable: an object drawn in the air falls and is named, an overhanging
// box tips off its support, objects resting on their supports stay put (a box, an upright
// cylinder, the Table-Cube cube), a scene without free bodies is not simulated, bad options are
// refused (a time too short to find rest among them), a body still moving at the end says how
// fast, a free body without contacts is a located error; and scenes it accepts stay put when
// their MJCF export is simulated for 2 s by MuJoCo directly, without this stage's code.
#include "sim/stability.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "sampling/sampler.h"
#include "sim/mujoco_model.h"
#include "sim/test/stays_put.h"
#include "sim/test/table_cube_scenes.h"

namespace prs::sim {
namespace {

// The program's text compiled beside examples/ (so `from model import *` works); kept alive.
const lang::CompiledProgram& Compile(const std::string& text) {
  static std::vector<std::unique_ptr<lang::CompiledProgram>> programs;
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  const std::string examples = std::string(dir ? dir : PRS_DEFAULT_SOURCE_DIR) + "/examples";
  options.search_path = {examples};
  programs.push_back(
      lang::CompileText(examples + "/stability_test.prs", text, options, diagnostics));
  EXPECT_FALSE(diagnostics.has_errors()) << text;
  return *programs.back();
}

lang::Scene Sample(const std::string& text, uint64_t index = 0) {
  return sampling::SampleScene(Compile(text), 1, index).scene;
}

constexpr char kTable[] = "from model import *\nt = Table on V3D(0, 0, 0)\n";

TEST(StabilityTest, AnObjectDrawnInTheAirFallsAndIsNamed) {
  const lang::Scene scene = Sample(std::string(kTable) + "c = Cube at V3D(0, 0, 1.5)\n");
  const std::optional<lang::Rejection> r = CheckStable(scene, {});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->kind, lang::RejectionKind::kUnstable);
  EXPECT_EQ(r->culprit, "c");
  EXPECT_NE(r->detail.find("c fell "), std::string::npos) << r->detail;
  // It stops once the cube is past the tolerance: about 45 ms of falling for 1 cm.
  const StabilityReport report = SimulateUnderGravity(exporting::MakeExportScene(scene, "t"), {});
  EXPECT_LT(report.simulated_s, 0.1);
  EXPECT_FALSE(report.at_rest);
  ASSERT_EQ(report.free_bodies.size(), 1u);
  EXPECT_LT(report.free_bodies[0].p_moved_W.z(), -0.01);
}

TEST(StabilityTest, ObjectsRestingOnTheirSupportsStayPut) {
  // A cube on the table, a cube on it, an upright cylinder (a cup) on the table.
  const lang::Scene scene = Sample(std::string(kTable) +
                                   "a = Cube on t\nb = Cube completely on a\n"
                                   "u = Cup on t, ahead of a by 0.2\n");
  const StabilityReport report = SimulateUnderGravity(exporting::MakeExportScene(scene, "t"), {});
  EXPECT_TRUE(report.at_rest);
  EXPECT_EQ(report.culprit, -1);
  ASSERT_EQ(report.free_bodies.size(), 3u);
  for (const BodyMotion& m : report.free_bodies) {
    EXPECT_LT(m.p_moved_W.norm(), 0.002) << scene.objects[m.object].DisplayName(m.object);
    EXPECT_LT(m.turned_rad, 0.5 * M_PI / 180) << scene.objects[m.object].DisplayName(m.object);
  }
  EXPECT_LT(report.simulated_s, 0.5);  // at rest early, not after the whole second
  EXPECT_FALSE(CheckStable(scene, {}).has_value());
}

TEST(StabilityTest, ABoxOverhangingItsSupportTipsOff) {
  // The table's right edge is at x = 0.9; the cube's centre 1 cm past it, on the top face.
  const lang::Scene scene = Sample(std::string(kTable) + "c = Cube at V3D(0.91, 0, 0.825)\n");
  const std::optional<lang::Rejection> r = CheckStable(scene, {});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->culprit, "c");
  // Its centre 1.5 cm inside the edge, it stays.
  EXPECT_FALSE(CheckStable(Sample(std::string(kTable) + "c = Cube at V3D(0.885, 0, 0.825)\n"), {}));
}

TEST(StabilityTest, ScenesWithoutFreeBodiesAreNotSimulated) {
  const lang::Scene scene = Sample(std::string(kTable) + "g = Chair at V3D(0, 1, 1.2)\n");
  const StabilityReport report = SimulateUnderGravity(exporting::MakeExportScene(scene, "t"), {});
  EXPECT_TRUE(report.at_rest);
  EXPECT_TRUE(report.free_bodies.empty());
  EXPECT_EQ(report.simulated_s, 0);
}

TEST(StabilityTest, TolerancesDecide) {
  // A cube 2 mm above the table drops 2 mm: unstable at a 1 mm tolerance, stable at 1 cm.
  const lang::Scene scene = Sample(std::string(kTable) + "c = Cube at V3D(0, 0, 0.827)\n");
  StabilityOptions tight;
  tight.max_move_m = 0.001;
  EXPECT_TRUE(CheckStable(scene, tight).has_value());
  EXPECT_FALSE(CheckStable(scene, {}).has_value());
}

TEST(StabilityTest, BadOptionsAreRefused) {
  for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    StabilityOptions options;
    options.duration_s = bad;
    EXPECT_THROW(CheckStabilityOptions(options), std::invalid_argument);
    options = {};
    options.max_move_m = bad;
    EXPECT_THROW(MakeStabilityTest(options), std::invalid_argument);
    options = {};
    options.max_turn_rad = bad;
    EXPECT_THROW(CheckStabilityOptions(options), std::invalid_argument);
  }
  for (const double too_short : {0.1, 0.199}) {
    EXPECT_THROW(MakeStabilityTest({too_short}), std::invalid_argument) << too_short;
  }
}

// Below kMinStableDuration_s a body cannot have been still for 0.1 s from 0.1 s on, so every
// scene would be "still moving at 0.000 m/s": such times are refused, naming the least.
TEST(StabilityTest, RestIsDecidedWithinTheLeastTime) {
  StabilityOptions options;
  options.duration_s = 0.1;
  try {
    CheckStabilityOptions(options);
    ADD_FAILURE() << "0.1 s accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("at least 0.2 s, not 0.1"), std::string::npos)
        << error.what();
  }
  // A cube at rest on the table is found at rest within the least time (rounded up to whole
  // steps), at MuJoCo's 2 ms steps and at steps that do not divide it.
  const lang::Scene scene = Sample(std::string(kTable) + "c = Cube completely on t\n");
  for (const double step_s : {0.002, 0.004, 0.003}) {
    options.duration_s = kMinStableDuration_s;
    options.timestep_s = step_s;
    const StabilityReport report =
        SimulateUnderGravity(exporting::MakeExportScene(scene, "t"), options);
    EXPECT_TRUE(report.at_rest) << step_s;
    EXPECT_LT(report.simulated_s, kMinStableDuration_s + step_s) << step_s;
  }
  options = {};
  options.duration_s = kMinStableDuration_s;
  EXPECT_FALSE(CheckStable(scene, options).has_value());
}

// When the time runs out with a body within the tolerances, the detail says how it was moving:
// a speed above the rest speed, never "moving at 0.000 m/s".
TEST(StabilityTest, ABodyStillMovingWhenTimeRunsOutSaysHowFast) {
  const lang::Scene scene = Sample(std::string(kTable) + "c = Cube at V3D(0, 0, 2.5)\n");
  StabilityOptions options;
  options.duration_s = 0.2;
  options.max_move_m = 10;  // falling 20 cm is within it
  const std::optional<lang::Rejection> r = CheckStable(scene, options);
  ASSERT_TRUE(r.has_value());
  EXPECT_NE(r->detail.find("c was still moving at 1.96"), std::string::npos) << r->detail;
  EXPECT_NE(r->detail.find("after 0.20 s"), std::string::npos) << r->detail;
}

// An object with a mass and allowCollisions: True has no contacts in the physics model and
// falls through the table: a located error, not a rejection that says only "fell 1.1 cm".
TEST(StabilityTest, AFreeBodyWithoutContactsIsALocatedError) {
  const lang::Scene scene =
      Sample(std::string(kTable) + "c = Cube completely on t, with allowCollisions True\n");
  try {
    CheckStable(scene, {});
    ADD_FAILURE() << "no error";
  } catch (const lang::ScenarioError& error) {
    EXPECT_EQ(error.diagnostic().id, "physics-without-contacts");
    EXPECT_TRUE(lang::IsKnownDiagnosticId(error.diagnostic().id));
    EXPECT_EQ(error.diagnostic().span.begin, scene.objects[1].span.begin);
    EXPECT_NE(error.diagnostic().message.find("c has a mass and allowCollisions: True"),
              std::string::npos)
        << error.diagnostic().message;
    EXPECT_NE(error.diagnostic().message.find("--stable"), std::string::npos);
  }
  // Without a mass it is static: nothing to simulate, no error.
  EXPECT_FALSE(CheckStable(Sample(std::string(kTable) +
                                  "c = Cube completely on t, with allowCollisions True, "
                                  "with mass 0\n"),
                           {})
                   .has_value());
}

// Independently of SimulateUnderGravity: each scene the check accepts is exported to MJCF,
// loaded and stepped for 2 s by MuJoCo here, and no free body moves past the tolerance.
TEST(StabilityTest, AcceptedScenesStayPutInMujocoForTwoSeconds) {
  const char* const examples[] = {"table_cube.prs", "pantry_shapes.prs", "kitchen_meshes.prs"};
  int accepted = 0;
  for (const char* name : examples) {
    const std::unique_ptr<const lang::CompiledProgram> program(
        testing_scenes::CompileExample(name));
    sampling::SampleOptions options;
    options.accept = MakeStabilityTest({});
    for (uint64_t index = 0; index < 4; ++index) {
      const lang::Scene scene = sampling::SampleScene(*program, 7, index, options).scene;
      testing_scenes::ExpectExportStaysPut(exporting::MakeExportScene(scene, "t"), 2.0, 0.01,
                                           std::string(name) + " scene " + std::to_string(index));
      ++accepted;
    }
  }
  EXPECT_EQ(accepted, 12);
}

}  // namespace
}  // namespace prs::sim
