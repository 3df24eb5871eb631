// The language stage's public interface: compile a .prs program once (parse, load modules,
// resolve names, plan object creation), then run it once per scene attempt with a seeded RNG.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "geometry/random.h"
#include "lang/diagnostics.h"
#include "lang/program.h"
#include "lang/scene.h"

namespace prs::lang {

/// File access, injected so tests can fake it and so the language never touches the disk itself.
class FileSystem {
 public:
  virtual ~FileSystem() = default;
  /// Returns the file's contents, or nullopt if it cannot be read.
  virtual std::optional<std::string> ReadFile(const std::string& path) const = 0;
};

/// The real file system.
const FileSystem& RealFileSystem();

/// Where reachable sets are cached by default: $PRS_CACHE_DIR when set (empty: no disk cache),
/// else $XDG_CACHE_HOME/probrobscene, else $HOME/.cache/probrobscene, else "" (no disk cache).
std::string DefaultCacheDir();

struct CompileOptions {
  /// Directories searched for `from NAME import *` after the importing file's own directory.
  std::vector<std::string> search_path;
  /// `param` overrides, NAME -> text (a number when it parses as one, else a string).
  std::vector<std::pair<std::string, std::string>> param_overrides;
  const FileSystem* file_system = nullptr;  // null: the real one
  /// Where reachable sets (`reachable by`) are cached between runs: by default the user's cache
  /// (DefaultCacheDir, as prs and the Python package use); empty: no disk cache.
  std::string cache_dir = DefaultCacheDir();
  /// The grid spacing of reachable sets (metres); 0 keeps kinematics::ReachOptions' default.
  /// Coarser grids compute faster and cover less: for the fuzzer, not for users.
  double reach_resolution_m = 0;
  /// Called (from any sampling thread, one call at a time) with notes for the user that arise
  /// while the program runs, e.g. "panda's reachable set (...): computed in 1.2 s".
  std::function<void(const std::string&)> on_note;
};

/// Compiles the program in `path`. Always returns a program, whose `sources` render the
/// diagnostics; it may be run only when `diagnostics.has_errors()` is false.
std::unique_ptr<CompiledProgram> CompileFile(const std::string& path, const CompileOptions& options,
                                             DiagnosticEngine& diagnostics);

/// Compiles program text given directly; `path` names it in messages and anchors imports.
std::unique_ptr<CompiledProgram> CompileText(const std::string& path, std::string text,
                                             const CompileOptions& options,
                                             DiagnosticEngine& diagnostics);

/// A file a program reads besides its modules (a URDF file an `arm` property names): the name
/// the program gives it, the path it was read from, and its text as read at compile time.
struct ProgramResource {
  std::string name;
  std::string path;
  std::string text;
};

/// The resources of a compiled program, by name (campaigns copy them; the spec hash covers them).
std::vector<ProgramResource> ListResources(const CompiledProgram& program);

/// Bounds on one run, each a clear error when exceeded.
struct RunLimits {
  int64_t max_loop_iterations = 1'000'000;  // all loops of one attempt together
  int max_call_depth = 100;
  /// Nested expression evaluations, function calls included (each tree's own height is
  /// bounded by the parser): keeps evaluation within a thread's stack, sanitizers included.
  int max_eval_depth = 2000;
  int max_objects = 10'000;
};

enum class SamplingMode {
  kRegion,  // positions drawn exactly from their specifiers' regions (the default)
  kNaive,   // positions drawn from the workspace; specifiers checked afterwards (paper baseline)
};

/// Per-thread caches of work that is the same in every scene (the sampler of a position
/// region built only from fixed values). Opaque; create with MakeRunCache, one per thread.
class RunCache;
struct RunCacheDeleter {
  void operator()(RunCache* cache) const;
};
std::unique_ptr<RunCache, RunCacheDeleter> MakeRunCache();

/// One scene coordinate: a number of [0, 1) that one draw of an attempt reads when the
/// attempt runs at a point of the unit cube (docs/search.md, "Scene coordinates").
struct CoordinateInfo {
  /// Readable and derived from the program: "Cube#5.position[0]", "tr_1.width",
  /// "Range at table_cube.prs:19:13". Names may repeat when one expression draws twice.
  std::string name;
  /// What reads it: "Range", "DiscreteRange", "Normal", "TruncatedNormal", "Uniform",
  /// "Discrete", "require[p]", "interval", "position" (one per dimension of the region),
  /// "position piece" (which piece of a union).
  std::string draw;
  SourceSpan span;  // the draw in the source
};

/// Where an attempt's draws come from. Draws take their numbers from `values`, in the order
/// the attempt makes them, each draw k numbers at once (1 for a number, one per dimension for
/// a position); the first draw that does not fit in what is left, and every draw after it,
/// reads the Rng stream instead. With no values every draw reads the stream (the default).
/// The most coordinates a log records (CoordinateInput::log): a program may draw a million
/// numbers in a loop, and naming them all would only cost time and memory.
inline constexpr size_t kMaxLoggedCoordinates = 1024;

struct CoordinateInput {
  const double* values = nullptr;  // the attempt's point u, each in [0, 1)
  int size = 0;
  /// When set, every draw appends one entry per number it reads (as if `size` were
  /// unlimited), whether the numbers came from `values` or the stream, up to
  /// kMaxLoggedCoordinates entries.
  std::vector<CoordinateInfo>* log = nullptr;
};

struct RunOptions {
  SamplingMode mode = SamplingMode::kRegion;
  RunLimits limits;
  RunCache* cache = nullptr;  // optional; never changes the result, only the speed
  CoordinateInput coordinates;
  /// Keep the region each position was drawn from in Scene::regions (for pictures); never
  /// changes the scene.
  bool record_regions = false;
  /// Rejections (kind, culprit) this scene's earlier attempts already reported: one of them
  /// again is rejected without working out its explanation (Rejection::detail and, for an
  /// empty region, the span of the specifier that emptied it), which only the first of each
  /// is kept for. Optional; never changes which attempts are rejected.
  const std::set<std::pair<RejectionKind, std::string>>* explained = nullptr;
  /// An object whose one position specifier is `on` or `completely on` another is drawn from
  /// the region made for the target at the world origin and moved to it (exact, and kept
  /// between scenes for templates; placement_fixed.cc). False: from the region made at the
  /// target, as any other object; the same law, with positions that differ in their last bits.
  /// For tests.
  bool move_on_regions = true;
  /// With a cache and coordinates: an object of a site that is a function of its own draws
  /// (ObjectPlan::own_draws_only) is copied from the last run that made it at this index from
  /// the same numbers, instead of made again (the Gibbs sampler's runs differ in one object's
  /// numbers). Never changes the scene.
  bool reuse_objects = false;
  /// The collision checks use a grid once this many collidable objects are made (collisions.cc;
  /// below it, testing each is cheaper). Never changes the scene or the rejection; for tests.
  int collision_grid_from = 32;
  /// Probe runs of the exact clutter sampler (sampling/partial_rejection.h): an object whose
  /// creation ordinal (its place among the run's creations, skipped ones counted, from 0) is
  /// marked true is not made, and its creation evaluates to None. Null: every object is made.
  const std::vector<bool>* skip_objects = nullptr;
  /// Probe runs: the run ends once the object of this creation ordinal is made and checked
  /// against the objects made before it, as if the program ended there (the workspace is still
  /// checked). Negative: the program runs to its end.
  int stop_after_object = -1;
  /// False: `require` statements are not checked (probe runs).
  bool check_requirements = true;
  /// False: objects are not tested against one another for overlap (the clutter sampler's
  /// first run, which only lists the objects a program makes).
  bool check_collisions = true;
};

/// What must still hold once a simulator has let the scene's free bodies come to rest
/// (--settle, sim/settle.h), checked on `settled`: every object inside the workspace, within
/// 5 mm (soft contacts sink that far), and every `require settled` the attempt ran. The
/// rejection (kind kUnsettled) naming the object or the statement, or nullopt. Throws
/// ScenarioError for errors in a requirement (a random draw, a type error).
std::optional<Rejection> CheckSettledScene(const Scene& settled);

/// Moves an object to a new pose (a simulator's rest pose), keeping its properties consistent:
/// `position`, `orientation`, and `yaw`, `pitch`, `roll` relative to the same base
/// orientation. The object is no longer `fixed`.
void MoveObject(SceneObject& o, const Eigen::Vector3d& p_WO, const Eigen::Quaterniond& R_WO);

/// Whether two placed objects collide as a run's scene check tests them (spec §6): both have
/// a box, neither allows collisions, and their shapes overlap (boxes exactly, meshes by FCL).
/// `cache` (optional, the thread's own) keeps meshes' collision shapes.
bool DoObjectsCollide(const SceneObject& a, const SceneObject& b, RunCache* cache);

/// The outcome of one attempt: a scene, or the reason it was rejected.
using AttemptResult = std::variant<Scene, Rejection>;

/// Runs the program once. Random draws come from `rng`. Throws ScenarioError for errors in the
/// program (type errors, unbounded regions, exceeded limits, deterministic impossibilities).
AttemptResult RunAttempt(const CompiledProgram& program, geometry::Rng& rng,
                         const RunOptions& options = {});

}  // namespace prs::lang
