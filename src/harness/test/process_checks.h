// Test helper: whether a process the harness should have killed is gone.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

namespace prs::harness::testing_checks {

/// True once `pid` no longer runs: it does not exist, or is a zombie waiting for its new parent
/// to reap it. A SIGKILL takes effect asynchronously, so this waits up to 2 s.
inline bool IsGone(pid_t pid) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  do {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string pid_text, name, state;
    if (!(stat >> pid_text >> name >> state) || state == "Z" || state == "X") return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  } while (std::chrono::steady_clock::now() < deadline);
  return false;
}

}  // namespace prs::harness::testing_checks
