// `prs check`: compiles a scenario, prints its errors (exit 1) or an outline on stdout: the
// creation sites with their position regions (static), the properties that varied over N
// sampled scenes (empirical; -n 0 skips it), and the classes.
#include <iostream>
#include <memory>

#include "cli/check_report.h"
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/interrupt.h"
#include "sampling/batch.h"

namespace prs::cli {
namespace {

struct CheckArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  int64_t count = 20;  // scenes sampled to see which properties vary
};

VariationObserver ObserveScenes(const lang::CompiledProgram& program, const CheckArgs& args,
                                const std::atomic<bool>& cancel) {
  sampling::BatchOptions options = MakeBatchOptions(args.sampling, args.count, cancel);
  VariationObserver observer;
  sampling::SampleBatch(program, options,
                        {.prepare = {}, .consume = [&](sampling::BatchScene&& scene) {
                           observer.Observe(scene.sampled.scene);
                         }});
  return observer;
}

// Prints the observed variation; a run-time error or a sampling failure is reported as by
// `prs sample` (exit 1 or 3), since a scenario that cannot be sampled is not ok.
int PrintObservedVariation(const lang::CompiledProgram& program, const CheckArgs& args,
                           const ScenarioOutline& outline) {
  if (args.count == 0) {
    std::cout << "\nrandom properties: not observed (-n 0)\n";
    return kExitSuccess;
  }
  InterruptWatch interrupt;
  try {
    const VariationObserver observed = ObserveScenes(program, args, interrupt.flag());
    std::cout << FormatRandomSection(outline, observed, args.sampling.seed, program.sources);
    return kExitSuccess;
  } catch (const lang::ScenarioError& error) {
    std::cout << "\nrandom properties: not observed, sampling failed (the error is on stderr)\n";
    std::cout.flush();
    return ReportScenarioError(error, program.sources);
  } catch (const sampling::BatchCancelled&) {
    PrintNote("interrupted");
    return kExitInterruptedBase + interrupt.signal_number();
  }
}

int RunCheck(const CheckArgs& args) {
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  const ScenarioOutline outline = OutlineScenario(*program);
  std::cout << FormatCheckHeader(args.scenario.file, *program, outline)
            << FormatObjectsSection(outline, program->sources);
  const int code = PrintObservedVariation(*program, args, outline);
  std::cout << FormatClassesSection(outline, program->sources);
  return code;
}

}  // namespace

CommandRunner ConfigureCheckCommand(CLI::App& command) {
  auto args = std::make_shared<CheckArgs>();
  AddScenarioOptions(command, args->scenario);
  command
      .add_option("-n,--count", args->count,
                  "scenes sampled to find which properties are random (0: none)")
      ->type_name("N")
      ->check(IntegerAtLeast(0))
      ->capture_default_str();
  AddSamplingOptions(command, args->sampling);
  return [args] { return RunCheck(*args); };
}

}  // namespace prs::cli
