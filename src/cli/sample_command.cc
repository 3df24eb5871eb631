// `prs sample`: scenes start..start+count-1 as JSON Lines (spec §8) on stdout or in a file,
// sampled by worker threads and written in index order; a summary, and for long runs on a
// terminal a progress bar, on stderr.
#include <fmt/format.h>

#include <charconv>
#include <chrono>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/design_option.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "output/line_writer.h"
#include "output/scene_json.h"
#include "sampling/batch.h"
#include "cli/like_option.h"
#include "search/like.h"

namespace prs::cli {
namespace {

struct SampleArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  DesignArgs design;
  LikeArgs like;  // --like, --outcome, --near, --scale
  SceneRangeArgs range;
  std::string output;  // empty or "-": stdout
  bool quiet = false;
};

std::unique_ptr<output::LineWriter> OpenOutput(const std::string& path) {
  if (path.empty() || path == "-") return std::make_unique<output::LineWriter>();
  return std::make_unique<output::LineWriter>(path);
}

// Scenes printed on the terminal show progress themselves, and a bar would garble them.
bool ShouldShowProgress(const SampleArgs& args, const output::LineWriter& writer) {
  return !args.quiet && IsStderrTerminal() && (writer.is_file() || !IsStdoutTerminal());
}

// "100 scenes, 137 attempts, 37 rejections (collision 30, requirement 7); 0.02 s, 5000 scenes/s
// on 2 threads" (FormatSamplingCounts names the counts of the other samplers).
std::string FormatSampleSummary(const sampling::BatchSummary& summary,
                                const sampling::SampleOptions& options, double seconds,
                                int threads) {
  const std::string text = FormatSamplingCounts(summary, options);
  const double rate = seconds > 0 ? summary.scenes / seconds : 0.0;
  // Whole scenes per second, or tenths below 10 (a first run that computes a reachable set).
  return text + fmt::format("; {:.2f} s, {:.{}f} scenes/s on {}", seconds, rate, rate < 10 ? 1 : 0,
                            FormatCount(threads, "thread"));
}

class SceneWriterRun {
 public:
  SceneWriterRun(const lang::CompiledProgram& program, const SampleArgs& args,
                 output::LineWriter& writer)
      : program_(program),
        args_(args),
        writer_(writer),
        progress_(args.range.count, ShouldShowProgress(args, writer)) {}

  int Run() {
    const auto begin = std::chrono::steady_clock::now();
    try {
      sampling::BatchOptions options = MakeBatchOptions();
      if (!PrepareDesign(args_.design, program_, args_.range, options.sample, &design_)) {
        return kExitUsage;
      }
      if (args_.like.given()) {
        if (!PrepareLike(args_.like, program_, options.sample, like_, args_.quiet))
          return kExitUsage;
      }
      sampling::BatchCallbacks callbacks = MakeCallbacks();
      progress_.Attach(options, callbacks);
      const sampling::BatchSummary summary = sampling::SampleBatch(program_, options, callbacks);
      writer_.Commit();
      progress_.Erase();
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      if (!args_.quiet) {
        PrintNote(FormatSampleSummary(summary, options.sample, seconds,
                                      sampling::CountBatchThreads(options)));
        const std::string gibbs = DescribeGibbs(options.sample, summary.scenes);
        if (!gibbs.empty()) PrintNote(gibbs);
      }
      return kExitSuccess;
    } catch (const lang::ScenarioError& error) {
      return ReportFailure(error);
    } catch (const sampling::BatchCancelled&) {
      return ReportInterruption();
    } catch (const std::exception& error) {  // cannot write the output
      progress_.Erase();
      PrintError(error.what());
      return kExitScenarioError;
    }
  }

 private:
  sampling::BatchOptions MakeBatchOptions() const {
    sampling::BatchOptions options;
    options.sample = MakeSampleOptions(args_.sampling);
    options.seed = args_.sampling.seed;
    options.start = args_.range.start;
    options.count = args_.range.count;
    options.threads = args_.sampling.threads;
    options.cancel = &interrupt_.flag();
    return options;
  }

