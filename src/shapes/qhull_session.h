// Internal to prs_shapes: one qhull run with its setup and teardown in one place (mesh.cc's 3-D
// hulls, support.cc's 2-D areas). qhull's own reports go to /dev/null; callers say ours.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace prs::shapes::internal {

/// Runs qhull on `coordinates` (dim numbers per point) with `flags`; while the hull is alive,
/// calls `read(qh)` when qhull succeeded. Returns qhull's exit status (0 on success).
template <typename Read>
int RunQhull(int dim, std::vector<coordT>& coordinates, const char* flags, Read read) {
  qhT qh_storage;
  qhT* qh = &qh_storage;
  FILE* quiet = std::fopen("/dev/null", "w");
  qh_zero(qh, quiet);
  std::vector<char> options(flags, flags + std::char_traits<char>::length(flags) + 1);
  const int status = qh_new_qhull(qh, dim, static_cast<int>(coordinates.size() / dim),
                                  coordinates.data(), False, options.data(), quiet, quiet);
  if (status == 0) read(qh);
  qh_freeqhull(qh, !qh_ALL);
  int still_long = 0, still_total = 0;
  qh_memfreeshort(qh, &still_long, &still_total);
  if (quiet) std::fclose(quiet);
  return status;
}

}  // namespace prs::shapes::internal
