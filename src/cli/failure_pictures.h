// Pictures of the failing scenes that `prs test --save-failures DIR` saved: STEM.png beside
// each STEM.json, drawn by src/render (`prs render`'s library).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/harness.h"

namespace prs::cli {

/// Draws STEM.png (640x480, overview, captioned with seed, index and outcome) for each record
/// whose scene was saved as STEM.json, one after another with one renderer on this thread.
/// Returns how many were drawn. Throws std::runtime_error when no
/// OpenGL context can be made or a file cannot be read or written.
int64_t DrawFailurePictures(const std::vector<harness::EpisodeRecord>& records);

/// After `prs test` or `prs search` with --save-failures DIR: draws the pictures and says how
/// many failing scenes were saved where. Returns the exit code (kExitScenarioError when the
/// pictures cannot be drawn, after saying so).
int ReportSavedFailures(const std::vector<harness::EpisodeRecord>& records,
                        const std::string& dir, bool quiet);

}  // namespace prs::cli
