// The `prs` command: `prs sample FILE` writes scenes as JSON Lines, `prs check FILE` compiles
// and reports errors. Data on stdout, diagnostics and the summary on stderr.
// Exit codes: 0 success, 1 scenario error, 2 usage error, 3 sampling failure.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "output/scene_json.h"

namespace {

constexpr int kExitScenarioError = 1;
constexpr int kExitUsage = 2;
constexpr int kExitSamplingFailure = 3;

struct CommonOptions {
  std::string file;
  std::vector<std::string> include_dirs;
  std::vector<std::string> params;
};

void PrintDiagnostics(const prs::lang::DiagnosticEngine& diagnostics,
                      const prs::lang::SourceManager& sources) {
  for (const auto& d : diagnostics.diagnostics()) {
    std::cerr << prs::lang::RenderDiagnostic(d, sources);
  }
}

std::unique_ptr<prs::lang::CompiledProgram> Compile(const CommonOptions& common) {
  prs::lang::CompileOptions options;
  options.search_path = common.include_dirs;
  if (const char* env = std::getenv("PRS_PATH")) {
    std::stringstream path(env);
    for (std::string dir; std::getline(path, dir, ':');) {
      if (!dir.empty()) options.search_path.push_back(dir);
    }
  }
  for (const std::string& p : common.params) {
    const size_t eq = p.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::cerr << "prs: error: -p expects NAME=VALUE, got '" << p << "'\n";
      std::exit(kExitUsage);
    }
    options.param_overrides.emplace_back(p.substr(0, eq), p.substr(eq + 1));
  }
  prs::lang::DiagnosticEngine diagnostics;
  auto program = prs::lang::CompileFile(common.file, options, diagnostics);
  PrintDiagnostics(diagnostics, program->sources);
  if (diagnostics.has_errors()) return nullptr;
  return program;
}

int RunSample(const CommonOptions& common, int64_t count, uint64_t seed, uint64_t start,
              int64_t max_attempts, bool naive) {
  auto program = Compile(common);
  if (!program) return kExitScenarioError;
  prs::sampling::SampleOptions options;
  options.max_attempts = max_attempts;
  options.run.mode = naive ? prs::lang::SamplingMode::kNaive : prs::lang::SamplingMode::kRegion;
  prs::sampling::RejectionCounts totals;
  int64_t attempts = 0;
  const auto begin = std::chrono::steady_clock::now();
  try {
    for (int64_t i = 0; i < count; ++i) {
      const auto sampled = prs::sampling::SampleScene(*program, seed, start + i, options);
      std::cout << prs::output::FormatSceneJson(sampled) << '\n';
      attempts += sampled.attempts;
      totals.Merge(sampled.rejections);
    }
  } catch (const prs::lang::ScenarioError& error) {
    std::cout.flush();
    std::cerr << prs::lang::RenderDiagnostic(error.diagnostic(), program->sources);
    return error.diagnostic().id == "sampling-failed" ? kExitSamplingFailure : kExitScenarioError;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  std::fprintf(stderr, "prs: %lld scenes, %lld attempts, %lld rejections", (long long)count,
               (long long)attempts, (long long)totals.total);
  for (const auto& [kind, n] : totals.by_kind) {
    std::fprintf(stderr, ", %s %lld", prs::lang::RejectionKindName(kind), (long long)n);
  }
  std::fprintf(stderr, "; %.0f scenes/s\n", seconds > 0 ? count / seconds : 0.0);
  return 0;
}

int RunCheck(const CommonOptions& common) {
  auto program = Compile(common);
  if (!program) return kExitScenarioError;
  std::cerr << "prs: " << common.file << ": ok (" << program->modules.size() << " modules, "
            << program->classes.size() << " classes, " << program->plans.size()
            << " creation sites)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"prs: sample scenes from ProbRobScene programs"};
  app.require_subcommand(1);
  CommonOptions common;
  auto add_common = [&](CLI::App* command) {
    command->add_option("FILE", common.file, "the .prs scenario")->required();
    command->add_option("-I", common.include_dirs, "a directory searched for imported modules");
    command->add_option("-p,--param", common.params, "override a param: NAME=VALUE");
  };
  int64_t count = 1, max_attempts = 10000;
  uint64_t seed = 0, start = 0;
  bool naive = false;
  CLI::App* sample = app.add_subcommand("sample", "write scenes as JSON Lines to stdout");
  add_common(sample);
  sample->add_option("-n,--count", count, "number of scenes")->check(CLI::NonNegativeNumber);
  sample->add_option("-s,--seed", seed, "random seed");
  sample->add_option("--start", start, "index of the first scene");
  sample->add_option("--max-attempts", max_attempts, "attempts per scene before failing")
      ->check(CLI::PositiveNumber);
  sample->add_flag("--naive", naive, "the paper's baseline: rejection from the workspace");
  CLI::App* check = app.add_subcommand("check", "compile a scenario and report errors");
  add_common(check);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitUsage;
  }
  if (sample->parsed()) return RunSample(common, count, seed, start, max_attempts, naive);
  return RunCheck(common);
}
