// A one-line progress bar on stderr for long runs. It appears only when enabled (the caller
// passes whether stderr is a terminal), only after the run has taken 1 s, is redrawn at most
// 10 times a second, and is erased at the end so that only the summary remains.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "sampling/batch.h"

namespace prs::cli {

class ProgressBar {
 public:
  ProgressBar(int64_t total, bool enabled);
  /// Erases the bar.
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Reports that `done` of the total are finished; cheap when nothing needs drawing.
  void Update(int64_t done);
  /// Removes the bar from the terminal (it may be drawn again by a later Update).
  void Erase();
  /// When enabled, connects the bar to a batch: attempts are counted as they happen, and
  /// while one scene takes over a second the line shows its attempts and rejections per
  /// second instead of a bar that does not move (its "program runs" with --sampler gibbs or
  /// partial-rejection). Both must outlive the batch.
  void Attach(sampling::BatchOptions& options, sampling::BatchCallbacks& callbacks);

 private:
  using Clock = std::chrono::steady_clock;
  void Tick();
  void Draw(const std::string& line, Clock::time_point now);
  int64_t total_;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point begin_;
  Clock::time_point last_draw_;
  sampling::LiveCounts live_;
  int64_t done_ = 0;
  Clock::time_point last_done_;   // when scene done_ - 1 was handed over
  int64_t attempts_at_done_ = 0;  // live_ counts then
  int64_t rejections_at_done_ = 0;
  const char* runs_noun_ = "attempts";  // what the live counts count
};

/// The bar's text, at most `width` columns, e.g.
/// `prs: [#######>            ]  37%  37000/100000 scenes  24817/s  ETA 3s`.
std::string FormatProgressLine(int64_t done, int64_t total, double elapsed_s, int width);

/// The line while scene `done` (0-based) is hard to find, at most `width` columns, e.g.
/// `prs: scene 4 of 10: 1234567 attempts in 12s, 102880/s, 100.0% rejected` (`runs_noun`
/// names what `attempts` counts: "program runs" for the samplers that are not rejection).
std::string FormatHardSceneLine(int64_t done, int64_t total, int64_t attempts, int64_t rejections,
                                double seconds, int width, const char* runs_noun = "attempts");

}  // namespace prs::cli
