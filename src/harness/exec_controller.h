// A user's own controller as a separate program (`prs test --exec CMD`): one process per
// episode, the scene JSON on its stdin and in a file, the outcome read from its last stdout
// line or its exit status (protocol in docs/harness.md).
#pragma once

#include <atomic>
#include <string>

#include "harness/harness.h"

namespace prs::harness {

struct ExecOptions {
  std::string command;    // run as `/bin/sh -c COMMAND`
  double timeout_s = 60;  // per episode; the process group is killed after it
  /// Polled every 50 ms; once true the running episode's process group is killed and the
  /// episode ends as "cancelled".
  const std::atomic<bool>* cancel = nullptr;
};

/// What the process answered, before it becomes an outcome (exposed for tests).
struct ExecAnswer {
  enum class End { kExited, kSignaled, kTimedOut, kCancelled };
  End end = End::kExited;
  int code = 0;             // exit code, or signal number for kSignaled
  /// For kSignaled: the exit status 128 + N by which /bin/sh reported its command's death by
  /// signal N; 0 when the shell itself was killed.
  int shell_status = 0;
  std::string stdout_tail;  // the end of its stdout (the last 64 KiB at least)
  std::string stderr_tail;  // the end of its stderr
};

/// Turns what the process did into an outcome: its last non-empty stdout line when that is a
/// JSON object with an "outcome" (a malformed one gives "bad-answer"), else its exit status
/// (0 success, "exit-N", "signal-N" for kSignaled), or "timeout" / "cancelled". An exit status
/// 128 + N is kSignaled already (internal::Reap reads the shell's report of a signal).
EpisodeResult InterpretAnswer(const ExecAnswer& answer, double timeout_s);

class ExecController : public Controller {
 public:
  /// Throws std::invalid_argument for an empty command or a timeout that is not positive.
  explicit ExecController(ExecOptions options);

  /// Runs the command once. The scene is written to a temporary file (removed afterwards)
  /// that is the process's stdin and is named by PRS_SCENE_FILE; PRS_SEED and PRS_INDEX name
  /// the scene. The process runs in its own process group, which is killed when the process
  /// ends (stray background children) or times out, so nothing outlives the episode.
  /// Throws std::runtime_error when the process cannot be started at all.
  EpisodeResult RunEpisode(const sampling::SampledScene& scene,
                           const std::string& scene_json) override;

 private:
  ExecOptions options_;
};

}  // namespace prs::harness
