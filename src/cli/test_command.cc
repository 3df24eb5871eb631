// `prs test`: runs a robot controller (a built-in one, or the user's own program with --exec)
// in sampled scenes, or in saved ones (a scenes file or directory, or --replay RECORDS), prints
// the outcome table (the paper's Table III) on stdout, one JSON record per episode to -o, and
// saves the failing scenes with --save-failures (docs/harness.md).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/controller_options.h"
#include "cli/design_option.h"
#include "cli/failure_pictures.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/test_replay.h"
#include "harness/harness.h"
#include "output/line_writer.h"
#include "search/like.h"

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
  std::string replay;        // --replay RECORDS.jsonl: the scenes of an earlier run
  bool failed_only = false;  // --failed: only its failures
  bool quiet = false;
  const CLI::Option* count_option = nullptr;  // given: -n selects among saved scenes too
  const CLI::Option* seed_option = nullptr;   // given: refused where scenes carry their seeds
};

// Runs the episodes with `options` (sampled, or replayed) and returns their summary.
using EpisodeRun = std::function<harness::RunSummary(harness::RunOptions& options)>;

harness::RunOptions MakeRunOptions(const TestArgs& args, const std::atomic<bool>& cancel) {
  harness::RunOptions options;
  options.sample = MakeSampleOptions(args.sampling);
  options.seed = args.sampling.seed;
  options.start = args.range.start;
  options.count = args.range.count;
  options.threads = args.sampling.threads;
  options.scenario_args = MakeScenarioWords(args.scenario, args.sampling);
  std::vector<std::string> scene_words = options.scenario_args;
  if (args.design.name != DesignArgs{}.name) {
    scene_words.insert(scene_words.end(), {"--design", args.design.name});
  }
  options.scene_options = harness::SceneOptionsOf(scene_words);
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

// Runs `count` episodes with `run`, writing each record as it arrives; returns the exit code.
// `program` (null for scenes that only files hold) locates run-time errors.
int RunAndReport(const lang::CompiledProgram* program, int64_t count, const EpisodeRun& run,
                 harness::RunOptions options, const TestArgs& args, output::LineWriter* records,
                 InterruptWatch& interrupt) {
  ProgressBar progress(count, !args.quiet && IsStderrTerminal());
  int64_t done = 0;
  options.on_record = [&](const harness::EpisodeRecord& record) {
    if (records) records->AddLine(harness::FormatRecordJson(record));
    progress.Update(++done);
  };
  options.on_warning = WarnOnce([&] { progress.Erase(); });
  const auto begin = std::chrono::steady_clock::now();
  try {
    const harness::RunSummary summary = run(options);
    if (records) records->Commit();
    progress.Erase();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::cout << FormatOutcomeTable(summary.records) << std::flush;
    if (!args.quiet) {
      PrintNote(FormatTestSummary(summary, seconds));
      const std::string gibbs =
          DescribeGibbs(options.sample, static_cast<int64_t>(summary.records.size()));
      if (!gibbs.empty()) PrintNote(gibbs);
    }
    if (IsEveryOutcome(summary.records, "exit-127")) {
      PrintNote("every episode exited with code 127: the shell did not find the --exec command");
    }
    return args.save_failures_dir.empty()
               ? kExitSuccess
               : ReportSavedFailures(summary.records, args.save_failures_dir, args.quiet);
  } catch (const lang::ScenarioError& error) {
    progress.Erase();
    if (!program) throw;
    return ReportScenarioError(error, program->sources);
  } catch (const harness::ControllerStartError& error) {
    progress.Erase();
    PrintError(error.what());
    if (records) PrintNote(DescribeRecordsSoFar(*records));
    return kExitScenarioError;
  } catch (const sampling::BatchCancelled&) {
    progress.Erase();
    PrintNote(fmt::format("interrupted after {} (resume with --start {} -n {})",
                          FormatCount(done, "episode"), args.range.start + uint64_t(done),
                          count - done));
    return kExitInterruptedBase + interrupt.signal_number();
  } catch (const std::exception& error) {  // records or failing scenes cannot be written
    progress.Erase();
    PrintError(error.what());
    return kExitScenarioError;
  }
}

// Items [--start, --start + -n) of `total` saved scenes, all from --start without -n; nullopt
// after a usage error when --start is past the last one or -n asks for more than are left.
std::optional<std::pair<int64_t, int64_t>> SelectSaved(const TestArgs& args, int64_t total,
                                                       const std::string& what) {
  if (args.range.start >= uint64_t(total)) {
    PrintError(fmt::format("--start {}: {} holds {}, numbered from 0", args.range.start, what,
                           FormatCount(total, "scene")));
    return std::nullopt;
  }
  const int64_t first = int64_t(args.range.start);
  const bool counted = args.count_option && args.count_option->count() > 0;
  if (counted && args.range.count > total - first) {
    const int64_t left = total - first;
    PrintError(fmt::format(
        "-n {} --start {}: {} holds {}, so only {} {} left from --start {}; give -n {} or leave "
        "out -n",
        args.range.count, args.range.start, what, FormatCount(total, "scene"), left,
        left == 1 ? "is" : "are", args.range.start, left));
    return std::nullopt;
  }
  return std::pair{first, counted ? args.range.count : total - first};
}

// `prs test SCENES.jsonl` / `prs test DIR`: the saved scenes as they are.
int RunSavedScenes(const TestArgs& args, const harness::ControllerFactory& factory,
                   InterruptWatch& interrupt) {
  const bool scene_options = !args.replay.empty() || args.design.name != DesignArgs{}.name ||
                             !args.sampling.settle_s.empty() || !args.sampling.stable_s.empty() ||
                             args.sampling.naive;
  if (scene_options) {
    PrintError(args.scenario.file +
               " holds scenes, which run as they are: --replay, --design, "
               "--naive, --stable and --settle need the .prs program");
    return kExitUsage;
  }
  if (args.seed_option->count() > 0) {
    PrintError("-s: the scenes of " + args.scenario.file +
               " carry their own seeds and run as they are; leave out -s");
    return kExitUsage;
  }
  const auto lines = ReadSavedScenes(args.scenario.file);
  if (!lines) return kExitScenarioError;
  const auto range = SelectSaved(args, int64_t(lines->size()), args.scenario.file);
  if (!range) return kExitUsage;
  const auto [first, count] = *range;
  const std::vector<SavedSceneLine> chosen(lines->begin() + first, lines->begin() + first + count);
  std::unique_ptr<output::LineWriter> records;
  if (!OpenEpisodeOutputs(args.output, args.save_failures_dir, &records)) return kExitScenarioError;
  harness::RunOptions options = MakeRunOptions(args, interrupt.flag());
  options.scenario_args.clear();  // no program: no command rewrites these scenes
  const harness::ReplaySourceFactory sources = MakeSavedSceneSources(chosen);
  return RunAndReport(
      nullptr, count,
      [&](harness::RunOptions& run) {
        return harness::ReplayEpisodes(count, sources, factory, run);
      },
      options, args, records.get(), interrupt);
}

// `prs test FILE.prs --replay RECORDS.jsonl`: the records' scenes, regenerated and checked.
int RunReplayedRecords(const lang::CompiledProgram& program, const TestArgs& args,
                       const harness::ControllerFactory& factory, output::LineWriter* records,
                       InterruptWatch& interrupt) {
  if (args.design.name != DesignArgs{}.name) {
    PrintError("--replay: the records carry their scenes' coordinates; leave out --design");
    return kExitUsage;
  }
  if (args.seed_option->count() > 0) {
    PrintError("--replay: the records carry their scenes' seeds; leave out -s");
    return kExitUsage;
  }
  if (!CheckSamplerTakesPoints(args.sampling, "--replay",
                               "leave out --sampler: a record's scene is made again at its "
                               "point, whichever sampler chose it")) {
    return kExitUsage;
  }
  harness::RunOptions options = MakeRunOptions(args, interrupt.flag());
  options.spec_hash = search::CalcSpecHash(program);
  const auto replayed =
      ReadRecordsToReplay(args.replay, program, options.scene_options, args.failed_only);
  if (!replayed) return kExitScenarioError;
  const auto range = SelectSaved(args, int64_t(replayed->size()), args.replay);
  if (!range) return kExitUsage;
  const auto [first, count] = *range;
  const std::vector<search::ReportRecord> chosen(replayed->begin() + first,
                                                 replayed->begin() + first + count);
  // A scene drawn at coordinates is not scene (seed, index) of the stream.
  const bool at_coordinates = std::any_of(chosen.begin(), chosen.end(),
                                          [](const auto& r) { return !r.coordinates.empty(); });
  if (at_coordinates) options.scenario_args.clear();
  // Each replayed record keeps its original's law: its search tag (an importance sample's
  // weight) and that it is a replay, of every record or of the failures alone (chosen by
  // outcome; a range of --start and -n is chosen by position and keeps the law).
  const harness::ReplaySourceFactory sources =
      MakeRegeneratedSources(program, options.sample, chosen, args.replay, args.failed_only);
  return RunAndReport(
      &program, count,
      [&](harness::RunOptions& run) {
        return harness::ReplayEpisodes(count, sources, factory, run);
      },
      options, args, records, interrupt);
}

// Checks that need no scenario, then compiles it, opens the outputs and runs.
int RunTest(const TestArgs& args) {
  if (!CheckSceneRange(args.range)) return kExitUsage;
  InterruptWatch interrupt;
  const auto factory = ChooseController(args.controller, interrupt.flag());
  if (!factory) return kExitUsage;
  if (IsScenesFile(args.scenario.file) || std::filesystem::is_directory(args.scenario.file)) {
    return RunSavedScenes(args, *factory, interrupt);
  }
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  std::unique_ptr<output::LineWriter> records;
  if (!OpenEpisodeOutputs(args.output, args.save_failures_dir, &records)) return kExitScenarioError;
  if (!args.replay.empty()) {
    return RunReplayedRecords(*program, args, *factory, records.get(), interrupt);
  }
  harness::RunOptions options = MakeRunOptions(args, interrupt.flag());
  std::unique_ptr<search::Design> design;
  if (!PrepareDesign(args.design, *program, args.range, options.sample, &design)) return kExitUsage;
  options.spec_hash = search::CalcSpecHash(*program);
  return RunAndReport(
      program.get(), args.range.count,
      [&](harness::RunOptions& run) { return harness::RunEpisodes(*program, *factory, run); },
      options, args, records.get(), interrupt);
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
  command
      .add_option("--replay", args->replay,
                  "run the scenes of an earlier run's records again (prs test -o, prs search -o), "
                  "regenerated from FILE and checked against what they recorded")
      ->type_name("RECORDS")
      ->check(NonEmptyPath());
  command.add_flag("--failed", args->failed_only, "with --replay: only the records that failed")
      ->needs("--replay");
  AddSamplingOptions(command, args->sampling);
  AddDesignOption(command, args->design);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  args->count_option = command.get_option("-n");
  args->seed_option = command.get_option("-s");
  command.get_option("FILE")->description(
      "the .prs scenario; or saved scenes to run as they are: a scenes file (.jsonl, from prs "
      "sample or --save-failures) or a directory of them");
  return [args] { return RunTest(*args); };
}

}  // namespace prs::cli
