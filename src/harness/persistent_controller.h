// A user's controller as a long-lived program (`prs test --exec CMD --persistent`): one process
// per worker thread, started once and handed scenes one JSON line at a time, for controllers
// that live in a simulator taking seconds to start (protocol in docs/harness.md).
#pragma once

#include <atomic>
#include <string>

#include "harness/harness.h"

namespace prs::harness {

struct PersistentOptions {
  std::string command;             // run as `/bin/sh -c COMMAND`
  double timeout_s = 60;           // per episode, from the scene sent to the answer read
  double startup_timeout_s = 120;  // from the start to the handshake line
  /// Polled between reads; once true the running episode's worker is killed and the episode
  /// ends as "cancelled".
  const std::atomic<bool>* cancel = nullptr;
};

/// The factory of persistent-worker controllers. The controllers it makes share one pool of
/// worker processes that lives as long as the factory and its controllers (so a search's
/// generations reuse the workers): a controller takes an idle worker, or a new one, and gives
/// it back when destroyed; at most as many processes run as controllers exist at once.
///
/// A controller's RunEpisode starts its worker when it has none (waiting for the handshake up
/// to startup_timeout_s), writes the scene line, and reads the answer line. A worker that
/// ends, passes timeout_s, answers what is not an answer for this scene, or is cancelled gives
/// that episode "exit-N" / "signal-N", "timeout", "bad-answer" or "cancelled", is killed with
/// its process group, and is started afresh before the next scene. A start that fails (the
/// process exits or sends no handshake in time) throws ControllerStartError naming the command,
/// what happened and its last error line. Workers are asked to stop by closing their stdin and
/// killed with their process group 2 s later at the latest.
/// Throws std::invalid_argument for an empty command or timeouts that are not positive.
ControllerFactory MakePersistentControllerFactory(const PersistentOptions& options);

}  // namespace prs::harness
