// Test helper: scenes sampled from every scenario in examples/ (several seeds), exported, and
// the checks every format test shares.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "export/export.h"

namespace prs::exporting::testing_scenes {

struct ExampleScene {
  std::string label;                   // "table_cube.prs seed 2 index 0", for failure messages
  const lang::Scene* scene = nullptr;  // owned by the helper, alive for the whole test program
  ExportScene exported;
};

/// Scenes 0 and 1 of seeds 1..3 of every examples/*.prs that places objects (sampled once).
const std::vector<ExampleScene>& ExampleScenes();

/// Compiles and samples scene `index` of `seed` of scenario text (imports resolved from
/// examples/); fails the test on compile errors.
const lang::Scene& SampleText(const std::string& text, uint64_t seed = 1, uint64_t index = 0);

/// Rotations equal within `radians` (q and -q are the same rotation).
::testing::AssertionResult SameRotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b,
                                        double radians = 1e-9);
/// Vectors equal within `tolerance` in every coordinate.
::testing::AssertionResult SameVector(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      double tolerance = 1e-9);

}  // namespace prs::exporting::testing_scenes
