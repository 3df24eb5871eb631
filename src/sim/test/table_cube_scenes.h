// The sim tests' scenes: examples/table_cube.prs and examples/table_cube_paper_model.prs (the
// same scenario with the original tool's 1.026 m tall robot boxes), compiled once per test
// program (scenes point at their classes, so they live until exit), and scenes of seed 1.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "sampling/sampler.h"

namespace prs::sim::testing_scenes {

// examples/NAME, compiled; never freed. Fails the test on compile errors.
inline const lang::CompiledProgram* CompileExample(const std::string& name) {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  lang::DiagnosticEngine diagnostics;
  const std::string path = std::string(dir ? dir : PRS_DEFAULT_SOURCE_DIR) + "/examples/" + name;
  auto compiled = lang::CompileFile(path, {}, diagnostics);
  EXPECT_FALSE(diagnostics.has_errors()) << name;
  return compiled.release();
}

inline const lang::CompiledProgram& TableCubeProgram() {
  static const lang::CompiledProgram* program = CompileExample("table_cube.prs");
  return *program;
}

inline const lang::CompiledProgram& PaperModelProgram() {
  static const lang::CompiledProgram* program = CompileExample("table_cube_paper_model.prs");
  return *program;
}

inline lang::Scene SampleTableCube(uint64_t index) {
  return sampling::SampleScene(TableCubeProgram(), 1, index).scene;
}

inline lang::Scene SamplePaperModel(uint64_t index) {
  return sampling::SampleScene(PaperModelProgram(), 1, index).scene;
}

/// The scene with every Robot box `height_m` tall and turned to `yaw_rad` about the vertical,
/// still standing on what it stood on (its bottom face stays where it was).
inline lang::Scene WithRobotBoxes(lang::Scene scene, double height_m, double yaw_rad) {
  for (lang::SceneObject& o : scene.objects) {
    if (o.cls == nullptr || o.cls->name != "Robot") continue;
    const double bottom_z = o.p_WO.z() - o.dimensions.z() / 2;
    o.dimensions.z() = height_m;
    o.p_WO.z() = bottom_z + height_m / 2;
    o.R_WO = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ());
  }
  return scene;
}

}  // namespace prs::sim::testing_scenes
