// The Table-Cube controller in simulation: the camera image shows the cube where the scene
// says, perception back-projects it within 1 cm where it is visible and reports a fault where it
// is not, an easy scene succeeds end to end (with short and with 1.026 m tall robot boxes), and
// episodes are deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <thread>

#include "render/model_renderer.h"
#include "sim/perception.h"
#include "sim/table_cube_controller.h"
#include "sim/test/table_cube_scenes.h"
#include "sim/world.h"

namespace prs::sim {
namespace {

class ControllerTest : public ::testing::Test {
 protected:
  static lang::Scene Scene(uint64_t index) { return testing_scenes::SampleTableCube(index); }
};

// Scene 0 of seed 1 has the cube well inside the camera's view; scene 3 has it beyond the left
// edge of the view (x = -0.68 m with a 45° vertical field of view from 2 m up).
constexpr uint64_t kVisibleScene = 0, kOutOfViewScene = 3;

struct Sighting {
  std::optional<ColorBlob> blob;
  PinholeCamera camera;
  render::DepthImage depth;
  Eigen::Vector3d p_cube_W;
};

Sighting LookAtCube(const lang::Scene& scene) {
  World world = BuildWorld(exporting::MakeExportScene(scene, "test"));
  render::ModelRenderer renderer(*world.model, 640, 480);
  Sighting s;
  const render::Image image = renderer.Render(*world.data, 0, &s.depth);
  s.camera = GetMujocoCamera(*world.model, *world.data, 0, 640, 480);
  s.blob = FindLargestBlob(image, IsBluePixel);
  s.p_cube_W = world.FindFirst("Cube")->p_WO;
  if (s.blob) {
    // The image shows the cube where the scene says: its projection lands inside the blob.
    const Eigen::Vector3d p = Project(s.camera, s.p_cube_W + Eigen::Vector3d(0, 0, 0.025));
    const int pixel = int(p.y()) * 640 + int(p.x());
    EXPECT_NE(std::find(s.blob->pixels.begin(), s.blob->pixels.end(), pixel), s.blob->pixels.end());
  }
  return s;
}

TEST_F(ControllerTest, PerceptionFindsAVisibleCubeWithinOneCentimetre) {
  const Sighting s = LookAtCube(Scene(kVisibleScene));
  ASSERT_TRUE(s.blob.has_value());
  EXPECT_FALSE(s.blob->touches_border);
  const Eigen::Vector3d p_top = BackProject(s.camera, s.blob->centroid_px, MedianDepth(s.depth, *s.blob));
  EXPECT_LT((p_top - Eigen::Vector3d(0, 0, 0.025) - s.p_cube_W).norm(), 0.01);
}

TEST_F(ControllerTest, PerceptionSeesNoCubeOutOfView) {
  const Sighting s = LookAtCube(Scene(kOutOfViewScene));
  EXPECT_FALSE(s.blob.has_value());
  const TaskOutcome o = TableCubeController().Run(Scene(kOutOfViewScene));
  EXPECT_EQ(o.outcome, "perception-fault") << o.detail;
}

TEST_F(ControllerTest, AnEasySceneSucceedsEndToEnd) {
  const TaskOutcome o = TableCubeController().Run(Scene(kVisibleScene));
  EXPECT_EQ(o.outcome, "success") << o.detail;
}

// The same scene with robot boxes of the Panda's real height (the original tool's object
// model): the arms stand on the table inside them, not a metre above it.
TEST_F(ControllerTest, AnEasySceneWithTallRobotBoxesSucceedsEndToEnd) {
  const lang::Scene tall = testing_scenes::WithRobotBoxes(Scene(kVisibleScene), 1.026, 0);
  const TaskOutcome o = TableCubeController().Run(tall);
  EXPECT_EQ(o.outcome, "success") << o.detail;
}

// examples/table_cube_paper_model.prs (the original tool's object model: a massless 4 cm cube,
// 1.026 m robot boxes), scenes 0-5 of seed 1: 4 of them succeed with the realistic controller.
// Before the arms stood at the robot boxes' bottoms, none did; before a massless cube was made
// free, none did either.
TEST_F(ControllerTest, ThePaperModelScenarioSucceedsInMostOfAFewScenes) {
  TableCubeController controller;
  int successes = 0;
  std::string outcomes;
  for (uint64_t index = 0; index < 6; ++index) {
    const TaskOutcome o = controller.Run(testing_scenes::SamplePaperModel(index));
    successes += o.outcome == "success";
    outcomes += std::to_string(index) + ": " + o.outcome + " (" + o.detail + ")\n";
  }
  EXPECT_GE(successes, 3) << outcomes;
}

double Metric(const TaskOutcome& o, const std::string& name) {
  for (const auto& [key, value] : o.metrics) {
    if (key == name) return value;
  }
  ADD_FAILURE() << "no metric " << name;
  return std::nan("");
}

std::optional<bool> Flag(const TaskOutcome& o, const std::string& name) {
  for (const auto& [key, value] : o.flags) {
    if (key == name) return value;
  }
  return std::nullopt;
}

// The original's Cube class has no mass, which the export rules make static: the controllers
// make it a free 64 g body (4 cm at 1000 kg/m^3), say so, and carry it to the right tray. It
// was a 100 % poor grip ("lifted it only 0.0 cm") when the cube stayed welded to the world.
TEST_F(ControllerTest, TheOriginalModelsMasslessCubeIsLiftedAndCarried) {
  const lang::Scene scene = testing_scenes::SamplePaperModel(1);
  for (const TableCubeOptions& options : {TableCubeOptions{}, MakePaperTableCubeOptions()}) {
    const TaskOutcome o = TableCubeController(options).Run(scene);
    EXPECT_EQ(o.outcome, "success") << o.detail;
    EXPECT_NEAR(Metric(o, "cube_mass_kg"), 0.064, 1e-12);
    EXPECT_EQ(Flag(o, "cube_mass_assumed"), true);
    ASSERT_EQ(o.warnings.size(), 1u);
    EXPECT_NE(o.warnings[0].find("Cube_5 (a Cube) has no mass"), std::string::npos)
        << o.warnings[0];
    EXPECT_NE(o.warnings[0].find("`mass: 0.1`"), std::string::npos) << o.warnings[0];
    EXPECT_GT(Metric(o, "cube_final_x_m"), 0) << "the cube should end in the right tray";
  }
  // A cube with a mass keeps it and no warning is given.
  const TaskOutcome o = TableCubeController().Run(Scene(kVisibleScene));
  EXPECT_NEAR(Metric(o, "cube_mass_kg"), 0.1, 1e-12);
  EXPECT_TRUE(o.warnings.empty());
  EXPECT_FALSE(Flag(o, "cube_mass_assumed").has_value());
}

// The paper's success is the cube within 0.453 m of the second tray in x and y; the record
// says whether it also rests in the tray.
TEST_F(ControllerTest, ThePaperControllerReportsBothCriteria) {
  const TaskOutcome o =
      TableCubeController(MakePaperTableCubeOptions()).Run(testing_scenes::SamplePaperModel(0));
  EXPECT_EQ(o.outcome, "success") << o.detail;
  EXPECT_EQ(Flag(o, "in_tray"), true);
  EXPECT_LT(Metric(o, "sighting_error_start_m"), 0.015);
  EXPECT_LT(Metric(o, "sighting_error_handover_m"), 0.015);
}

// The original's robot box is the whole Panda, 1.025562 m; a base's box is 0.1 m. Object models
// that differ in that height alone give the same table: the arm stands on the box's bottom.
TEST_F(ControllerTest, RobotBoxHeightsGiveComparableTables) {
  constexpr int kScenes = 6;
  std::map<std::string, int> tables[3];
  const double heights[3] = {0.1, 0.5, 1.025562};
  for (int h = 0; h < 3; ++h) {
    const auto program = testing_scenes::CompilePaperModelWithRobotHeight(heights[h]);
    TableCubeController controller(MakePaperTableCubeOptions());
    for (uint64_t index = 0; index < kScenes; ++index) {
      const lang::Scene scene = sampling::SampleScene(*program, 1, index).scene;
      for (const lang::SceneObject& o : scene.objects) {
        if (o.cls && o.cls->name == "Robot") {
          ASSERT_EQ(o.dimensions.z(), heights[h]);
        }
      }
      ++tables[h][controller.Run(scene).outcome];
    }
  }
  EXPECT_GE(tables[2]["success"], kScenes / 2);
  for (int h = 0; h < 2; ++h) {
    for (const auto& [outcome, count] : tables[2]) {
      EXPECT_NEAR(tables[h][outcome], count, 1)
          << outcome << " with boxes " << heights[h] << " m tall";
    }
  }
}

TEST_F(ControllerTest, EpisodesAreDeterministic) {
  TableCubeController controller;
  const TaskOutcome a = controller.Run(Scene(kVisibleScene));
  const TaskOutcome b = controller.Run(Scene(kVisibleScene));
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.metrics, b.metrics);
}

// prs test keeps controllers in a pool, so one controller (and its OpenGL context) runs
// episodes on one worker thread after another.
TEST_F(ControllerTest, AControllerRunsOnAnotherThreadAfterThisOne) {
  TableCubeController controller;
  const TaskOutcome here = controller.Run(Scene(kVisibleScene));
  TaskOutcome there;
  std::string error;
  std::thread([&] {
    try {
      there = controller.Run(Scene(kVisibleScene));
    } catch (const std::exception& e) {
      error = e.what();
    }
  }).join();
  EXPECT_EQ(error, "");
  EXPECT_EQ(there.outcome, here.outcome);
  EXPECT_EQ(there.metrics, here.metrics);
}

}  // namespace
}  // namespace prs::sim
