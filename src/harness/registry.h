// The built-in controllers that `prs test --controller NAME` can run, by name. Other stages
// (the simulated case study) register theirs; the demonstration `demo-reach` is always there.
#pragma once

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

}  // namespace prs::harness
