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

/// The controller a user chose: a registered one by name, or a shell command (--exec).
struct ControllerChoice {
  std::string name;
  std::string exec;
  double timeout_s = 60;           // --timeout: seconds an --exec episode may take
  bool persistent = false;         // --persistent: one --exec process per worker thread
  double startup_timeout_s = 120;  // --startup-timeout: seconds a persistent worker may start in
  /// --perception: a perception worker's command for table-cube (or table-cube-clear-view),
  /// with the timeouts above per sighting and to start (perception_worker.h).
  std::string perception = {};
};

/// The factory of the shell command `choice.exec` when it is not empty (harness::ExecController,
/// or with `persistent` harness::MakePersistentControllerFactory's, with the timeouts and
/// `cancel`, warning with kNoFreeBodyWarning on scenes without a free body), else of the
/// registered controller `choice.name`; nullopt when no controller has that name. With
/// `choice.perception`, table-cube's with a pool of perception workers; std::invalid_argument,
/// saying what to give, when the controller is not table-cube or table-cube-clear-view, or the
/// perception's command or timeouts are not usable. Registers the built-in controllers first.
std::optional<harness::ControllerFactory> MakeControllerFactory(const ControllerChoice& choice,
                                                                const std::atomic<bool>* cancel);

}  // namespace prs::controllers
