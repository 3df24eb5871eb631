// `prs check`: compiles a scenario and samples N trial scenes, then prints its errors (exit 1,
// or 3 for a sampling failure) and an outline on stdout: the creation sites with their position
// regions (static), the properties that varied over the N scenes (-n 0 skips them), the classes.
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <optional>

#include "cli/check_report.h"
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/interrupt.h"
#include "cli/search_report.h"
#include "sampling/batch.h"

namespace prs::cli {
namespace {

struct CheckArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  int64_t count = 20;  // scenes sampled to see which properties vary
  bool coordinates = false;
};

// `prs check --coordinates`: only the list of scene coordinates.
int ListCoordinates(const lang::CompiledProgram& program, const CheckArgs& args) {
  try {
    const std::vector<lang::CoordinateInfo> coordinates =
        sampling::DescribeCoordinates(program, MakeSampleOptions(args.sampling));
    if (coordinates.empty()) {
      std::cout << args.scenario.file << ": no scene coordinates (nothing is drawn at random)\n";
      return kExitSuccess;
    }
    std::cout << args.scenario.file << ": " << FormatCount(coordinates.size(), "scene coordinate")
              << " (docs/search.md)\n"
              << FormatCoordinateTable(coordinates, program.sources) << std::flush;
    return kExitSuccess;
  } catch (const lang::ScenarioError& error) {
    return ReportScenarioError(error, program.sources);
  }
}

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

// What the trial sampling found: the variation, or the error that stopped it.
struct Observation {
  std::optional<VariationObserver> observed;
  std::optional<lang::ScenarioError> error;
  int interrupted_by = 0;  // a signal number
};

Observation Observe(const lang::CompiledProgram& program, const CheckArgs& args) {
  Observation o;
  if (args.count == 0) return o;
  InterruptWatch interrupt;
  try {
    o.observed = ObserveScenes(program, args, interrupt.flag());
  } catch (const lang::ScenarioError& error) {
    o.error = error;
  } catch (const sampling::BatchCancelled&) {
    o.interrupted_by = interrupt.signal_number();
  }
  return o;
}

// The first line says one thing: "ok" only when the program compiled and its trial scenes
// sampled; "compiles" when sampling was skipped (-n 0) or failed (the error goes to stderr,
// reported as by `prs sample`: exit 1 or 3).
std::string Verdict(const CheckArgs& args, const Observation& o) {
  if (o.observed) return fmt::format("ok, {} sampled", FormatCount(args.count, "scene"));
  if (args.count == 0) return "compiles (not sampled: -n 0)";
  if (o.error) return "compiles, but sampling fails (the error is on stderr)";
  return "compiles (sampling interrupted)";
}

int RunCheck(const CheckArgs& args) {
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  if (args.coordinates) return ListCoordinates(*program, args);
  const ScenarioOutline outline = OutlineScenario(*program);
  const Observation o = Observe(*program, args);
  std::cout << FormatCheckHeader(args.scenario.file, Verdict(args, o), *program, outline)
            << FormatObjectsSection(outline, program->sources);
  if (o.observed) {
    std::cout << FormatRandomSection(outline, *o.observed, args.sampling.seed, program->sources);
  } else {
    std::cout << "\nrandom properties: not observed\n";
  }
  std::cout << FormatClassesSection(outline, program->sources);
  std::cout.flush();
  if (o.error) return ReportScenarioError(*o.error, program->sources);
  if (o.interrupted_by) {
    PrintNote("interrupted");
    return kExitInterruptedBase + o.interrupted_by;
  }
  return kExitSuccess;
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
  command.add_flag("--coordinates", args->coordinates,
                   "list the scene coordinates (what each random draw decides; docs/search.md)");
  return [args] { return RunCheck(*args); };
}

}  // namespace prs::cli
