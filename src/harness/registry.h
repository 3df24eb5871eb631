// The built-in controllers that `prs test --controller NAME` can run, by name. Other stages
// (the simulated case study) register theirs; the demonstration `demo-reach` is always there.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "harness/harness.h"

namespace prs::harness {

struct ControllerInfo {
  std::string name;         // lowercase-hyphenated, e.g. "table-cube"
  std::string description;  // one line for `prs test --help` and error messages
  ControllerFactory factory;
};

/// Adds a controller. Thread-safe. Throws std::invalid_argument when `name` is not a
/// lowercase-hyphenated name, is already taken, or `factory` is empty.
void RegisterController(std::string name, std::string description, ControllerFactory factory);

/// The controller called `name`, or nullptr. The pointer stays valid for the program's life.
const ControllerInfo* FindController(const std::string& name);

/// Every controller, by name.
std::vector<ControllerInfo> ListControllers();

/// The demonstration controller `demo-reach`: no simulation, it decides from the scene alone
/// whether each Cube lies within a Panda arm's reach (0.25 to 0.855 m) of the nearest Robot.
std::unique_ptr<Controller> MakeDemoReachController();

/// A planted failure: the disk of radius `radius_m` around `p_center_xy` (world x, y, metres).
struct PlantedFailure {
  Eigen::Vector2d p_center_xy;
  double radius_m = 0;
};
/// The disks of `planted-1-percent` and `planted-1-permille`: around (-0.8, 0.3), the far
/// corner of the cube's range in examples/table_cube.prs, holding about 1 % and 0.1 % of its
/// scenes (measured in docs/search.md).
PlantedFailure PlantedOnePercent();
PlantedFailure PlantedOnePermille();
/// A controller that fails ("planted-failure") exactly when the first Cube's centre lies in
/// the disk, with score = the centre's distance to the disk (negative inside); "missing-object"
/// without a Cube.
std::unique_ptr<Controller> MakePlantedController(const PlantedFailure& failure);

}  // namespace prs::harness
