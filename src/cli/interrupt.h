// Graceful Ctrl-C: while an InterruptWatch lives, SIGINT and SIGTERM only raise a flag that a
// long run polls to stop cleanly (whole lines written, progress bar erased); a second signal
// gets the default action and ends the process at once.
#pragma once

#include <atomic>

namespace prs::cli {

class InterruptWatch {
 public:
  /// Installs the handlers. Only one InterruptWatch may exist at a time.
  InterruptWatch();
  /// Restores the previous handlers.
  ~InterruptWatch();
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;

  /// Becomes true when SIGINT or SIGTERM arrives.
  const std::atomic<bool>& flag() const;
  /// The signal that arrived (0 if none).
  int signal_number() const;
};

}  // namespace prs::cli
