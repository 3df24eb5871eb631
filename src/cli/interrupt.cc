// Signal handlers that only set a lock-free flag (async-signal-safe), installed with
// SA_RESETHAND so that a second Ctrl-C is not caught.
#include "cli/interrupt.h"

#include <signal.h>

namespace prs::cli {
namespace {

std::atomic<bool> interrupted{false};
std::atomic<int> received_signal{0};
struct sigaction previous_sigint, previous_sigterm;

void NoteSignal(int signal_number) {
  received_signal.store(signal_number, std::memory_order_relaxed);
  interrupted.store(true, std::memory_order_relaxed);
}

// Leaves a signal alone when it is ignored (SIGINT for a background job of a script).
void Install(int signal_number, struct sigaction* previous) {
  sigaction(signal_number, nullptr, previous);
  if (previous->sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = NoteSignal;
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigemptyset(&action.sa_mask);
  sigaction(signal_number, &action, previous);
}

}  // namespace

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "signal handlers may only touch lock-free atomics");

InterruptWatch::InterruptWatch() {
  interrupted = false;
  received_signal = 0;
  Install(SIGINT, &previous_sigint);
  Install(SIGTERM, &previous_sigterm);
}

InterruptWatch::~InterruptWatch() {
  sigaction(SIGINT, &previous_sigint, nullptr);
  sigaction(SIGTERM, &previous_sigterm, nullptr);
}

const std::atomic<bool>& InterruptWatch::flag() const { return interrupted; }

int InterruptWatch::signal_number() const { return received_signal.load(); }

}  // namespace prs::cli
