// `prs stats`: samples N scenes (discarding them) and reports the acceptance rate, the
// rejections by reason and by culprit, and the time per scene, as a table or as JSON.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/stats_report.h"
#include "sampling/batch.h"

namespace prs::cli {
namespace {

struct StatsArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  int64_t count = 1000;
  bool json = false;
};

SamplingStats MeasureSampling(const lang::CompiledProgram& program, const StatsArgs& args,
                              const std::atomic<bool>& cancel) {
  SamplingStats stats;
  stats.file = args.scenario.file;
  stats.seed = args.sampling.seed;
  stats.naive = args.sampling.naive;
  sampling::BatchOptions options = MakeBatchOptions(args.sampling, args.count, cancel);
  stats.threads = sampling::CountBatchThreads(options);
  ProgressBar progress(args.count, IsStderrTerminal());
  int64_t done = 0;
  const auto begin = std::chrono::steady_clock::now();
  sampling::BatchCallbacks callbacks{.prepare = {}, .consume = [&](sampling::BatchScene&& scene) {
                                       stats.max_attempts_per_scene = std::max(
                                           stats.max_attempts_per_scene, scene.sampled.attempts);
                                       progress.Update(++done);
                                     }};
  progress.Attach(options, callbacks);
  stats.summary = sampling::SampleBatch(program, options, callbacks);
  if (options.sample.gibbs) stats.gibbs = options.sample.gibbs->plan();
  if (options.sample.partial_rejection) {
    stats.partial_rejection = options.sample.partial_rejection->plan();
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return stats;
}

int RunStats(const StatsArgs& args) {
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  InterruptWatch interrupt;
  try {
    const SamplingStats stats = MeasureSampling(*program, args, interrupt.flag());
    std::cout << (args.json ? FormatStatsJson(stats, program->sources)
                            : FormatStatsTable(stats, program->sources));
    return kExitSuccess;
  } catch (const lang::ScenarioError& error) {
    return ReportScenarioError(error, program->sources);
  } catch (const sampling::BatchCancelled&) {
    PrintNote("interrupted");
    return kExitInterruptedBase + interrupt.signal_number();
  }
}

}  // namespace

CommandRunner ConfigureStatsCommand(CLI::App& command) {
  auto args = std::make_shared<StatsArgs>();
  AddScenarioOptions(command, args->scenario);
  command.add_option("-n,--count", args->count, "number of scenes to sample")
      ->type_name("N")
      ->check(IntegerAtLeast(0))
      ->capture_default_str();
  AddSamplingOptions(command, args->sampling);
  command.add_flag("--json", args->json, "print the report as JSON (format prs-stats/1)");
  return [args] { return RunStats(*args); };
}

}  // namespace prs::cli