  sampling::BatchCallbacks MakeCallbacks() {
    sampling::BatchCallbacks callbacks;
    // Formatting is per scene and independent, so it runs on the workers, into one buffer
    // per run of scenes. The objects are freed there too: only the text and the counts travel
    // to the writer.
    callbacks.format = [](sampling::BatchScene& scene, std::string& text) {
      output::AppendSceneJson(scene.sampled, text);
      text += '\n';
      scene.sampled.scene = {};
    };
    callbacks.write = [this](std::string_view text, int64_t count) {
      writer_.AddLines(text, count);
    };
    callbacks.consume = [this](sampling::BatchScene&&) { progress_.Update(++done_); };
    return callbacks;
  }

  // The scenes before the failing one stay written (in OUT.partial for a file).
  int ReportFailure(const lang::ScenarioError& error) {
    progress_.Erase();
    const bool flushed = FlushQuietly();
    const int code = ReportScenarioError(error, program_.sources);
    if (flushed) PrintNote(DescribeFailure());
    return code;
  }

  std::string DescribeFailure() const {
    const uint64_t failed = args_.range.start + uint64_t(done_);
    const std::string where = writer_.partial_path();
    if (done_ == 0) return fmt::format("scene {} failed; no scene was written", failed);
    if (done_ == 1)
      return fmt::format("scene {} failed; the scene before it was written to {}", failed, where);
    return fmt::format("scene {} failed; the {} scenes before it were written to {}", failed, done_,
                       where);
  }

  int ReportInterruption() {
    progress_.Erase();
    if (FlushQuietly()) {
      PrintNote(fmt::format("interrupted; {} written to {} (resume with --start {} -n {})",
                            FormatCount(done_, "scene"), writer_.partial_path(),
                            args_.range.start + uint64_t(done_), args_.range.count - done_));
    }
    return kExitInterruptedBase + interrupt_.signal_number();
  }

  bool FlushQuietly() {
    try {
      writer_.Flush();
      return true;
    } catch (const std::exception& error) {
      PrintError(error.what());
      return false;
    }
  }

  const lang::CompiledProgram& program_;
  const SampleArgs& args_;
  output::LineWriter& writer_;
  InterruptWatch interrupt_;
  ProgressBar progress_;
  int64_t done_ = 0;
  std::unique_ptr<search::Design> design_;
  std::unique_ptr<search::GaussianPoints> like_;
};

int RunSample(const SampleArgs& args) {
  if (!CheckSceneRange(args.range)) return kExitUsage;
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  std::unique_ptr<output::LineWriter> writer;
  try {
    writer = OpenOutput(args.output);
  } catch (const std::exception& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
  return SceneWriterRun(*program, args, *writer).Run();
}

}  // namespace

CommandRunner ConfigureSampleCommand(CLI::App& command) {
  auto args = std::make_shared<SampleArgs>();
  AddScenarioOptions(command, args->scenario);
  AddSceneRangeOptions(command, args->range, 0);
  // --index I: the one scene a `prs test` record names, short for `-n 1 --start I`.
  command.add_option("--index", args->range.start, "only scene I (same as -n 1 --start I)")
      ->type_name("I")
      ->check(UnsignedIntegerText())
      ->excludes(command.get_option("--count"))
      ->excludes(command.get_option("--start"))
      ->each([args](const std::string&) { args->range.count = 1; });
  command
      .add_option("-o,--output", args->output,
                  "write to OUT (via OUT.partial, renamed when complete) instead of stdout")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  AddSamplingOptions(command, args->sampling);
  AddDesignOption(command, args->design);
  AddLikeOptions(command, args->like);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  return [args] { return RunSample(*args); };
}

}  // namespace prs::cli
