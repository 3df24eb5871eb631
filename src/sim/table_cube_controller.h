// The paper's case-study controller for Table-Cube scenes, in two variants.
// - kRealistic ("table-cube"): it finds the cube as a blue blob in the ceiling camera's full
//   RGB-D image (arms can hide it), back-projects it into the world, and with inverse
//   kinematics the arm nearest the cube picks it, puts it down between the arms, and the other
//   arm picks it again (from a new image) and drops it into the tray in front of it.
// - kPaper ("table-cube-paper"): the original tool's controller — the cube seen alone in the
//   depth image (paper_perception.h), the first Robot picks it, drops it from 0.2 m above the
//   trays' midpoint and moves 0.45 m away, the second picks it and drops it 0.1 m above the
//   second tray; success is the paper's loose criterion (within 0.453 m of that tray in x and y).
// Neither controller reads the cube's true pose; only the outcome classification afterwards
// compares with it.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camera/camera.h"
#include "lang/scene.h"
#include "render/render.h"

namespace prs::render {
class ModelRenderer;
}

namespace prs::sim {

enum class TableCubeVariant { kRealistic, kPaper };

/// What a learned perception is shown at one sighting: the ceiling camera's picture (rows from
/// the top), its depth (metres along the look axis) and the camera's pose and field of view.
struct CubeSightingRequest {
  const render::Image& rgb;
  const render::DepthImage& depth;
  const camera::PinholeCamera& camera;
  int sighting = 0;  // 0: at the start; 1: after the hand-over
};

/// What it answers: the cube's centre in the world frame (metres), or, when it has none,
/// the episode's outcome ("perception-fault": it saw no cube; "controller-error": the
/// perception itself failed) and a sentence saying why.
struct CubeSightingAnswer {
  std::optional<Eigen::Vector3d> p_WCube;
  std::string outcome;
  std::string detail;
};

/// A perception the controller calls instead of its own colour-blob detector (the learned
/// model of `prs test --perception CMD`, bound in src/controllers).
using CubePerception = std::function<CubeSightingAnswer(const CubeSightingRequest&)>;

struct TableCubeOptions {
  TableCubeVariant variant = TableCubeVariant::kRealistic;
  int image_width = 640;  // kPaper: the original's 256 x 256 (MakePaperTableCubeOptions)
  int image_height = 480;
  double cube_size_m = 0.05;           // the task's nominal cube, known to the controller
  double perception_tolerance_m = 0.015;  // a sighting further off than this is a fault
  /// The camera's field of view (degrees, both image axes of the square kPaper image) when its
  /// object has no `fovy_deg`: unset keeps the export's 45° (docs/export.md); the paper
  /// variant takes 60°, the default of the vision sensor the original created.
  std::optional<double> default_fovy_deg = std::nullopt;
  /// The fix documented in docs/case_study.md: turn both arms away (joint 1 to the back)
  /// before each picture, so that no arm hides the cube from the ceiling camera.
  bool clear_view_before_sighting = false;
  /// kRealistic only: where the cube is comes from this function instead of the blue blob.
  /// An answer off the table's top (outside its footprint, more than kMaxAboveTable_m above it,
  /// or more than the cube's size below it) ends the episode as "perception-fault" before any
  /// arm moves there.
  CubePerception perception = nullptr;
};

/// How far above the table's top a perceived cube's centre may be.
inline constexpr double kMaxAboveTable_m = 0.3;

/// The original tool's controller: kPaper with its 256 x 256 depth camera.
TableCubeOptions MakePaperTableCubeOptions();

/// What happened in one episode. `outcome` is one of "success", "perception-fault",
/// "no-path", "poor-grip", "missed-tray", "no-camera", "no-cube", "world-error".
struct TaskOutcome {
  std::string outcome;
  std::string detail;  // one sentence: what went wrong, with numbers
  std::vector<std::pair<std::string, double>> metrics;  // e.g. perception error, final position
  std::vector<std::pair<std::string, bool>> flags = {};  // e.g. whether the cube ended in the tray
  /// About the scene rather than the controller, for the user once per run (e.g. the cube had
  /// no mass and was given one).
  std::vector<std::string> warnings = {};
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
  TableCubeOptions options_;
  // Made on the first episode and kept: the OpenGL context outlives each episode's world.
  std::unique_ptr<render::ModelRenderer> renderer_;
};

}  // namespace prs::sim
