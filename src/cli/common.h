// What every `prs` command shares: the exit codes, the scenario and sampling options, compiling
// the scenario with its diagnostics printed, and reporting errors as `prs: error: ...`.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "lang/lang.h"
#include "sampling/batch.h"
#include "sampling/sampler.h"
#include "sim/settle.h"

namespace prs::cli {

/// The documented exit codes (docs/cli.md).
enum ExitCode : int {
  kExitSuccess = 0,
  kExitScenarioError = 1,      // compile or run-time error, unreadable FILE, unwritable OUT
  kExitUsage = 2,              // bad command line
  kExitSamplingFailure = 3,    // no valid scene within the attempt limit (or none possible)
  kExitInterruptedBase = 128,  // + the signal number, after SIGINT or SIGTERM
};

/// The scenario a command works on: FILE, -I DIR..., -p NAME=VALUE...
struct ScenarioArgs {
  std::string file;
  std::vector<std::string> include_dirs;
  std::vector<std::string> params;
};

/// How scenes are sampled: -s, --threads, --naive, --max-attempts.
struct SamplingArgs {
  uint64_t seed = 0;
  int threads = 1;
  bool naive = false;
  std::string sampler = "rejection";  // --sampler rejection|partial-rejection|gibbs
  int64_t max_attempts = 10'000;
  /// --stable[=T]: the simulated seconds of the physics check, as given ("1" for a bare
  /// --stable); empty when off.
  std::string stable_s;
  double stable_move_m = 0.01;
  double stable_turn_deg = 5;
  /// --settle[=T]: the simulated seconds scenes get to come to rest, as given ("4" for a bare
  /// --settle); empty when off.
  std::string settle_s;
};

/// The physics check of --stable or --settle (sim::MakePhysicsTest makes it).
sim::PhysicsCheck MakePhysicsCheck(const SamplingArgs& args);

/// `--stable 0.5` (a space where `=` belongs) in the words after a command name: the usage
/// error that suggests `--stable=0.5`, for --stable or --settle (options of `command` whose
/// value is optional, so that CLI11 takes the number for FILE or an extra word) followed by a
/// number; nullopt otherwise.
std::optional<std::string> DiagnoseSpacedFlagValue(const CLI::App& command,
                                                   const std::vector<std::string>& args);

/// What --sampler gibbs says after a run of `scenes` scenes: that they are correlated, the
/// autocorrelation time, thinning, burn-in and the effective number of scenes. Empty without
/// --sampler gibbs, or before any scene was drawn.
std::string DescribeGibbs(const sampling::SampleOptions& options, int64_t scenes);

/// The counts of a run of scenes, named for what they are. Whole-scene rejection: "100 scenes,
/// 137 attempts, 37 rejections (collision 30, requirement 7)", where attempts = scenes +
/// rejections. --sampler gibbs and partial-rejection run the program many times a scene and
/// have no attempts in that sense: "3000 scenes, 183069 program runs (Gibbs moves, each
/// redrawing one object), 12 rejected (collision 12)", "... program runs (one-object probes of
/// hard-core draws, and whole scenes), 2 whole scenes rejected (requirement 2)".
std::string FormatSamplingCounts(const sampling::BatchSummary& summary,
                                 const sampling::SampleOptions& options);

/// For a command or option that runs scenes at points it chooses (`with`: "prs estimate",
/// "--design sobol"): with --sampler gibbs or partial-rejection, which choose their own scene
/// coordinates, prints the usage error `--sampler KIND cannot be used with WITH: ...; INSTEAD`
/// and returns false; else returns true.
bool CheckSamplerTakesPoints(const SamplingArgs& args, std::string_view with,
                             std::string_view instead);
/// The same for a command that holds only the sample options (gibbs or partial_rejection set).
bool CheckSamplerTakesPoints(const sampling::SampleOptions& options, std::string_view with,
                             std::string_view instead);

/// Adds FILE, -I and -p to `command`.
void AddScenarioOptions(CLI::App& command, ScenarioArgs& args);
/// Adds -s, --threads, --naive, --sampler, --max-attempts and --stable[=T], --stable-move,
/// --stable-turn, --settle[=T] to `command`.
void AddSamplingOptions(CLI::App& command, SamplingArgs& args);
/// Which scenes a command makes: -n N (at least `min_count`) and --start I.
struct SceneRangeArgs {
  int64_t count = 1;
  uint64_t start = 0;
};
/// Adds -n/--count and --start to `command`.
void AddSceneRangeOptions(CLI::App& command, SceneRangeArgs& args, int64_t min_count);
/// Prints a usage error and returns false when the range runs past the last index, 2^64 - 1.
bool CheckSceneRange(const SceneRangeArgs& args);

/// Checks that an option's text is an integer in [min, max], with a message a user can act on.
CLI::Validator IntegerInRange(int64_t min, int64_t max);
CLI::Validator IntegerAtLeast(int64_t min);
/// Checks that an option's text is a non-negative integer (digits only, so "-1" is refused
/// instead of wrapping around in an unsigned option).
CLI::Validator UnsignedIntegerText();

/// Refuses an empty path (`-o ''`), which would otherwise mean stdout or nothing, silently.
CLI::Validator NonEmptyPath();
/// A number above 0 and below 10^6 ("expects a number of seconds above 0 ...").
CLI::Validator PositiveNumber(const std::string& of_what);

/// All hardware threads (at least 1).
int CountHardwareThreads();

/// Compiles the scenario (search path: -I dirs, then $PRS_PATH), printing every diagnostic on
/// stderr. Returns null when there were errors (a missing FILE is one: "file-not-found").
std::unique_ptr<lang::CompiledProgram> CompileScenario(const ScenarioArgs& args);

/// The sample options of `args`; the scene test is the physics check (MakePhysicsCheck). Without
/// --settle, the first scene that ran a `require settled` prints a warning, once a run of prs,
/// that it is ignored (`prs: warning: FILE:LINE:COL: ...`).
sampling::SampleOptions MakeSampleOptions(const SamplingArgs& args);
/// Batch options for scenes 0..count-1 of the seed in `args`, stopped when `cancel` is set.
sampling::BatchOptions MakeBatchOptions(const SamplingArgs& args, int64_t count,
                                        const std::atomic<bool>& cancel);

/// Prints the diagnostic of a failed run and returns its exit code: kExitSamplingFailure for
/// "sampling-failed" and "partial-rejection-too-dense" (no valid scene found), kExitScenarioError
/// for anything else.
int ReportScenarioError(const lang::ScenarioError& error, const lang::SourceManager& sources);

/// "1 scene", "2 scenes", "3 classes".
std::string FormatCount(int64_t n, std::string_view noun);

/// Prints `prs: error: MESSAGE` on stderr.
void PrintError(std::string_view message);
/// Prints `prs: MESSAGE` on stderr.
void PrintNote(std::string_view message);
/// Prints `prs: warning: MESSAGE` on stderr.
void PrintWarning(std::string_view message);

/// Prints each distinct warning once per command, however many episodes, generations or runs
/// report it (harness::RunOptions::on_warning). `before` runs first (to erase a progress bar).
/// Copies share what was printed (a search copies its options for each generation).
class WarnOnce {
 public:
  explicit WarnOnce(std::function<void()> before = {}) : before_(std::move(before)) {}
  void operator()(const std::string& warning);

 private:
  std::function<void()> before_;
  std::shared_ptr<std::set<std::string>> printed_ = std::make_shared<std::set<std::string>>();
};

/// True when stderr is a terminal (then diagnostics are coloured unless NO_COLOR is set).
bool IsStderrTerminal();
bool IsStdoutTerminal();

/// True for a scenes file (`prs sample` output: .jsonl, .json or .ndjson) rather than a program.
bool IsScenesFile(const std::string& path);
/// The file's lines; prints an error and returns nullopt if it cannot be read.
std::optional<std::vector<std::string>> ReadLines(const std::string& path);
/// True for a line of only spaces, tabs and carriage returns (skipped in scenes files).
bool IsBlankLine(std::string_view line);
/// The lines that are not blank.
int64_t CountNonBlank(const std::vector<std::string>& lines);
/// Prints that the scenes file `path` holds no scene (an error for every command reading one).
void PrintNoScenes(const std::string& path);

}  // namespace prs::cli
