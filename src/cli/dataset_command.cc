// `prs dataset`: scenes seen through their cameras, with exact labels, as a BOP dataset and
// COCO annotations (src/dataset, docs/dataset.md). Scenes are sampled and rendered on worker
// threads and added in index order; the dataset is written to DIR.partial and renamed to DIR
// when complete.
#include <fmt/format.h>

#include <chrono>
#include <filesystem>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/dataset_options.h"
#include "cli/design_option.h"
#include "cli/interrupt.h"
#include "cli/like_option.h"
#include "cli/progress.h"
#include "dataset/dataset.h"
#include "output/scene_reader.h"
#include "render/scene_input.h"
#include "sampling/batch.h"

namespace prs::cli {
namespace {

struct DatasetArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  DesignArgs design;
  LikeArgs like;
  SceneRangeArgs range;
  std::string output;
  DatasetPictureArgs pictures;
  std::string classes;  // --classes PROGRAM.prs: a scenes file's ids as that program's
  bool append = false;  // --append: grow the dataset DIR
  bool quiet = false;
};

// The checks a usage error reports before anything is written; "" when all is well.
std::string CheckArgs(const DatasetArgs& args, dataset::DatasetOptions& options) {
  if (args.like.given() && IsScenesFile(args.scenario.file))
    return "--like and --near draw scenes from a program: give the .prs file, not a scenes file";
  if (!args.classes.empty() && !IsScenesFile(args.scenario.file))
    return "--classes is for a scenes file: a program's objects are numbered by its own classes";
  options.dir = args.output;
  if (args.append) {
    if (!std::filesystem::is_directory(args.output + "/train_pbr"))
      return "--append: " + args.output + " is not a dataset (no train_pbr/) to add images to";
    options.dir = args.output + ".append";  // joined to DIR when complete
  }
  return ReadDatasetPictureArgs(args.pictures, options);
}

class DatasetRun {
 public:
  explicit DatasetRun(const DatasetArgs& args)
      : args_(args), progress_(args.range.count, !args.quiet && IsStderrTerminal()) {}

