// The paper's case-study controller for Table-Cube scenes, honestly limited as the paper's was:
// it finds the cube as a blue blob in the ceiling camera's RGB-D image, back-projects it into
// the world, and with inverse kinematics the arm nearest the cube picks it, puts it down
// between the arms, and the other arm picks it again (from a new image) and drops it into the
// tray in front of it. The controller never reads the cube's true pose; only the outcome
// classification afterwards compares with it.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lang/scene.h"

namespace prs::render {
class ModelRenderer;
}

namespace prs::sim {

struct TableCubeOptions {
  int image_width = 640;
  int image_height = 480;
  double cube_size_m = 0.05;           // the task's nominal cube, known to the controller
  double perception_tolerance_m = 0.015;  // a sighting further off than this is a fault
  /// The fix documented in docs/case_study.md: turn both arms away (joint 1 to the back)
  /// before each picture, so that no arm hides the cube from the ceiling camera.
  bool clear_view_before_sighting = false;
};

/// What happened in one episode. `outcome` is one of "success", "perception-fault",
/// "no-path", "poor-grip", "missed-tray", "no-camera", "no-cube", "world-error".
struct TaskOutcome {
  std::string outcome;
  std::string detail;  // one sentence: what went wrong, with numbers
  std::vector<std::pair<std::string, double>> metrics;  // e.g. perception error, final position
};

class TableCubeController {
 public:
  explicit TableCubeController(TableCubeOptions options = {});
  ~TableCubeController();
  TableCubeController(const TableCubeController&) = delete;
  TableCubeController& operator=(const TableCubeController&) = delete;

  /// Runs one episode on a sampled scene. Never throws for a scene: a world MuJoCo rejects is
  /// reported as "world-error". Throws std::runtime_error when no rendering context can be made.
  TaskOutcome Run(const lang::Scene& scene);

 private:
  struct Episode;
  TableCubeOptions options_;
  // Made on the first episode and kept: the OpenGL context outlives each episode's world.
  std::unique_ptr<render::ModelRenderer> renderer_;
};

}  // namespace prs::sim
