// `prs search`: looks for scenes where a controller fails (docs/search.md). Runs the controller
// in generations of episodes at points of the scene coordinates chosen by a strategy (ce,
// anneal, or random as the baseline), writes one record per episode to -o as each generation
// finishes, and prints the outcome table, the failures per generation and a verdict.
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/controller_options.h"
#include "cli/failure_pictures.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/search_report.h"
#include "output/line_writer.h"
#include "search/search.h"

namespace prs::cli {
namespace {

struct SearchArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  ControllerArgs controller;
  std::string strategy = "ce";
  int64_t budget = 0;
  int64_t batch = 0;
  std::string output;
  std::string save_failures_dir;
  bool quiet = false;
};

search::SearchOptions MakeSearchOptions(const SearchArgs& args, const std::atomic<bool>& cancel) {
  search::SearchOptions options;
  search::ParseStrategy(args.strategy, &options.strategy);
  options.budget = args.budget;
  options.batch = args.batch;
  options.run.sample = MakeSampleOptions(args.sampling);
  options.run.seed = args.sampling.seed;
  options.run.scene_options =
      harness::SceneOptionsOf(MakeScenarioWords(args.scenario, args.sampling));
  options.run.threads = args.sampling.threads;
  // No regenerate command: a searched scene comes from a proposed point, not from (seed,
  // index); its record carries the point (coordinates) instead.
  options.run.save_failures_dir = args.save_failures_dir;
  options.run.cancel = &cancel;
  return options;
}

int RunAndReport(const lang::CompiledProgram& program, const harness::ControllerFactory& factory,
                 const SearchArgs& args, output::LineWriter* records, InterruptWatch& interrupt) {
  search::SearchOptions options = MakeSearchOptions(args, interrupt.flag());
  ProgressBar progress(args.budget, !args.quiet && IsStderrTerminal());
  int64_t done = 0;
  options.on_record = [&](const harness::EpisodeRecord& record) {
    if (records) records->AddLine(harness::FormatRecordJson(record));
    progress.Update(++done);
  };
  options.run.on_warning = WarnOnce([&] { progress.Erase(); });
  try {
    const search::SearchSummary summary = search::RunSearch(program, factory, options);
    if (records) records->Commit();
    progress.Erase();
    std::cout << FormatOutcomeTable(summary.records) << '\n'
              << FormatGenerationTable(summary) << std::flush;
    if (!args.quiet) {
      PrintNote(FormatSearchVerdict(summary, options.strategy) +
                fmt::format("; {} generations of {} on {}", summary.generations, summary.batch,
                            FormatCount(summary.threads, "thread")));
      const std::string batch_note = FormatBatchUseNote(summary.batch, summary.threads);
      if (!batch_note.empty()) PrintNote(batch_note);
    }
    return args.save_failures_dir.empty()
               ? kExitSuccess
               : ReportSavedFailures(summary.records, args.save_failures_dir, args.quiet);
  } catch (const search::NothingToSearch& error) {
    progress.Erase();
    PrintError(std::string(error.what()) + " (prs check --coordinates lists what is random)");
    return kExitUsage;
  } catch (const lang::ScenarioError& error) {
    progress.Erase();
    if (records) records->Flush();
    return ReportScenarioError(error, program.sources);
  } catch (const sampling::BatchCancelled&) {
    progress.Erase();
    if (records) records->Flush();
    PrintNote(fmt::format(
        "interrupted after {}; the records of every finished generation are "
        "in {}",
        FormatCount(done, "episode"), records ? records->partial_path() : std::string("(no -o)")));
    return kExitInterruptedBase + interrupt.signal_number();
  } catch (const std::exception& error) {
    progress.Erase();
    PrintError(error.what());
    return kExitScenarioError;
  }
}

int RunSearchCommand(const SearchArgs& args) {
  if (!CheckSamplerTakesPoints(args.sampling, "prs search",
                               "leave out --sampler (the default, rejection, is exact for any "
                               "program)")) {
    return kExitUsage;
  }
  InterruptWatch interrupt;
  const auto factory = ChooseController(args.controller, interrupt.flag());
  if (!factory) return kExitUsage;
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  std::unique_ptr<output::LineWriter> records;
  if (!OpenEpisodeOutputs(args.output, args.save_failures_dir, &records)) return kExitScenarioError;
  return RunAndReport(*program, *factory, args, records.get(), interrupt);
}

CLI::Validator StrategyName() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        search::Strategy strategy;
        if (search::ParseStrategy(text, &strategy)) return "";
        if (text == "bo") {
          return "Bayesian optimisation runs in the Python package, on scikit-learn: "
                 "probrobscene.search(scenario, controller, budget, strategy=\"bo\") "
                 "(docs/search.md); prs search has ce, anneal and random";
        }
        const std::string suggestion = lang::SuggestClosest(text, search::StrategyNames());
        return "unknown strategy '" + text + "'" +
               (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?") +
               " (strategies: ce, anneal, random)";
      },
      "");
}

}  // namespace

CommandRunner ConfigureSearchCommand(CLI::App& command) {
  auto args = std::make_shared<SearchArgs>();
  AddScenarioOptions(command, args->scenario);
  AddControllerOptions(command, args->controller);
  command
      .add_option("--strategy", args->strategy,
                  "ce (cross-entropy), anneal (simulated annealing) or random (i.i.d., the "
                  "baseline)")
      ->type_name("NAME")
      ->check(StrategyName())
      ->capture_default_str();
  command.add_option("--budget", args->budget, "episodes in all")
      ->type_name("N")
      ->required()
      ->check(IntegerAtLeast(1));
  command
      .add_option("--batch", args->batch,
                  "episodes per generation (default: budget/50 within 20..200)")
      ->type_name("B")
      ->check(IntegerAtLeast(1));
  command
      .add_option("-o,--output", args->output,
                  "write one JSON record per episode to OUT (as `prs test -o`, with the scene "
                  "coordinates, score and generation)")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  command
      .add_option("--save-failures", args->save_failures_dir,
                  "write each failing scene to DIR/seed-S-index-I.json")
      ->type_name("DIR")
      ->check(NonEmptyPath());
  AddSamplingOptions(command, args->sampling);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  return [args] { return RunSearchCommand(*args); };
}

}  // namespace prs::cli
