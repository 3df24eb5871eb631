// A one-line progress bar on stderr for long runs. It appears only when enabled (the caller
// passes whether stderr is a terminal), only after the run has taken 1 s, is redrawn at most
// 10 times a second, and is erased at the end so that only the summary remains.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

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

 private:
  using Clock = std::chrono::steady_clock;
  int64_t total_;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point begin_;
  Clock::time_point last_draw_;
};

/// The bar's text, at most `width` columns, e.g.
/// `prs: [#######>            ]  37%  37000/100000 scenes  24817/s  ETA 3s`.
std::string FormatProgressLine(int64_t done, int64_t total, double elapsed_s, int width);

}  // namespace prs::cli
