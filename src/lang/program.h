// The compiled form of a scenario: parsed modules, the class table, and one evaluation plan
// per object-creation site. Built once by Compile(); read-only while scenes are sampled,
// so any number of threads may sample from one CompiledProgram.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "lang/ast.h"
#include "lang/source.h"
#include "shapes/mesh.h"

namespace prs::lang {

namespace internal {
class ArmStore;  // arms.h: URDF texts, chains and reachable sets for `reachable by`
}

/// A property's default in a class body (or a built-in default when `expr` is null).
struct PropertyDefault {
  std::string name;
  const Expr* expr = nullptr;          // null: built-in default (origin, identity, 1 m, 0, False)
  int module_index = -1;               // module whose globals the default is evaluated in
  std::vector<std::string> self_reads; // properties read as `self.NAME`
  SourceSpan span;
};

/// An object class. Built-in: Point3D <- OrientedPoint3D <- Object <- user classes.
struct ClassInfo {
  std::string name;
  const ClassInfo* parent = nullptr;
  SourceSpan span;
  bool has_span = false;
  bool has_orientation = false;  // OrientedPoint3D and below
  bool has_box = false;          // Object and below: width, length, height
  std::vector<PropertyDefault> defaults;  // inherited ones first; a child's override in place

  const PropertyDefault* FindDefault(const std::string& property) const;
  bool IsSubclassOf(const ClassInfo* other) const;
};

/// Where a property of an object comes from in a creation plan.
enum class PlanStepKind {
  kDefault,      // a class default
  kWith,         // `with PROP value`
  kPosition,     // every position specifier together (regions intersect)
  kOrientation,  // the orientation: `facing`, `facing toward`, `with orientation`, or default,
                 // composed with yaw, pitch and roll
};

struct PlanStep {
  PlanStepKind kind;
  std::string property;
  const PropertyDefault* default_value = nullptr;  // kDefault
  const Specifier* specifier = nullptr;            // kWith, or the orientation specifier
};

/// How to build an object at one creation site: properties in dependency order.
struct ObjectPlan {
  const ClassInfo* cls = nullptr;
  std::vector<PlanStep> steps;
  std::vector<const Specifier*> position_specifiers;
  /// Size and orientation are known before the position, so the workspace (eroded by the
  /// object's box) is folded into the position region instead of being a rejection check.
  bool fold_workspace = false;
  /// The position region, the object's box and its orientation are the same in every scene
  /// (a top-level creation from fixed values; see fixed.cc), so fixed obstacles can be cut out
  /// of the region exactly and the result cached.
  bool region_fixed = false;
  /// Every property, the position included, is the same in every scene: a fixed obstacle.
  bool object_fixed = false;
  /// Every property but the position is the same in every scene, and nothing the placement
  /// reads (size, shape, orientation) comes after the position step: the
  /// object is built once per thread as a template (RunCache::object_templates), and later
  /// scenes copy it and only place it (placement_fixed.cc).
  bool template_fixed = false;
  /// Set when the orientation reads the position while a position specifier needs the box's
  /// orientation (`completely on X, facing toward Y`; spec §7): the position is drawn from a
  /// superset of the valid centres that holds for every orientation the object may take, and
  /// the exact test runs once the orientation is known, rejecting the attempt when it fails.
  /// kYaw: only a turn about the vertical is open (pitch and roll are known first), so the
  /// superset erodes by the largest horizontal disk inside the box; kAny: any turn, so it
  /// erodes by the box's inscribed ball.
  enum class OpenTurn { kNone, kYaw, kAny };
  OpenTurn open_turn = OpenTurn::kNone;
  /// The object is a function of the numbers its creation draws: its specifiers and class
  /// defaults read only names that are the same in every scene (and never rebound), its own
  /// properties and built-ins, and create nothing (own_draws.cc). A run may then reuse an
  /// earlier run's object made from the same numbers (RunOptions::reuse_objects).
  bool own_draws_only = false;
};

/// A parsed module (the main file or an imported one).
struct ModuleInfo {
  std::string name;  // module name ("model"), or the main file's path
  FileId file = 0;
  Module ast;
  std::vector<std::string> global_names;  // every name bound at top level, imports included
};

struct CompiledProgram {
  SourceManager sources;
  std::vector<std::unique_ptr<ModuleInfo>> modules;  // imported modules first, main last
  std::vector<std::unique_ptr<ClassInfo>> classes;   // built-ins first
  std::unordered_map<const CreateObject*, ObjectPlan> plans;
  /// Plans for a bare class name used as a statement or assigned (`c = Cube`).
  std::unordered_map<const ClassInfo*, ObjectPlan> default_plans;
  /// `-p NAME=VALUE` overrides: the text is parsed as a number when it is one, else a string.
  std::unordered_map<std::string, std::string> param_overrides;
  /// For each module, which module each `from M import *` statement runs.
  std::unordered_map<const FromImportStmt*, int> import_targets;
  /// For each module, its class table (name -> class) as seen by its creation sites.
  std::vector<std::map<std::string, const ClassInfo*>> class_scopes;
  int main_module = 0;
  /// The arms `reachable by` uses: URDF files read at compile time, chains and reachable sets
  /// built on first use (thread-safe).
  std::shared_ptr<internal::ArmStore> arms;
  /// A mesh file a `Mesh("...")` call names: loaded and checked at compile time, by the name
  /// the program gives it; the bytes are kept for campaigns, which copy the files they use.
  struct MeshFile {
    std::shared_ptr<const shapes::MeshShape> shape;
    std::string path;
    std::string bytes;
  };
  std::map<std::string, MeshFile> meshes;

  const ModuleInfo& main() const { return *modules[main_module]; }
};

}  // namespace prs::lang
