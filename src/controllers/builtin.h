// The built-in controllers that live in other stages (the simulated case study), registered with
// the harness's registry before `prs test`, `prs campaign` or the Python package look them up.
// A stage of its own, above src/sim and src/harness, so that those two need not know each other.
#pragma once

#include <atomic>
#include <optional>
#include <string>

#include "harness/harness.h"

namespace prs::controllers {

/// Registers `table-cube`, `table-cube-paper` and `table-cube-clear-view` (src/sim's
/// case-study controllers). Idempotent and thread-safe.
void RegisterBuiltInControllers();

/// The warning an --exec episode reports (harness::EpisodeResult::warnings) when its scene has
/// no free body.
extern const char* const kNoFreeBodyWarning;

/// Every registered controller's name, comma-separated, after RegisterBuiltInControllers().
std::string ListControllerNames();

/// The factory of the shell command `exec` (harness::ExecController with `timeout_s` and
/// `cancel`, warning with kNoFreeBodyWarning on scenes without a free body) when it is not
/// empty, else of the registered controller `name`; nullopt when no
/// controller has that name. Registers the built-in controllers first.
std::optional<harness::ControllerFactory> MakeControllerFactory(const std::string& name,
                                                                const std::string& exec,
                                                                double timeout_s,
                                                                const std::atomic<bool>* cancel);

}  // namespace prs::controllers
