// libFuzzer entry point for the language stage: the input is a scenario's source text. It is
// compiled (with the repository's examples/ modules importable, served from memory), every
// diagnostic is rendered, and a program that compiled cleanly is run for a few bounded attempts.
// Only ScenarioError may escape the interpreter; any other exception, crash, hang, leak or
// sanitizer report is a bug (spec §9: "never a crash, a hang, or a library's internals").
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <variant>

#include "geometry/random.h"
#include "lang/diagnostics.h"
#include "lang/lang.h"

namespace {

// Serves examples/*.prs, read once at start-up; nothing else is readable, so imports are
// deterministic and the fuzzer never touches the rest of the disk.
class ExamplesFileSystem : public prs::lang::FileSystem {
 public:
  ExamplesFileSystem() {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(PRS_FUZZ_EXAMPLES_DIR, ec)) {
      if (entry.path().extension() != ".prs") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      files_[entry.path().string()] = text.str();
    }
  }
  std::optional<std::string> ReadFile(const std::string& path) const override {
    auto it = files_.find(std::filesystem::path(path).lexically_normal().string());
    if (it == files_.end()) return std::nullopt;
    return it->second;
  }

 private:
  std::map<std::string, std::string> files_;
};

void RenderAll(const prs::lang::DiagnosticEngine& diagnostics,
               const prs::lang::SourceManager& sources) {
  bool color = false;
  for (const prs::lang::Diagnostic& d : diagnostics.diagnostics()) {
    volatile size_t sink = prs::lang::RenderDiagnostic(d, sources, color).size();
    (void)sink;
    color = !color;  // both renderings get exercised
  }
}

// Inputs up to 16 KiB by default; PRS_FUZZ_MAX_BYTES raises it for the long-input run
// (scripts/fuzz.sh SECONDS long), where 100,000-term chains test the stack-depth limits.
size_t MaxInputBytes() {
  static const size_t kMax = [] {
    const char* text = std::getenv("PRS_FUZZ_MAX_BYTES");
    return text ? static_cast<size_t>(std::strtoull(text, nullptr, 10)) : size_t{16 * 1024};
  }();
  return kMax;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > MaxInputBytes()) return -1;  // larger inputs add nothing but time
  static const ExamplesFileSystem kFileSystem;
  prs::lang::CompileOptions options;
  options.search_path = {PRS_FUZZ_EXAMPLES_DIR};
  options.file_system = &kFileSystem;
  // `reachable by` on the coarsest grid (a second or two under the sanitizers, not a minute),
  // cached where scripts/fuzz.sh points PRS_CACHE_DIR, so each arm and options set is computed
  // once per fuzzing run; the inputs exercise the code, not the cells' precision.
  options.reach_resolution_m = 0.1;
  options.cache_dir = prs::lang::DefaultCacheDir();
  prs::lang::DiagnosticEngine diagnostics;
  auto program = prs::lang::CompileText(
      "fuzz.prs", std::string(reinterpret_cast<const char*>(data), size), options, diagnostics);
  RenderAll(diagnostics, program->sources);
  if (diagnostics.has_errors()) return 0;

  prs::lang::RunOptions run;
  run.limits.max_loop_iterations = 2'000;
  run.limits.max_call_depth = 20;
  run.limits.max_objects = 30;
  // The second attempt keeps work from the first (templates, shared modules, kept regions) as
  // a sampler does; the last uses the naive mode so its checks are fuzzed too.
  auto cache = prs::lang::MakeRunCache();
  for (uint64_t attempt = 0; attempt < 3; ++attempt) {
    run.mode = attempt == 2 ? prs::lang::SamplingMode::kNaive : prs::lang::SamplingMode::kRegion;
    run.cache = attempt == 2 ? nullptr : cache.get();
    prs::geometry::Rng rng(/*seed=*/7, /*stream=*/attempt);
    try {
      auto result = prs::lang::RunAttempt(*program, rng, run);
      volatile bool accepted = std::holds_alternative<prs::lang::Scene>(result);
      (void)accepted;
    } catch (const prs::lang::ScenarioError& error) {
      volatile size_t sink =
          prs::lang::RenderDiagnostic(error.diagnostic(), program->sources).size();
      (void)sink;
    }
  }
  return 0;
}
