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
#include "search/like.h"

namespace prs::cli {
namespace {

struct SampleArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  DesignArgs design;
  std::string like;     // --like RESULTS.jsonl
  std::string outcome;  // --outcome NAME (with --like)
  std::string near;     // --near RESULTS.jsonl[:LINE]
  double scale = 0.05;  // --scale S (with --near)
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
      if (!args_.like.empty() || !args_.near.empty()) {
        if (!PrepareLike(options.sample)) return kExitUsage;
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

  // --like: the proposal fitted to the failures of the records file; --near: normals of
  // standard deviation --scale around one record's coordinates.
  bool PrepareLike(sampling::SampleOptions& sample) {
    if (!CheckSamplerTakesPoints(sample, args_.near.empty() ? "--like" : "--near",
                                 "leave out --sampler (the default, rejection, is exact for any "
                                 "program)")) {
      return false;
    }
    std::string path = args_.near.empty() ? args_.like : args_.near;
    int64_t line = 0;
    const size_t colon = path.rfind(':');
    if (!args_.near.empty() && colon != std::string::npos && colon + 1 < path.size() &&
        path.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
      const char* digits = path.c_str() + colon + 1;
      if (std::from_chars(digits, path.c_str() + path.size(), line).ec != std::errc()) {
        PrintError("--near: no such line " + path.substr(colon + 1) + " in " +
                   path.substr(0, colon));
        return false;
      }
      path.resize(colon);
    }
    const auto lines = ReadLines(path);
    if (!lines) return false;
    const int dimension = static_cast<int>(sampling::DescribeCoordinates(program_, sample).size());
    try {
      if (dimension == 0) {
        throw std::runtime_error(std::string(args_.near.empty() ? "--like" : "--near") +
                                 ": this program draws nothing at random, so every scene is "
                                 "like every other");
      }
      if (!args_.near.empty()) {
        const std::vector<double> centre = search::ReadRecordCoordinates(
            *lines, path, line, search::CalcSpecHash(program_), dimension);
        like_ = std::make_unique<search::GaussianPoints>(
            centre, std::vector<double>(centre.size(), args_.scale), 0.0);
        sample.points = like_.get();
        if (!args_.quiet) {
          PrintNote(fmt::format("drawing scenes near {} {} (scale {})", path,
                                line ? fmt::format("line {}", line) : "(its first failure)",
                                args_.scale));
        }
        return true;
      }
      const search::FailureSet failures = search::ReadFailures(
          *lines, args_.like, args_.outcome, search::CalcSpecHash(program_), dimension);
      like_ = std::make_unique<search::GaussianPoints>(search::FitLike(failures));
      if (!args_.quiet) {
        PrintNote(fmt::format("drawing scenes like the {} of {}",
                              FormatCount(static_cast<int64_t>(failures.coordinates.size()),
                                          args_.outcome.empty() ? "failure" : args_.outcome),
                              args_.like));
      }
    } catch (const std::runtime_error& error) {
      PrintError(error.what());
      return false;
    }
    sample.points = like_.get();
    return true;
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
  CLI::Option* like =
      command
          .add_option("--like", args->like,
                      "draw scenes like the failing episodes of RESULTS (prs search -o, or prs "
                      "test --design -o): each still satisfies the whole program")
          ->type_name("RESULTS")
          ->check(NonEmptyPath())
          ->excludes(command.get_option("--design"));
  command.add_option("--outcome", args->outcome, "with --like: only episodes with this outcome")
      ->type_name("NAME")
      ->needs(like);
  CLI::Option* near =
      command
          .add_option("--near", args->near,
                      "draw scenes near one episode of RESULTS (LINE, or its first failure): "
                      "small changes that keep the whole program satisfied")
          ->type_name("RESULTS[:LINE]")
          ->check(NonEmptyPath())
          ->excludes(command.get_option("--design"))
          ->excludes(like);
  command
      .add_option("--scale", args->scale,
                  "with --near: the standard deviation of the changes, in scene coordinates")
      ->type_name("S")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str()
      ->needs(near);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  return [args] { return RunSample(*args); };
}

}  // namespace prs::cli
