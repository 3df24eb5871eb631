// Samples the example scenarios once per test program, for every format test to check.
#include "export/test/example_scenes.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "sampling/gibbs.h"
#include "sampling/sampler.h"

namespace prs::exporting::testing_scenes {
namespace {

namespace fs = std::filesystem;

fs::path RepoRoot() {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  return dir ? fs::path(dir) : fs::path(PRS_DEFAULT_SOURCE_DIR);
}

// Programs and scenes live until exit: scenes point at their program's classes.
struct Store {
  std::vector<std::unique_ptr<lang::CompiledProgram>> programs;
  std::vector<std::unique_ptr<lang::Scene>> scenes;
};
Store& TheStore() {
  static Store store;
  return store;
}

const lang::CompiledProgram* Compile(const std::string& path, const std::string* text) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.search_path = {(RepoRoot() / "examples").string()};
  auto program = text ? lang::CompileText(path, *text, options, diagnostics)
                      : lang::CompileFile(path, options, diagnostics);
  for (const lang::Diagnostic& d : diagnostics.diagnostics())
    ADD_FAILURE() << lang::RenderDiagnostic(d, program->sources, false);
  if (diagnostics.has_errors()) return nullptr;
  TheStore().programs.push_back(std::move(program));
  return TheStore().programs.back().get();
}

const lang::Scene& Keep(sampling::SampledScene sampled) {
  TheStore().scenes.push_back(std::make_unique<lang::Scene>(std::move(sampled.scene)));
  return *TheStore().scenes.back();
}

std::vector<ExampleScene> SampleExamples() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(RepoRoot() / "examples")) {
    if (entry.path().extension() == ".prs") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<ExampleScene> scenes;
  for (const fs::path& file : files) {
    const lang::CompiledProgram* program = Compile(file.string(), nullptr);
    if (program == nullptr) continue;
    // Clutter beyond whole-scene rejection is drawn by a Gibbs chain (sampling/gibbs.h).
    sampling::SampleOptions options;
    if (file.filename() == "bin_clutter.prs") {
      options.gibbs = std::make_shared<sampling::GibbsRequest>();
    }
    sampling::SceneSampler sampler(*program, options);
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      for (uint64_t index = 0; index < 2; ++index) {
        const lang::Scene& scene = Keep(sampler.Sample(seed, index));
        if (scene.objects.empty()) break;  // a module of classes only (model.prs)
        const std::string label = file.filename().string() + " seed " + std::to_string(seed) +
                                  " index " + std::to_string(index);
        scenes.push_back({label, &scene, MakeExportScene(scene, label)});
      }
    }
  }
  return scenes;
}

}  // namespace

const std::vector<ExampleScene>& ExampleScenes() {
  static const std::vector<ExampleScene> scenes = SampleExamples();
  return scenes;
}

const lang::Scene& SampleText(const std::string& text, uint64_t seed, uint64_t index) {
  static const lang::Scene kEmpty;
  const std::string path = (RepoRoot() / "examples" / "test_scenario.prs").string();
  const lang::CompiledProgram* program = Compile(path, &text);
  if (program == nullptr) return kEmpty;
  return Keep(sampling::SampleScene(*program, seed, index));
}

::testing::AssertionResult SameRotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b,
                                        double radians) {
  const double angle = a.normalized().angularDistance(b.normalized());
  if (angle <= radians) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "rotations differ by " << angle << " rad: (" << a.coeffs().transpose() << ") vs ("
         << b.coeffs().transpose() << ") [x y z w]";
}

::testing::AssertionResult SameVector(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      double tolerance) {
  if ((a - b).cwiseAbs().maxCoeff() <= tolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.transpose() << ") vs (" << b.transpose() << ")";
}

}  // namespace prs::exporting::testing_scenes
