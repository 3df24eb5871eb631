// `prs estimate`: how often a controller fails under the program's own law, with 95 %
// intervals (docs/search.md, "How often does it fail"). Adapts a proposal toward failures,
// samples from it with importance weights, and prints one row per failure outcome; --from
// makes the estimate again from a record file alone.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/controller_options.h"
#include "cli/estimate_report.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "output/line_writer.h"
#include "search/estimate.h"
#include "search/like.h"
#include "search/search.h"

namespace prs::cli {
namespace {

struct EstimateArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  ControllerArgs controller;
  int64_t budget = 0;
  std::string output;
  std::string from;  // --from RESULTS.jsonl
  bool json = false;
  bool quiet = false;
  std::vector<std::pair<std::string, const CLI::Option*>> run_options;  // refused with --from
};

// --from reads records and runs nothing: the options of a run would be ignored, so they are
// refused. Returns the first one given, or "".
std::string FindRunOption(const EstimateArgs& args) {
  for (const auto& [name, option] : args.run_options) {
    if (option->count() > 0) return name;
  }
  return "";
}

int EstimateFromRecords(const EstimateArgs& args) {
  if (const std::string option = FindRunOption(args); !option.empty()) {
    PrintError(fmt::format(
        "{}: --from makes the estimate from the records alone and runs nothing; leave out {} "
        "(the records keep the seed, options and controller of the run that wrote them)",
        option, option));
    return kExitUsage;
  }
  std::string spec;
  if (!args.scenario.file.empty()) {
    auto program = CompileScenario(args.scenario);
    if (!program) return kExitScenarioError;
    spec = search::CalcSpecHash(*program);
  }
  const auto lines = ReadLines(args.from);
  if (!lines) return kExitScenarioError;
  try {
    const search::WeightedRecords records = search::ReadWeightedRecords(*lines, args.from, spec);
    const search::Estimate e = search::CalcEstimate(records.records, records.outcomes_seen);
    if (!args.quiet) {
      PrintNote(e.iid ? fmt::format("{} in {}, drawn independently from the program's law",
                                    FormatCount(e.episodes, "i.i.d. episode"), args.from)
                      : fmt::format("{} in {}; effective sample size {:.0f}",
                                    FormatCount(e.episodes, "weighted episode"), args.from, e.ess));
    }
    return PrintEstimate(e, args.json, args.quiet);
  } catch (const std::exception& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
}

int RunEstimateCommand(const EstimateArgs& args) {
  if (!args.from.empty()) return EstimateFromRecords(args);
  if (!CheckSamplerTakesPoints(args.sampling, "prs estimate",
                               "leave out --sampler (the default, rejection, is exact for any "
                               "program, which the estimate's weights need)")) {
    return kExitUsage;
  }
  if (args.scenario.file.empty() || args.budget == 0) {
    PrintError("give the .prs scenario, a controller and --budget N (or --from RESULTS.jsonl)");
    return kExitUsage;
  }
  InterruptWatch interrupt;
  const auto factory = ChooseController(args.controller, interrupt.flag());
  if (!factory) return kExitUsage;
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  std::unique_ptr<output::LineWriter> records;
  if (!OpenEpisodeOutputs(args.output, "", &records)) return kExitScenarioError;
  search::EstimateOptions options;
  options.budget = args.budget;
  options.run.sample = MakeSampleOptions(args.sampling);
  options.run.seed = args.sampling.seed;
  options.run.threads = args.sampling.threads;
  options.run.cancel = &interrupt.flag();
  options.run.spec_hash = search::CalcSpecHash(*program);
  options.run.scene_options =
      harness::SceneOptionsOf(MakeScenarioWords(args.scenario, args.sampling));
  ProgressBar progress(args.budget, !args.quiet && IsStderrTerminal());
  int64_t done = 0;
  options.on_record = [&](const harness::EpisodeRecord& record) {
    if (records) records->AddLine(harness::FormatRecordJson(record));
    progress.Update(++done);
  };
  options.run.on_warning = WarnOnce([&] { progress.Erase(); });
  try {
    const search::EstimateSummary summary = search::RunEstimate(*program, *factory, options);
    if (records) records->Commit();
    progress.Erase();
    if (!args.quiet) {
      PrintNote(fmt::format(
          "{}: {} adapting the proposal, {} weighted (effective sample size {:.0f}) on {}",
          FormatCount(args.budget, "episode"), summary.adapt_episodes, summary.estimate.episodes,
          summary.estimate.ess, FormatCount(summary.threads, "thread")));
      if (!summary.scored) {
        PrintNote(
            "the controller reports no score: the adaptation only tells failures from "
            "successes, and finds rare failures more slowly (docs/harness.md, \"score\")");
      }
    }
    return PrintEstimate(summary.estimate, args.json, args.quiet);
  } catch (const std::invalid_argument& error) {  // a budget too small
    progress.Erase();
    PrintError(error.what());
    return kExitUsage;
  } catch (const search::NothingToSearch& error) {
    progress.Erase();
    PrintError(std::string(error.what()) +
               ": every scene is the same, so it fails always or "
               "never (prs check --coordinates lists what is random)");
    return kExitUsage;
  } catch (const lang::ScenarioError& error) {
    progress.Erase();
    return ReportScenarioError(error, program->sources);
  } catch (const sampling::BatchCancelled&) {
    progress.Erase();
    PrintNote(fmt::format("interrupted after {}; no estimate (run it again){}",
                          FormatCount(done, "episode"),
                          records ? "; " + DescribeRecordsSoFar(*records) : std::string()));
    return kExitInterruptedBase + interrupt.signal_number();
  } catch (const std::exception& error) {  // a controller that cannot start, records unwritable
    progress.Erase();
    PrintError(error.what());
    return kExitScenarioError;
  }
}

}  // namespace

CommandRunner ConfigureEstimateCommand(CLI::App& command) {
  auto args = std::make_shared<EstimateArgs>();
  AddScenarioOptions(command, args->scenario);
  command.get_option("FILE")->required(false)->description(
      "the .prs scenario (with --from: optional, then the records' program is checked)");
  AddControllerOptions(command, args->controller);
  command.add_option("--budget", args->budget, "episodes in all")
      ->type_name("N")
      ->check(IntegerAtLeast(search::kMinEstimateBudget));
  command
      .add_option("-o,--output", args->output,
                  "write one JSON record per episode to OUT (the sampling phase's with their "
                  "weights), from which --from makes the estimate again")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  command
      .add_option("--from", args->from,
                  "the estimate of a record file (prs estimate -o, or prs test -o for i.i.d. "
                  "episodes) without running anything")
      ->type_name("RESULTS")
      ->check(NonEmptyPath());
  command.add_flag("--json", args->json, "print one JSON object instead of the table");
  AddSamplingOptions(command, args->sampling);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  for (const char* name : {"--controller", "--exec", "--budget", "-s", "-o", "--threads",
                           "--settle", "--stable", "--sampler", "--naive"}) {
    if (const CLI::Option* option = command.get_option_no_throw(name)) {
      args->run_options.emplace_back(name, option);
    }
  }
  return [args] { return RunEstimateCommand(*args); };
}

}  // namespace prs::cli
