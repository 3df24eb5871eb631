// The language stage's public interface: compile a .prs program once (parse, load modules,
// resolve names, plan object creation), then run it once per scene attempt with a seeded RNG.
#pragma once

#include <functional>
#include <memory>
#include <optional>
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

struct CompileOptions {
  /// Directories searched for `from NAME import *` after the importing file's own directory.
  std::vector<std::string> search_path;
  /// `param` overrides, NAME -> text (a number when it parses as one, else a string).
  std::vector<std::pair<std::string, std::string>> param_overrides;
  const FileSystem* file_system = nullptr;  // null: the real one
};

/// Compiles the program in `path`. Always returns a program, whose `sources` render the
/// diagnostics; it may be run only when `diagnostics.has_errors()` is false.
std::unique_ptr<CompiledProgram> CompileFile(const std::string& path, const CompileOptions& options,
                                             DiagnosticEngine& diagnostics);

/// Compiles program text given directly; `path` names it in messages and anchors imports.
std::unique_ptr<CompiledProgram> CompileText(const std::string& path, std::string text,
                                             const CompileOptions& options,
                                             DiagnosticEngine& diagnostics);

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

struct RunOptions {
  SamplingMode mode = SamplingMode::kRegion;
  RunLimits limits;
  RunCache* cache = nullptr;  // optional; never changes the result, only the speed
};

/// The outcome of one attempt: a scene, or the reason it was rejected.
using AttemptResult = std::variant<Scene, Rejection>;

/// Runs the program once. Random draws come from `rng`. Throws ScenarioError for errors in the
/// program (type errors, unbounded regions, exceeded limits, deterministic impossibilities).
AttemptResult RunAttempt(const CompiledProgram& program, geometry::Rng& rng,
                         const RunOptions& options = {});

}  // namespace prs::lang
