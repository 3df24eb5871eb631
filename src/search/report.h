// Failure maps (docs/search.md, "Failure reports"): from episode records (prs test, prs search)
// to what a person needs to say "it fails when the cube is near the tray's far edge": the
// outcomes by scene feature and coordinate, the features that best separate failures from
// successes (one-threshold splits with confidence intervals, and a depth-2 tree), and the
// failure modes (failure-rich leaves of a depth-3 tree) with a representative episode each.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace prs::search {

/// One episode record as a report reads it.
struct ReportRecord {
  int64_t line = 0;              // 1-based line in the results file
  std::optional<uint64_t> seed;  // none in records written before seeds were recorded
  uint64_t index = 0;
  std::string outcome;
  std::string detail;
  std::string regenerate;  // the command that writes the scene again (failures only)
  std::string spec;        // the program's fingerprint (empty: scenes read from files, old records)
  /// The options that shaped the scenes (harness::SceneOptionsOf), when recorded.
  std::optional<std::string> scene_options;
  std::optional<double> score;
  std::vector<double> coordinates;
  std::vector<std::pair<std::string, double>> features;  // as recorded
  /// The scene's file when it was saved (--save-failures), as recorded; the report links it
  /// (and its picture, the same path with .png) as given, so a caller writing the report
  /// elsewhere first makes it relative to the report's folder.
  std::string saved_scene;
  /// The record's "search" tag: empty for scenes drawn from the program's law (prs test), else
  /// what chose the scene ("cross-entropy", "estimate-walk", "importance", ...).
  std::string search_strategy;
  /// prs estimate's importance-sampling records ("importance"): the weight against the
  /// program's law, the proposal's uniform share, and whether the estimate is self-normalised.
  double weight = 1, uniform_share = 1;
  bool normalised = true;
  double kernel_share = NAN;  // of an importance record's proposal density, when recorded
  std::string search_json;  // the "search" object as written (a replay copies it), else ""
  /// Set for a replay's records (`prs test --replay R`): R, and whether only R's failures
  /// were replayed.
  std::string replay_of;
  bool replay_failed_only = false;
  bool failed() const { return outcome != "success"; }
};

/// How a record's scene was chosen, which decides what its outcomes can estimate.
enum class RecordLaw {
  kIid,         // drawn independently from the program's law (prs test, a replay of such)
  kImportance,  // prs estimate's weighted draws: an estimate with the weights
  kSearch,      // chosen by a search or an estimate's adaptation: not the program's law
  kChain,       // a Markov chain's (--sampler gibbs): the program's law, but correlated
  kDesign,      // a design's points (--design): spread evenly, not independent
  kSelected,    // a replay of the failures alone (--failed): chosen by outcome
};

/// The law of `record`'s scene, from its search tag, replay tag and scene options.
RecordLaw DescribeLaw(const ReportRecord& record);

/// What a law's records are, for messages: "records of a search (not drawn from the
/// program's law)", ...
std::string DescribeLawInWords(RecordLaw law);

/// Parses JSON Lines records. Throws std::runtime_error located at "PATH:LINE" for a line that
/// is not a record or an importance-sampling record without a positive weight, and for a file
/// with no records.
std::vector<ReportRecord> ParseReportRecords(const std::vector<std::string>& lines,
                                             const std::string& path);

/// Features per record: the recorded ones whose values vary, then for every pair of objects
/// whose positions vary the horizontal distance "dist(A, B)" and the offsets "A-B.x",
/// "A-B.y", then the coordinates "u[j]". Records without a feature get NaN for it.
struct FeatureTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;  // rows[record][feature]
};
FeatureTable BuildFeatureTable(const std::vector<ReportRecord>& records);

/// The best one-threshold split of one feature: failures are more frequent on one side.
struct Split {
  int feature = -1;
  double threshold = 0;                     // the side is feature <= threshold, or > threshold
  bool failures_below = true;               // the failure-rich side is <= threshold
  int64_t n_side = 0, failures_side = 0;    // the failure-rich side
  int64_t n_other = 0, failures_other = 0;  // the rest
  double gain = 0;                          // information gain of the split (bits)
};

/// Every feature's best split, by gain (largest first). Empty when there are no failures or
/// no successes.
std::vector<Split> RankSplits(const FeatureTable& table, const std::vector<bool>& failed);

/// A node of the depth-2 tree: a split, and per side either a further split or a leaf.
struct TreeNode {
  std::optional<Split> split;      // none: a leaf
  int64_t n = 0, failures = 0;     // the records that reach it
  std::vector<TreeNode> children;  // [<= threshold, > threshold] when split
};
TreeNode GrowTree(const FeatureTable& table, const std::vector<bool>& failed, int depth,
                  int64_t min_leaf = 10);

/// Failure modes: the leaves of a depth-3 tree (GrowTree) where failures are more frequent than
/// overall and that hold at least 10 % of the failures, each described by its path
/// ("Cube#5.x ≤ -0.75 and ..."), with the failure nearest the mode's mean (in the path's
/// features, standardised) as its representative. Largest first. Failures outside every mode
/// are scattered ones.
struct FailureMode {
  std::string description;
  std::vector<size_t> members;  // the failing records in it (indexes into the records)
  int64_t n = 0;                // every record in it
  size_t representative = 0;
  std::vector<double> mean;  // per feature, over the members
};
std::vector<FailureMode> FindFailureModes(const FeatureTable& table,
                                          const std::vector<bool>& failed);

struct ReportOptions {
  std::string title;  // e.g. the results file's name
  /// When set, the scatter plot's path: it lies beside the report, which links it by its file
  /// name.
  std::string svg_path;
};

/// The whole report as Markdown (and the scatter plot as SVG text into *svg when asked).
std::string FormatFailureReport(const std::vector<ReportRecord>& records,
                                const ReportOptions& options, std::string* svg);

}  // namespace prs::search
