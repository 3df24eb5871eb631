// Always-on invariant checks for the geometry library: PRS_CHECK(cond) aborts with
// file:line when an internal invariant is broken (never used for bad user arguments).
#pragma once

#include <cstdio>
#include <cstdlib>

namespace prs::geometry::internal {

/// Reports a failed invariant on stderr and aborts. Never returns.
[[noreturn]] inline void CheckFailed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: PRS_CHECK failed: %s\n", file, line, condition);
  std::abort();
}

}  // namespace prs::geometry::internal

#define PRS_CHECK(cond)                                                  \
  do {                                                                   \
    if (!(cond)) ::prs::geometry::internal::CheckFailed(#cond, __FILE__, __LINE__); \
  } while (0)
