// The sim tests' scenes: examples/table_cube.prs and examples/table_cube_paper_model.prs (the
// same scenario with the original tool's 1.026 m tall robot boxes), compiled once per test
// program (scenes point at their classes, so they live until exit), and scenes of seed 1.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
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

/// table_cube_paper_model.prs with the original model's Robot box `height_m` tall (the
/// model's text with that one number changed), compiled. Keep it while its scenes are used.
inline std::unique_ptr<lang::CompiledProgram> CompilePaperModelWithRobotHeight(double height_m) {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  const std::string examples = std::string(dir ? dir : PRS_DEFAULT_SOURCE_DIR) + "/examples/";
  std::ifstream model_file(examples + "paper_model.prs");
  std::stringstream model;
  model << model_file.rdbuf();
  std::string text = model.str();
  const std::string original = "height: 1.025562";
  const size_t at = text.find(original);
  EXPECT_NE(at, std::string::npos) << "paper_model.prs no longer has " << original;
  if (at != std::string::npos) {
    text.replace(at, original.size(), "height: " + std::to_string(height_m));
  }
  const std::string temp = ::testing::TempDir() + "prs_robot_height_" + std::to_string(height_m);
  std::filesystem::create_directories(temp);
  std::ofstream(temp + "/paper_model.prs") << text;
  std::ifstream scenario(examples + "table_cube_paper_model.prs");
  std::ofstream(temp + "/table_cube_paper_model.prs") << scenario.rdbuf();
  lang::DiagnosticEngine diagnostics;
  auto compiled = lang::CompileFile(temp + "/table_cube_paper_model.prs", {}, diagnostics);
  EXPECT_FALSE(diagnostics.has_errors()) << temp;
  return compiled;
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