  int Run() {
    const auto begin = std::chrono::steady_clock::now();
    dataset::DatasetOptions options;
    if (const std::string problem = CheckArgs(args_, options); !problem.empty()) {
      PrintError(problem);
      return kExitUsage;
    }
    int64_t images = 0;
    std::unique_ptr<dataset::DatasetWriter> writer;
    // Sampling's share is what the stages leave of the run (exact on one thread).
    try {
      const int code = IsScenesFile(args_.scenario.file) ? RunOnFile(options, writer, images)
                                                         : RunOnProgram(options, writer, images);
      if (code != kExitSuccess) return code;
    } catch (const sampling::BatchCancelled&) {
      progress_.Erase();
      PrintNote(fmt::format("interrupted; {} of the dataset are in {}",
                            FormatCount(writer->scenes_added(), "scene"), writer->partial_dir()));
      return kExitInterruptedBase + interrupt_.signal_number();
    } catch (const lang::ScenarioError& error) {
      progress_.Erase();
      const int code = ReportScenarioError(error, program_->sources);
      if (writer) PrintNote(DescribePartial(*writer));
      return code;
    } catch (const std::invalid_argument& error) {  // a camera, a label, a size
      progress_.Erase();
      PrintError(error.what());
      if (writer) PrintNote(DescribePartial(*writer));
      return kExitUsage;
    } catch (const std::exception& error) {  // DIR, a file, no OpenGL
      progress_.Erase();
      PrintError(error.what());
      if (writer) PrintNote(DescribePartial(*writer));
      return kExitScenarioError;
    }
    progress_.Erase();
    if (args_.append) {
      try {
        dataset::AppendDataset(args_.output, args_.output + ".append");
      } catch (const std::exception& error) {
        PrintError(error.what());
        return kExitScenarioError;
      }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    if (!args_.quiet) {
      PrintNote(fmt::format("{} of {} ({}) in {:.2f} s, {:.1f} images/s, to {}",
                            FormatCount(images, "labelled image"), FormatCount(done_, "scene"),
                            args_.pictures.format == "both"  ? "BOP and COCO"
                            : args_.pictures.format == "bop" ? "BOP"
                                                             : "COCO",
                            seconds, seconds > 0 ? double(images) / seconds : 0.0, args_.output));
      const dataset::StageSeconds stages = writer->stage_seconds();
      PrintNote(fmt::format(
          "time by stage (thread-seconds): rendering {:.2f}, labels {:.2f}, pictures {:.2f}, JSON "
          "and "
          "models {:.2f}; the rest (sampling, scene lines) {:.2f} s of the run",
          stages.render, stages.labels, stages.pictures, stages.json,
          std::max(0.0, seconds - (stages.render + stages.labels + stages.pictures + stages.json) /
                                      std::max(1, args_.sampling.threads))));
    }
    return kExitSuccess;
  }

 private:
  std::string DescribePartial(const dataset::DatasetWriter& writer) const {
    return fmt::format("the {} before it are in {}", FormatCount(writer.scenes_added(), "scene"),
                       writer.partial_dir());
  }

  int RunOnProgram(dataset::DatasetOptions& options,
                   std::unique_ptr<dataset::DatasetWriter>& writer, int64_t& images) {
    program_ = CompileScenario(args_.scenario);
    if (!program_) return kExitScenarioError;
    sampling::BatchOptions batch =
        MakeBatchOptions(args_.sampling, args_.range.count, interrupt_.flag());
    batch.start = args_.range.start;
    if (!PrepareDesign(args_.design, *program_, args_.range, batch.sample, &design_)) {
      return kExitUsage;
    }
    if (args_.like.given() &&
        !PrepareLike(args_.like, *program_, batch.sample, like_, args_.quiet)) {
      return kExitUsage;
    }
    if (options.cameras.empty()) {
      options.cameras = dataset::ListDefaultCameras(*program_, batch.sample, batch.seed);
      if (options.cameras.empty()) {
        PrintError(DescribeNoCamera(fmt::format("scene 0 of seed {}", batch.seed)));
        return kExitUsage;
      }
    }
    writer = std::make_unique<dataset::DatasetWriter>(options, dataset::ListClassIds(*program_));
    sampling::BatchCallbacks callbacks;
    callbacks.consume = [&](sampling::BatchScene&&) { progress_.Update(++done_); };
    progress_.Attach(batch, callbacks);
    dataset::AddSampledScenes(*writer, *program_, batch, callbacks);
    images = writer->Finish();
    return kExitSuccess;
  }

  int RunOnFile(dataset::DatasetOptions& options, std::unique_ptr<dataset::DatasetWriter>& writer,
                int64_t& images) {
    const auto lines = ReadLines(args_.scenario.file);
    if (!lines) return kExitScenarioError;
    // The scenes of the range, read on this thread (the reader is not thread-safe).
    output::SceneReader reader;
    std::vector<sampling::SampledScene> scenes;
    uint64_t at = 0;
    for (size_t i = 0; i < lines->size() && int64_t(scenes.size()) < args_.range.count; ++i) {
      if (IsBlankLine((*lines)[i])) continue;
      if (at++ < args_.range.start) continue;
      try {
        scenes.push_back(reader.Read((*lines)[i]));
      } catch (const std::invalid_argument& error) {
        PrintError(fmt::format("{}:{}: {}", args_.scenario.file, i + 1, error.what()));
        return kExitScenarioError;
      }
    }
    if (scenes.empty()) {
      PrintError(
          fmt::format("{} has no scene at index {}", args_.scenario.file, args_.range.start));
      return kExitScenarioError;
    }
    if (options.cameras.empty()) {
      options.cameras = dataset::ListCameraObjects(render::MakeRenderScene(scenes[0].scene));
      if (options.cameras.empty()) {
        PrintError(DescribeNoCamera(args_.scenario.file + "'s first scene"));
        return kExitUsage;
      }
    }
    std::vector<std::string> class_ids = dataset::ListClassIds(*reader.classes());
    if (!args_.classes.empty()) {
      ScenarioArgs program_args = args_.scenario;
      program_args.file = args_.classes;
      const auto program = CompileScenario(program_args);
      if (!program) return kExitScenarioError;
      class_ids = dataset::ListClassIds(*program);
    } else if (!args_.quiet) {
      PrintNote(
          "objects are numbered by the classes in the order the file first uses them; "
          "--classes PROGRAM.prs numbers them as that program's own dataset does");
    }
    writer = std::make_unique<dataset::DatasetWriter>(options, class_ids);
    // Images are numbered by the scene's place in the file (its line keeps its own seed and
    // index), so that a file of scenes `prs sample --like` drew is numbered densely.
    std::vector<const sampling::SampledScene*> pointers;
    std::vector<uint64_t> positions;
    for (size_t i = 0; i < scenes.size(); ++i) {
      pointers.push_back(&scenes[i]);
      positions.push_back(args_.range.start + i);
    }
    done_ = dataset::AddScenes(*writer, pointers, positions, args_.sampling.threads);
    images = writer->Finish();
    return kExitSuccess;
  }

  const DatasetArgs& args_;
  std::unique_ptr<lang::CompiledProgram> program_;
  std::unique_ptr<search::Design> design_;
  std::unique_ptr<search::GaussianPoints> like_;
  InterruptWatch interrupt_;
  ProgressBar progress_;
  int64_t done_ = 0;
};

}  // namespace

CommandRunner ConfigureDatasetCommand(CLI::App& command) {
  auto args = std::make_shared<DatasetArgs>();
  AddScenarioOptions(command, args->scenario);
  AddSceneRangeOptions(command, args->range, 1);
  command
      .add_option("-o,--output", args->output,
                  "write the dataset to DIR (via DIR.partial, renamed when complete); DIR must "
                  "not exist or be empty, unless --append")
      ->type_name("DIR")
      ->required()
      ->check(NonEmptyPath());
  AddDatasetPictureOptions(command, args->pictures);
  command.add_flag("--append", args->append,
                   "add these scenes' images to the dataset DIR (their image numbers must be new: "
                   "another --start)");
  command
      .add_option("--classes", args->classes,
                  "with a scenes file: number objects by this program's classes, as its own "
                  "dataset does")
      ->type_name("PROGRAM.prs")
      ->check(NonEmptyPath());
  AddSamplingOptions(command, args->sampling);
  AddDesignOption(command, args->design);
  AddLikeOptions(command, args->like);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  return [args]() -> int {
    if (!CheckSceneRange(args->range)) return kExitUsage;
    return DatasetRun(*args).Run();
  };
}

}  // namespace prs::cli
