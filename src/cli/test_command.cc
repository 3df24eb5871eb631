// `prs test`: runs a robot controller (a built-in one, or the user's own program with --exec)
// in sampled scenes, prints the outcome table (the paper's Table III) on stdout, one JSON
// record per episode to -o, and saves the failing scenes with --save-failures (docs/harness.md).
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/controller_options.h"
#include "cli/design_option.h"
#include "search/like.h"
#include "cli/failure_pictures.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "harness/harness.h"
#include "output/line_writer.h"

namespace prs::cli {
namespace {

struct TestArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  ControllerArgs controller;
  DesignArgs design;
  SceneRangeArgs range{.count = 100, .start = 0};
  std::string output;  // empty: no records written
  std::string save_failures_dir;
  bool quiet = false;
};

harness::RunOptions MakeRunOptions(const TestArgs& args, const std::atomic<bool>& cancel) {
  harness::RunOptions options;
  options.sample = MakeSampleOptions(args.sampling);
  options.seed = args.sampling.seed;
  options.start = args.range.start;
  options.count = args.range.count;
  options.threads = args.sampling.threads;
  options.scenario_args = MakeScenarioWords(args.scenario, args.sampling);
  // A Sobol or Halton scene is (seed, index, design): `prs sample --design` rewrites it. A
  // lattice scene depends on the lattice's size too, so no one-scene command rewrites it.
  if (args.design.name == "sobol" || args.design.name == "halton") {
    options.scenario_args.insert(options.scenario_args.end(), {"--design", args.design.name});
  } else if (args.design.name == "lattice") {
    options.scenario_args.clear();
  }
  options.save_failures_dir = args.save_failures_dir;
  // Pictures are drawn after the run from the saved JSON (failure_pictures.h), so no
  // FailureHook is needed here.
  options.cancel = &cancel;
  return options;
}

// "10 episodes, 7 successes, 3 failures; 0.05 s, 12000 episodes/min on 2 threads"
std::string FormatTestSummary(const harness::RunSummary& summary, double seconds) {
  int64_t successes = 0;
  for (const harness::EpisodeRecord& record : summary.records) {
    successes += record.result.outcome == "success";
  }
  const int64_t episodes = int64_t(summary.records.size());
  const double per_minute = seconds > 0 ? 60 * double(episodes) / seconds : 0.0;
  return fmt::format("{}, {}, {}; {:.2f} s, {:.0f} episodes/min on {}",
                     FormatCount(episodes, "episode"), FormatCount(successes, "success"),
                     FormatCount(episodes - successes, "failure"), seconds, per_minute,
                     FormatCount(summary.threads, "thread"));
}

bool IsEveryOutcome(const std::vector<harness::EpisodeRecord>& records, const std::string& name) {
  return !records.empty() && std::all_of(records.begin(), records.end(), [&](const auto& record) {
    return record.result.outcome == name;
  });
}

// Runs the episodes, writing each record as it arrives; returns the exit code.
int RunAndReport(const lang::CompiledProgram& program, const harness::ControllerFactory& factory,
                 const TestArgs& args, output::LineWriter* records, InterruptWatch& interrupt) {
  harness::RunOptions options = MakeRunOptions(args, interrupt.flag());
  std::unique_ptr<search::Design> design;
  ProgressBar progress(args.range.count, !args.quiet && IsStderrTerminal());
  int64_t done = 0;
  options.on_record = [&](const harness::EpisodeRecord& record) {
    if (records) records->AddLine(harness::FormatRecordJson(record));
    progress.Update(++done);
  };
  options.on_warning = WarnOnce([&] { progress.Erase(); });
  const auto begin = std::chrono::steady_clock::now();
  try {
    if (!PrepareDesign(args.design, program, args.range, options.sample, &design)) return kExitUsage;
    options.spec_hash = search::CalcSpecHash(program);
    const harness::RunSummary summary = harness::RunEpisodes(program, factory, options);
    if (records) records->Commit();
    progress.Erase();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::cout << FormatOutcomeTable(summary.records) << std::flush;
    if (!args.quiet) PrintNote(FormatTestSummary(summary, seconds));
    if (IsEveryOutcome(summary.records, "exit-127")) {
      PrintNote("every episode exited with code 127: the shell did not find the --exec command");
    }
    return args.save_failures_dir.empty()
               ? kExitSuccess
               : ReportSavedFailures(summary.records, args.save_failures_dir, args.quiet);
  } catch (const lang::ScenarioError& error) {
    progress.Erase();
    return ReportScenarioError(error, program.sources);
  } catch (const sampling::BatchCancelled&) {
    progress.Erase();
    PrintNote(fmt::format("interrupted after {} (resume with --start {} -n {})",
                          FormatCount(done, "episode"), args.range.start + uint64_t(done),
                          args.range.count - done));
    return kExitInterruptedBase + interrupt.signal_number();
  } catch (const std::exception& error) {  // records or failing scenes cannot be written
    progress.Erase();
    PrintError(error.what());
    return kExitScenarioError;
  }
}

// Checks that need no scenario, then compiles it, opens the outputs and runs.
int RunTest(const TestArgs& args) {
  if (!CheckSceneRange(args.range)) return kExitUsage;
  InterruptWatch interrupt;
  const auto factory = ChooseController(args.controller, interrupt.flag());
  if (!factory) return kExitUsage;
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  std::unique_ptr<output::LineWriter> records;
  if (!OpenEpisodeOutputs(args.output, args.save_failures_dir, &records)) return kExitScenarioError;
  return RunAndReport(*program, *factory, args, records.get(), interrupt);
}

}  // namespace

CommandRunner ConfigureTestCommand(CLI::App& command) {
  auto args = std::make_shared<TestArgs>();
  AddScenarioOptions(command, args->scenario);
  AddControllerOptions(command, args->controller);
  AddSceneRangeOptions(command, args->range, 0);
  command.add_option("-o,--output", args->output, "write one JSON record per episode to OUT")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  command
      .add_option("--save-failures", args->save_failures_dir,
                  "write each failing scene to DIR/seed-S-index-I.json")
      ->type_name("DIR")
      ->check(NonEmptyPath());
  AddSamplingOptions(command, args->sampling);
  AddDesignOption(command, args->design);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  return [args] { return RunTest(*args); };
}

}  // namespace prs::cli
