// The test harness of the case study (paper §"Case Study", Table III): sample scenes, run a
// robot controller in each, and tabulate the outcomes. Independent of any simulator: a
// controller is anything that turns a sampled scene into an outcome (docs/harness.md).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/scene_json.h"
#include "output/scene_json.h"
#include "sampling/batch.h"
#include "sampling/sampler.h"

namespace prs::harness {

/// What one episode ended in.
struct EpisodeResult {
  /// "success", "perception-fault", "no-path", "poor-grip", or any other lowercase-hyphenated
  /// name (IsOutcomeName).
  std::string outcome;
  std::string detail;                               // one sentence for a person
  nlohmann::json extra = nlohmann::json::object();  // anything else the controller reports
  /// Robustness, when the controller reports one: finite, larger is safer, <= 0 should come
  /// with a failing outcome. Failure searches descend it (docs/search.md).
  std::optional<double> score = std::nullopt;
  /// About the scene or the set-up rather than the controller's behaviour (a pick target that
  /// had no mass and was given one, a scene with nothing movable), one sentence each. Not part
  /// of the record: a run reports each distinct one once (RunOptions::on_warning).
  std::vector<std::string> warnings = {};
};

/// A robot controller under test. RunEpisodes gives each worker thread its own controller, so
/// an implementation need not be thread-safe; it must not keep state that changes the outcome
/// of later episodes if the results are to be the same for any thread count.
class Controller {
 public:
  virtual ~Controller() = default;
  /// Runs one episode in `scene`, whose spec §8 JSON line is `scene_json`. Exceptions are
  /// recorded as the outcome "controller-error" with their message as the detail.
  virtual EpisodeResult RunEpisode(const sampling::SampledScene& scene,
                                   const std::string& scene_json) = 0;
};

/// Thrown by a controller that cannot start at all (a persistent worker that exits or sends no
/// handshake): unlike other exceptions it is not an episode's "controller-error" but stops the
/// run, as the same would happen in every later episode.
class ControllerStartError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Makes one controller (one per worker thread).
using ControllerFactory = std::function<std::unique_ptr<Controller>()>;

/// True for a non-empty name of lowercase letters, digits and single inner hyphens
/// ("no-path", "exit-3"), at most 64 characters.
bool IsOutcomeName(const std::string& name);

/// One episode as the harness records it.
struct EpisodeRecord {
  uint64_t seed = 0;
  uint64_t index = 0;
  EpisodeResult result;
  double wall_s = 0;        // wall-clock time of the episode alone (not the sampling)
  std::string saved_scene;  // the failure's scene file under --save-failures, else empty
  std::string regenerate;   // failures only: the `prs sample` command that rewrites the scene
  /// The scene coordinates the scene was drawn at (designs and searches), else empty.
  std::vector<double> coordinates;
  /// The program's fingerprint (search::CalcSpecHash) and the options that shape its scenes
  /// (SceneOptionsOf: "--settle=3 --sampler gibbs", "" for the defaults), set whenever a
  /// program made the scene (empty for scenes read from files), so that records are never
  /// read back, replayed or compared against another program or other scenes.
  std::string spec;
  std::string scene_options;
  /// Set by searches: {"strategy": ..., "generation": ...} (docs/search.md), else null. A
  /// replay keeps its record's (with an importance sample's weight).
  nlohmann::json search;
  /// Set by replays (`prs test --replay`): {"of": RECORDS, "failed_only": bool}, else null.
  /// A replay of only the failures is chosen by outcome, so its shares estimate nothing.
  nlohmann::json replay;
  /// The scene's features for failure reports (docs/search.md, "Failure maps"): per object,
  /// "NAME.x", "NAME.y", "NAME.z" (metres) and "NAME.yaw" (radians), in scene order.
  std::vector<std::pair<std::string, double>> features;
};

/// The features of EpisodeRecord::features for one scene (output/scene_json.h).
using output::CalcSceneFeatures;

/// Called for each failing episode on the worker thread that ran it, after the scene was
/// saved as `path_stem` + ".json": e.g. to render `path_stem` + ".png". It must be
/// thread-safe. Exceptions stop the run and propagate from RunEpisodes.
using FailureHook =
    std::function<void(const sampling::SampledScene& scene, const std::string& path_stem)>;

struct RunOptions {
  sampling::SampleOptions sample;
  uint64_t seed = 0;
  uint64_t start = 0;  // index of the first scene
  int64_t count = 0;
  int threads = 1;
  /// The arguments that select the scenes of `prs sample` (FILE, -I, -p, --naive), for the
  /// regenerate command of failure records; none, no command.
  std::vector<std::string> scenario_args;
  /// When non-empty, each failure's scene is written to DIR/seed-S-index-I.json (DIR exists).
  std::string save_failures_dir;
  FailureHook on_failure;  // optional; only with save_failures_dir
  /// Called on the calling thread with each record, in index order (optional).
  std::function<void(const EpisodeRecord&)> on_record;
  /// Called on the calling thread once for each distinct EpisodeResult::warnings sentence, at
  /// the first record that has it, before that record's on_record (optional).
  std::function<void(const std::string&)> on_warning;
  /// Polled between episodes; once true the run stops with sampling::BatchCancelled.
  const std::atomic<bool>* cancel = nullptr;
  /// Copied into each record of a scene the program made (EpisodeRecord::spec), with
  /// scene_options (EpisodeRecord::scene_options).
  std::string spec_hash;
  std::string scene_options;
};

struct RunSummary {
  std::vector<EpisodeRecord> records;  // in index order
  sampling::BatchSummary sampling;
  int threads = 1;  // the worker threads used
};

/// Runs the controller in scenes start..start+count-1 of `seed` on `threads` worker threads
/// (scenes sampled with sampling::SampleBatch) and returns the records in index order.
/// Throws what SampleBatch throws (lang::ScenarioError for a scenario that fails,
/// BatchCancelled, std::invalid_argument for bad counts), and std::runtime_error naming the
/// file when a failure's scene cannot be saved.
RunSummary RunEpisodes(const lang::CompiledProgram& program, const ControllerFactory& factory,
                       const RunOptions& options);

/// One scene of a replay as a worker thread makes it: a scene read back from a file with the
/// line the controller is to get, or one regenerated from its program (scene_json empty: the
/// controller gets output::FormatSceneJson(sampled)).
struct ReplayScene {
  sampling::SampledScene sampled;
  std::string scene_json;
  /// Copied into the episode's record (EpisodeRecord::search, EpisodeRecord::replay).
  nlohmann::json search = nullptr, replay = nullptr;
  /// When set, the record's scene_options instead of RunOptions::scene_options: the options
  /// of the run that first drew the scene (a Gibbs chain's point replayed without the chain).
  std::optional<std::string> scene_options = std::nullopt;
};
/// Makes the scene of replay item `item` (0 for the first). One per worker thread, so that it
/// may keep per-thread state (a sampling::SceneSampler); exceptions stop the replay.
using ReplaySource = std::function<ReplayScene(int64_t item)>;
using ReplaySourceFactory = std::function<ReplaySource()>;

/// Runs the controller in the scenes of items 0..count-1 (`prs test SCENES.jsonl`, `--replay`)
/// on options.threads worker threads and returns the records in item order, each with its
/// scene's own seed and index. Of `options` it uses threads, scenario_args (the regenerate
/// command of failures; empty for scenes that only a file holds), save_failures_dir,
/// on_failure, on_record, on_warning, cancel and spec_hash. Throws what the sources throw and
/// ControllerStartError for the lowest item that failed, after on_record has seen every record
/// before it; sampling::BatchCancelled once cancelled.
RunSummary ReplayEpisodes(int64_t count, const ReplaySourceFactory& sources,
                          const ControllerFactory& factory, const RunOptions& options);

/// One row of the outcome table.
struct OutcomeRow {
  std::string outcome;
  int64_t count = 0;
  double share = 0;  // count / episodes, in [0, 1]
};

/// The paper's Table III: one row per outcome, "success" first, then by count (largest
/// first), ties by name.
std::vector<OutcomeRow> TabulateOutcomes(const std::vector<EpisodeRecord>& records);

/// One JSON Lines record: seed, index, outcome, detail, score (when reported), wall_s, extra,
/// coordinates (when set), spec and scene_options (when spec is set), search and replay (when
/// set), features, and for failures regenerate (and saved_scene when saved). No trailing
/// newline.
std::string FormatRecordJson(const EpisodeRecord& record);

/// `prs sample ARGS... -s S --start I -n 1`, each argument quoted for a POSIX shell when it
/// needs to be.
std::string FormatRegenerateCommand(const std::vector<std::string>& scenario_args, uint64_t seed,
                                    uint64_t index);

/// The options among `scenario_words` (FILE, then -I, -p, --naive, --sampler, --stable...,
/// --settle, --design as prs sample takes them) that shape the scenes beyond the program's
/// fingerprint, which holds the files and -p: the rest after FILE without -I and -p pairs,
/// joined by spaces ("" for the defaults).
std::string SceneOptionsOf(const std::vector<std::string>& scenario_words);

/// `word` as one POSIX shell word: unchanged when it is plain, else in single quotes.
std::string QuoteForShell(const std::string& word);

}  // namespace prs::harness
