// Scenes per second on one thread for the bundled examples (JSON writing included), naive
// against region sampling, reachable and visible against Figure 1, and compile time. Figures
// go to docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

#include "output/scene_json.h"
#include "sampling/sampler.h"

namespace {

using prs::lang::CompiledProgram;
using prs::sampling::SampleOptions;
using prs::sampling::SceneSampler;

std::string Example(const std::string& name) {
  const char* root = std::getenv("PRS_SOURCE_DIR");
  return std::string(root ? root : PRS_DEFAULT_SOURCE_DIR) + "/examples/" + name;
}

std::unique_ptr<CompiledProgram> Compile(const std::string& path) {
  prs::lang::DiagnosticEngine diagnostics;
  prs::lang::CompileOptions options;
  options.cache_dir = prs::lang::DefaultCacheDir();  // reachable sets as prs reads them
  auto program = prs::lang::CompileFile(path, options, diagnostics);
  if (diagnostics.has_errors()) {
    std::fprintf(stderr, "%s does not compile\n", path.c_str());
    std::exit(1);
  }
  return program;
}

// One scene per iteration, rendered to JSON as `prs sample` does; counters report attempts.
void SampleScenes(benchmark::State& state, const std::string& file, bool naive,
                  bool json = true) {
  auto program = Compile(Example(file));
  SampleOptions options;
  options.max_attempts = 10'000'000;
  if (naive) options.run.mode = prs::lang::SamplingMode::kNaive;
  SceneSampler sampler(*program, options);
  // Reachable sets are made (or read from the cache) the first time a scene needs them: not timed.
  benchmark::DoNotOptimize(prs::sampling::SampleScene(*program, 1, 0, options).attempts);
  uint64_t index = 0;
  int64_t attempts = 0;
  size_t bytes = 0;
  for (auto _ : state) {
    const auto scene = sampler.Sample(1, index++);
    attempts += scene.attempts;
    if (json) bytes += prs::output::FormatSceneJson(scene).size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["attempts_per_scene"] = double(attempts) / state.iterations();
  benchmark::DoNotOptimize(bytes);
}

void BM_TableCubeRegion(benchmark::State& state) { SampleScenes(state, "table_cube.prs", false); }
void BM_TableCubeRegionNoJson(benchmark::State& state) {
  SampleScenes(state, "table_cube.prs", false, false);
}
void BM_TableCubeNaive(benchmark::State& state) { SampleScenes(state, "table_cube.prs", true); }
void BM_ConstructsRegion(benchmark::State& state) { SampleScenes(state, "constructs.prs", false); }
// Figure 1 with `reachable by` both arms and `completely visible from` the camera.
void BM_TableCubeReachableVisible(benchmark::State& state) {
  SampleScenes(state, "table_cube_reachable_visible.prs", false);
}

void BM_CompileTableCube(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(Compile(Example("table_cube.prs")));
}

}  // namespace

BENCHMARK(BM_TableCubeRegion)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TableCubeRegionNoJson)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TableCubeNaive)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_ConstructsRegion)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TableCubeReachableVisible)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompileTableCube)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
