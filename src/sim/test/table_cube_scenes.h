// The sim tests' scenes: examples/table_cube.prs, compiled once per test program (scenes point
// at its classes, so it lives until exit), and its scene `index` of seed 1.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "sampling/sampler.h"

namespace prs::sim::testing_scenes {

inline const lang::CompiledProgram& TableCubeProgram() {
  static const lang::CompiledProgram* program = [] {
    const char* dir = std::getenv("PRS_SOURCE_DIR");
    lang::DiagnosticEngine diagnostics;
    auto compiled = lang::CompileFile(std::string(dir ? dir : PRS_DEFAULT_SOURCE_DIR) +
                                          "/examples/table_cube.prs", {}, diagnostics);
    EXPECT_FALSE(diagnostics.has_errors());
    return compiled.release();
  }();
  return *program;
}

inline lang::Scene SampleTableCube(uint64_t index) {
  return sampling::SampleScene(TableCubeProgram(), 1, index).scene;
}

}  // namespace prs::sim::testing_scenes
