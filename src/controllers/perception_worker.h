// A learned perception for the case study (`prs test --controller table-cube --perception CMD`):
// a persistent worker process (harness/line_worker.h) that is shown each sighting's picture as
// files laid out like a BOP image and answers where the cube is (protocol in docs/harness.md,
// "Perception workers"). Binds src/sim's CubePerception to src/harness's worker processes.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "harness/line_worker.h"
#include "sim/table_cube_controller.h"

namespace prs::controllers {

struct PerceptionOptions {
  std::string command;             // run as `/bin/sh -c COMMAND`
  double timeout_s = 60;           // per sighting, from the request sent to the answer read
  double startup_timeout_s = 120;  // from the start to the handshake (loading the model)
  const std::atomic<bool>* cancel = nullptr;
};

/// The depth picture's unit in millimetres (BOP's depth_scale): 0.1 mm, so that 16 bits reach
/// 6.5 m.
inline constexpr double kPerceptionDepthScale_mm = 0.1;

/// The pool of perception workers of one run: the controllers of every thread share it, each
/// holding one worker while it lives. Throws std::invalid_argument for an empty command or
/// timeouts that are not positive.
std::shared_ptr<harness::LineWorkerPool> MakePerceptionPool(const PerceptionOptions& options);

/// One controller's perception: a worker from `pool` and a directory of its own for the
/// pictures (removed with it). Not thread-safe: one per controller.
class PerceptionClient {
 public:
  explicit PerceptionClient(std::shared_ptr<harness::LineWorkerPool> pool);
  ~PerceptionClient();
  PerceptionClient(const PerceptionClient&) = delete;
  PerceptionClient& operator=(const PerceptionClient&) = delete;

  /// The scene the next sightings belong to (their answers must name it).
  void SetScene(uint64_t seed, uint64_t index) { seed_ = seed, index_ = index; }

  /// Writes the request's pictures, asks the worker and reads its answer. Never throws for
  /// what the worker does: a worker that fails or answers what is not an answer for this
  /// sighting gives "controller-error" with the reason (and is started afresh next time); an
  /// answer `{"found": false}` gives "perception-fault". Throws harness::ControllerStartError
  /// when the worker cannot start, std::runtime_error when the pictures cannot be written.
  sim::CubeSightingAnswer Ask(const sim::CubeSightingRequest& request);

 private:
  harness::LeasedLineWorker worker_;
  std::filesystem::path directory_;
  uint64_t seed_ = 0, index_ = 0;
};

}  // namespace prs::controllers
