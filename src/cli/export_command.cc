// `prs export`: scenes of a scenario (or of a scenes .jsonl file) as files for simulators and
// viewers, one per scene: MJCF, URDF, SDF, USD text or glTF (docs/export.md). Sampling runs on
// worker threads as in `prs sample`; files are written in index order.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <set>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/export_output.h"
#include "cli/interrupt.h"
#include "export/export.h"
#include "sampling/batch.h"

namespace prs::cli {
namespace {

namespace fs = std::filesystem;

struct ExportArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  std::string format;  // empty: from -o's extension
  SceneRangeArgs range;
  std::string output;  // a file (one scene), a directory, or empty for stdout
  bool quiet = false;
};

// Warnings from worker threads, each printed once at the end.
class WarningSet {
 public:
  void Add(const std::vector<std::string>& warnings) {
    std::lock_guard lock(mutex_);
    warnings_.insert(warnings.begin(), warnings.end());
  }
  void Print() const {
    for (const std::string& warning : warnings_) std::cerr << "prs: warning: " << warning << "\n";
  }

 private:
  std::mutex mutex_;
  std::set<std::string> warnings_;
};

int ReportWritten(const ExportArgs& args, const ExportTarget& target, int64_t files,
                  const WarningSet& warnings) {
  warnings.Print();
  if (!args.quiet && !target.to_stdout()) {
    PrintNote(fmt::format("wrote {} to {}", FormatCount(files, "file"), target.Describe()));
  }
  return kExitSuccess;
}

int ExportSampledScenes(const ExportArgs& args, exporting::Format format,
                        const ExportTarget& target) {
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  InterruptWatch interrupt;
  sampling::BatchOptions options =
      MakeBatchOptions(args.sampling, args.range.count, interrupt.flag());
  options.start = args.range.start;
  WarningSet warnings;
  int64_t written = 0;
  sampling::BatchCallbacks callbacks;
  callbacks.prepare = [&](sampling::BatchScene& scene) {
    exporting::ExportScene exported = exporting::MakeExportScene(
        scene.sampled.scene,
        fmt::format("seed {} index {}", scene.sampled.seed, scene.sampled.index));
    warnings.Add(exported.warnings);
    scene.rendered = exporting::WriteScene(exported, format);
    scene.sampled.scene = {};
  };
  callbacks.consume = [&](sampling::BatchScene&& scene) {
    target.Write(scene.sampled.seed, scene.sampled.index, scene.rendered);
    ++written;
  };
  try {
    sampling::SampleBatch(*program, options, callbacks);
  } catch (const lang::ScenarioError& error) {
    return ReportScenarioError(error, program->sources);
  } catch (const sampling::BatchCancelled&) {
    PrintNote(fmt::format("interrupted; {} written", FormatCount(written, "file")));
    return kExitInterruptedBase + interrupt.signal_number();
  } catch (const std::exception& error) {  // cannot write a file
    PrintError(error.what());
    return kExitScenarioError;
  }
  return ReportWritten(args, target, written, warnings);
}

int ExportScenesFile(const ExportArgs& args, exporting::Format format,
                     const std::vector<std::string>& lines, const ExportTarget& target) {
  WarningSet warnings;
  int64_t written = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (IsBlankLine(lines[i])) continue;
    try {
      const exporting::ExportScene scene = exporting::ReadSceneJson(lines[i]);
      warnings.Add(scene.warnings);
      target.Write(scene.seed, scene.index, exporting::WriteScene(scene, format));
      ++written;
    } catch (const std::invalid_argument& error) {
      PrintError(fmt::format("{}:{}: {}", args.scenario.file, i + 1, error.what()));
      return kExitScenarioError;
    } catch (const std::exception& error) {  // cannot write a file
      PrintError(error.what());
      return kExitScenarioError;
    }
  }
  return ReportWritten(args, target, written, warnings);
}

int RunExport(const ExportArgs& args) {
  if (!CheckSceneRange(args.range)) return kExitUsage;
  const auto format = ChooseFormat(args.format, args.output);
  if (!format) return kExitUsage;
  if (!IsScenesFile(args.scenario.file)) {
    const auto target = PlanExportTarget(args.output, *format, args.range.count,
                                         fs::path(args.scenario.file).stem().string());
    if (!target) return kExitUsage;
    return ExportSampledScenes(args, *format, *target);
  }
  const auto lines = ReadLines(args.scenario.file);
  if (!lines) return kExitScenarioError;
  const int64_t scenes = CountNonBlank(*lines);
  if (scenes == 0) {
    PrintNoScenes(args.scenario.file);
    return kExitScenarioError;
  }
  const auto target = PlanExportTarget(args.output, *format, scenes,
                                       fs::path(args.scenario.file).stem().string());
  if (!target) return kExitUsage;
  return ExportScenesFile(args, *format, *lines, *target);
}

}  // namespace

CommandRunner ConfigureExportCommand(CLI::App& command) {
  auto args = std::make_shared<ExportArgs>();
  AddScenarioOptions(command, args->scenario);
  command.footer(
      "FILE may also be a scenes file (.jsonl, from `prs sample`): then every scene in it is "
      "exported, and -n, --start and the sampling options do not apply.\nSee docs/export.md.");
  command
      .add_option("--format", args->format,
                  "mjcf, urdf, sdf, usda, gltf or glb (default: from -o's extension)")
      ->type_name("FORMAT")
      ->check(FormatNameValidator());
  AddSceneRangeOptions(command, args->range, 1);
  command
      .add_option("-o,--output", args->output,
                  "OUT.ext for one scene, or a directory for one file per scene (default: stdout "
                  "for one scene)")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  AddSamplingOptions(command, args->sampling);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  return [args] { return RunExport(*args); };
}

}  // namespace prs::cli
