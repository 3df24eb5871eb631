// The interpreter's internal interface: one Interpreter runs one scene attempt over a
// CompiledProgram. Split across files by job: interp.cc (statements, names, control flow),
// eval.cc (expressions and operators), call.cc (built-in and user calls), objects.cc (object
// creation plans and scene checks), placement.cc (position regions and sampling).
#pragma once

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "camera/camera.h"
#include "geometry/geometry.h"
#include "lang/builtins.h"
#include "lang/lang.h"
#include "lang/run_cache.h"

namespace prs::lang::internal {

// kStop: a probe run's object is made (RunOptions::stop_after_object): every statement, loop
// and module in progress ends.
enum class Flow { kNormal, kBreak, kContinue, kReturn, kStop };

using Env = std::unordered_map<std::string, Value>;

/// A module's globals: its own bindings over an optional shared layer, the globals of a module
/// whose run is the same in every scene (RunCache::module_globals), read but never written.
/// Importing such a module into one that has bound nothing yet, or running it, takes its
/// globals as the layer instead of copying them; any other import copies (later bindings win).
struct ModuleEnv {
  const Env* shared = nullptr;
  Env own;

  const Value* Find(const std::string& name) const {
    if (auto it = own.find(name); it != own.end()) return &it->second;
    if (shared) {
      if (auto it = shared->find(name); it != shared->end()) return &it->second;
    }
    return nullptr;
  }
  bool empty() const { return own.empty() && (!shared || shared->empty()); }
  /// Every binding, the shared layer's under the module's own.
  Env Flatten() const {
    Env all = shared ? *shared : Env{};
    for (const auto& [name, value] : own) all[name] = value;
    return all;
  }
};

/// Thrown to abandon the attempt: not an error, the sampler counts it and restarts.
struct RejectSignal {
  Rejection rejection;
};

/// A position constraint from one specifier: a point, or a region the position must lie in.
struct PositionConstraint {
  const Specifier* specifier;
  bool is_point = false;
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  geometry::ConvexRegion region = geometry::ConvexRegion::All();
  int target_object = -1;  // `on`/`completely on` an object: its index, for messages
  /// Naive mode only: where a lower-dimensional specifier's draw comes from when it differs
  /// from `region` (for `completely on`, the whole face before erosion).
  std::optional<geometry::ConvexRegion> naive_domain;
  /// Set while the orientation is still open (ObjectPlan::open_turn): the region the object's
  /// whole box must lie in, tested exactly once the orientation is known. `region` then holds
  /// a superset of the valid centres.
  std::optional<geometry::ConvexRegion> box_region;
  /// Set for a specifier whose region is a union of convex pieces (`reachable by`, `not in
  /// view of`); `region` is then all of space. `pieces_description` names it in messages.
  std::optional<geometry::RegionUnion> pieces;
  std::string pieces_description;
};

/// A line-of-sight test that waits for the whole scene (`visible from`, `completely visible
/// from`, `not visible from`): every other object may hide the one seen.
struct SightCheck {
  int index;       // the object seen
  int camera;      // the camera object (never an occluder), or -1 for an oriented point
  Eigen::Isometry3d X_WC;
  camera::CameraIntrinsics intrinsics;
  const Specifier* specifier;
};

/// A round set inside the object's box for every turn its open orientation may take: the disk
/// of `radius` normal to `axis`, or the ball of `radius` when `axis` is zero.
struct RoundCore {
  Eigen::Vector3d axis;
  double radius;
};

/// A `completely on` or side specifier whose exact test waits for the object's orientation.
struct OpenTurnCheck {
  int index;  // the object
  const Specifier* specifier;
  geometry::ConvexRegion box_region;  // where the whole box must lie
};

/// The object's box in the world: its centre, orientation and half its dimensions.
geometry::OrientedBox BoxOfObject(const SceneObject& o);
/// Whether the object (its mesh's hull, or its box) lies in `region` within `tolerance` metres.
bool ObjectInRegion(const geometry::ConvexRegion& region, const SceneObject& o, double tolerance);

/// Whether two placed objects overlap: boxes exactly, a mesh by FCL where the boxes overlap.
/// `cache` (optional) keeps the meshes' collision shapes (RunCache::colliders).
bool DoPlacedObjectsOverlap(const SceneObject& a, const SceneObject& b, RunCache* cache);
/// Whether caches keyed by the object's mesh may hold it (not a one-scene primitive).
bool IsShapeCachedIn(const SceneObject& o, const RunCache* cache);

/// The collision checks' broad phase: completed collidable objects, by the cells of a
/// horizontal grid their bounding balls' squares overlap (collisions.cc).
struct CollisionGrid {
  int collidable = 0;  // collidable objects checked so far
  bool built = false;  // from RunOptions::collision_grid_from of them on
  /// The filed (cell, object) pairs, chained by the cell's hash: heads[hash] is the last
  /// pair filed under it, Entry::next the one before (-1: none). Two arrays a run, not an
  /// allocation per cell.
  struct Entry {
    uint64_t cell;
    int object;
    int next;
  };
  std::vector<int> heads;  // a power of two of them
  std::vector<Entry> entries;
  std::vector<int> large;       // balls wider than a cell: tested against every object
  std::vector<int> candidates;  // scratch for one object's tests
};

class Interpreter {
 public:
  Interpreter(const CompiledProgram& program, geometry::Rng& rng, const RunOptions& options);
  AttemptResult Run();
  /// lang::CheckSettledScene (settled.cc).
  static std::optional<Rejection> CheckSettled(const Scene& settled);
  static bool IsSameInEveryScene(const Value& value);
  static bool IsSameInEveryScene(const Env& env);

  // --- expressions (eval.cc) ---
  void EnterNested(SourceSpan span);  // ++eval_depth_, or a limit error
  Value Eval(const Expr& expr);       // EnterNested, then EvalNode
  Value EvalNode(const Expr& expr);
  static constexpr int kMaxContainerDepth = 1000;
  Value CheckNesting(Value container, SourceSpan span);  // a limit error past kMaxContainerDepth
  double ToNumber(const Value& v, SourceSpan span, const std::string& what);
  Eigen::Vector3d ToVector(const Value& v, SourceSpan span, const std::string& what);
  Eigen::Quaterniond ToOrientation(const Value& v, SourceSpan span, const std::string& what);
  bool Truthy(const Value& v, SourceSpan span);
  double EvalNumber(const Expr& e, const std::string& what) { return ToNumber(Eval(e), e.span, what); }
  Eigen::Vector3d EvalVector(const Expr& e, const std::string& what) {
    return ToVector(Eval(e), e.span, what);
  }

  /// Throws a located ScenarioError.
  [[noreturn]] void Fail(SourceSpan span, const std::string& id, const std::string& message,
                         std::vector<DiagnosticNote> notes = {}) const;

  // --- randomness (coordinates.cc): every draw goes through here, so a scene with no draws is
  // deterministic; each reads its scene coordinates when the attempt runs at a point ---
  // `draw` names the draw's kind (CoordinateInfo::draw); `span` its source.
  double DrawUniform(double lo, double hi, SourceSpan span, const char* draw);
  double DrawNormal(double mean, double std, SourceSpan span);
  // Returns NaN when the interval holds almost none of the normal's mass.
  double DrawTruncatedNormal(double mean, double std, double lo, double hi, SourceSpan span,
                             int max_tries);
  int64_t DrawInt(int64_t lo, int64_t hi, SourceSpan span, const char* draw);
  // A uniform position of object `index` in the sampler's region.
  Eigen::Vector3d DrawPosition(const geometry::RegionSampler& sampler, int index, SourceSpan span);

 private:
  friend class ExprEvaluator;

  // --- statements (interp.cc) ---
  Flow ExecBody(const std::vector<StmtPtr>& body);
  Flow Exec(const Stmt& stmt);
  Flow ExecFor(const ForStmt& node, SourceSpan span);
  Flow ExecWhile(const WhileStmt& node, SourceSpan span);
  void ExecAssign(const AssignStmt& node, SourceSpan span);
  void ExecRequire(const RequireStmt& node, SourceSpan span);
  // --- requirements on the settled scene (settled.cc) ---
  void RecordSettledRequirement(const RequireStmt& node, SourceSpan span);
  std::optional<Rejection> CheckSettledRequirement(const SettledRequirement& requirement);
  void ExecParam(const ParamStmt& node);
  void RunModule(int module_index);
  void Bind(const std::string& name, Value value);
  Value Lookup(const std::string& name, SourceSpan span);
  Value EvalStatementValue(const Expr& expr);  // a bare class name here creates an object
  void CountLoopIteration(SourceSpan span);
  std::vector<Value> Iterate(const Value& v, SourceSpan span);

  // --- expressions (eval.cc) ---
  Value EvalBinary(BinaryOp op, const Value& a, const Value& b, SourceSpan span);
  Value EvalArithmetic(BinaryOp op, const Value& a, const Value& b, SourceSpan span);
  Value EvalCompare(BinaryOp op, const Value& a, const Value& b, SourceSpan span);
  Value EvalAttribute(const Value& object, const Identifier& attribute, SourceSpan span);
  Value EvalIndex(const Value& object, const Value& index, SourceSpan span);
  Value EvalSidePoint(const SidePointExpr& node, SourceSpan span);
  Value EvalRelativeTo(const Value& value, const Value& base, SourceSpan span);
  Value EvalOffsetBy(const Value& value, const Value& offset, SourceSpan span);
  bool ValuesEqual(const Value& a, const Value& b);
  OrientedPoint ToOrientedPoint(const Value& v, SourceSpan span, const std::string& what);

  // --- calls (call.cc) ---
  Value EvalCall(const CallExpr& call, SourceSpan span);
  // Each argument's value and span, in order.
  void EvalArguments(const CallExpr& call, std::vector<Value>& args,
                     std::vector<SourceSpan>& spans);
  void CheckArgumentCount(Builtin id, int n, SourceSpan span);  // of a built-in's call
  // The numbers range(...) gives: start + i·step for i in [0, count).
  struct NumberRange {
    double start, step;
    int64_t count;
    double At(int64_t i) const { return start + static_cast<double>(i) * step; }
  };
  NumberRange CalcRange(const std::vector<Value>& args, const std::vector<SourceSpan>& spans,
                        SourceSpan span);
  // `expr` is a call of the built-in range by its name: its numbers, the arguments evaluated
  // as EvalCall would. nullopt, with nothing evaluated but the name, for any other expression.
  std::optional<NumberRange> EvalRangeCall(const Expr& expr);
  Value CallBuiltin(Builtin id, const std::vector<Value>& args,
                    const std::vector<SourceSpan>& spans, SourceSpan span);
  Value CallDistribution(Builtin id, const std::vector<Value>& args,
                         const std::vector<SourceSpan>& spans, SourceSpan span);
  Value CallRegion(Builtin id, const std::vector<Value>& args,
                   const std::vector<SourceSpan>& spans, SourceSpan span);
  // CallRegion through RunCache::region_calls: the region this call made before when its
  // arguments are the same bits (call.cc).
  Value CallRegionKept(const CallExpr& call, Builtin id, const std::vector<Value>& args,
                       const std::vector<SourceSpan>& spans, SourceSpan span);
  Value CallMath(Builtin id, const std::vector<Value>& args, const std::vector<SourceSpan>& spans,
                 SourceSpan span);
  Value CallFunction(const FunctionRef& fn, const CallExpr& call, std::vector<Value> args,
                     SourceSpan span);
  Value CallMethod(const BoundMethod& method, const std::vector<Value>& args,
                   const std::vector<SourceSpan>& spans, SourceSpan span);
  void CheckWholeNumbers(const std::vector<Value>& args, const std::vector<SourceSpan>& spans);
  Value Draw(const Distribution& distribution, SourceSpan span);
  Value Resample(const Value& v, SourceSpan span);

  // --- objects (objects.cc) ---
  // A creation: skipped, or made (MakeObject), and the end of a probe run (RunOptions).
  Value CreateObject(const ObjectPlan& plan, SourceSpan span);
  Value MakeObject(const ObjectPlan& plan, SourceSpan span);
  /// Appends a copy of a made object (a template's, a reused one) at this statement, with the
  /// name it is bound to; returns its index. Its scene checks are still to run.
  int AddObjectCopy(const SceneObject& object, SourceSpan span);
  /// RunOptions::reuse_objects (reuse.cc): the object made at `index` from the same numbers by
  /// an earlier run, checked and placed in the scene, or nullopt to make it.
  std::optional<Value> ReuseObject(const ObjectPlan& plan, int index, SourceSpan span);
  /// Whether the object being made at `index` may be kept for reuse, and what it starts from.
  struct ReuseMark {
    bool active = false;
    int first_coordinate = 0;
    int64_t draws_before = 0;
    std::optional<geometry::Rng> stream_before;
  };
  bool CanReuse(const ObjectPlan& plan) const;
  ReuseMark MarkReuse(const ObjectPlan& plan) const;
  /// Keeps the object just made (before its scene checks) when its draws all came from the
  /// coordinates.
  void KeepForReuse(const ObjectPlan& plan, int index, const ReuseMark& mark);
  void RunPlanStep(const PlanStep& step, int index, SourceSpan span);
  Value EvalDefault(const PropertyDefault& d, int index);
  void SetOrientation(const PlanStep& step, int index);
  // `value_span` locates the value's expression for type and range errors.
  void SetProperty(int index, const std::string& name, Value value, SourceSpan value_span);
  Value GetProperty(int index, const std::string& name, SourceSpan span);
  void FinishObject(int index, SourceSpan span);
  // --- collisions (collisions.cc): each object against those made before it ---
  void CheckCollisions(int index);
  /// Completed, with a box, not allowing collisions: what CheckCollisions tests against.
  bool IsCollidable(int index) const;
  /// Files every collidable object so far but `checking` in the grid; later ones are filed as
  /// they come.
  void BuildGrid(int checking);
  void AddToCollisionGrid(int index);
  [[noreturn]] void RejectCollision(int index, int other);
  void CheckWorkspace();
  geometry::OrientedBox BoxOf(int index) const;
  // --- shapes (shapes.cc): meshes where boxes would be conservative ---
  Value CallMesh(const std::vector<Value>& args, const std::vector<SourceSpan>& spans, SourceSpan span);
  // A size step of an object whose shape is a mesh: the mesh's scaled bounding box; a size
  // given explicitly must agree with it (a located error otherwise).
  Value SizeFromShape(const PlanStep& step, int index, Value value, SourceSpan value_span);
  // A built-in shape's polytope at the object's size, into SceneObject::mesh once width,
  // length and height are all set (RunCache::primitives keeps those of repeated sizes).
  void SetPrimitiveMesh(int index);
  // Whether caches keyed by the object's mesh may hold it (not a one-scene primitive).
  bool IsShapeCached(const SceneObject& o) const;
  // Object `index`'s convex hull vertices in its frame, scaled; empty for a box.
  std::vector<Eigen::Vector3d> ScaledHull(int index) const;
  // The centres at which the object (its hull, or its box) lies in `region`, exactly.
  geometry::ConvexRegion ErodeByOwnShape(const geometry::ConvexRegion& region, int index) const;
  // Whether the object (its hull, or its box) lies in `region`.
  bool RegionContainsObject(const geometry::ConvexRegion& region, int index, double tolerance) const;
  // The object's extent beyond its centre along `normal` (its hull's or box's support).
  double CalcObjectSupport(int index, const Eigen::Vector3d& normal) const;
  // Whether two placed objects overlap (DoPlacedObjectsOverlap).
  bool DoObjectsOverlap(int a, int b);
  // `on X` / `completely on X` where X has a mesh: X's upward-facing surfaces as a union of
  // convex pieces in X's frame (each raised by the object's half height; for `completely`,
  // eroded by the object's hull or box), into c.pieces.
  void SetOnMeshSurfaces(PositionConstraint& c, int index, int target, bool completely,
                         ObjectPlan::OpenTurn open);
  std::string DescribeBox(int index) const;  // "c (0.05 x 0.05 x 0.05 m at (x, y, z))"
  const geometry::ConvexRegion* Workspace() const;
  const RegionPtr* FindWorkspace() const;  // null when `workspace` is not a region
  // `workspace` lives as long as the cache (RunCache::kept_regions): bound by a shared module,
  // or made by a region call of RunCache::region_calls.
  bool IsWorkspaceKept(const geometry::ConvexRegion& workspace) const;

  // --- placement (placement.cc) ---
  Eigen::Vector3d PlacePosition(const ObjectPlan& plan, int index, SourceSpan span);
  // The workspace eroded by the object's box: the kept one, or one made in `storage`.
  const geometry::ConvexRegion& ErodeWorkspace(const geometry::ConvexRegion& workspace, int index,
                                               geometry::ConvexRegion& storage);
  // PlacePosition with draws named after "position"; sets p_WO (objects.cc).
  Eigen::Vector3d PlaceObject(const ObjectPlan& plan, int index, SourceSpan span);
  PositionConstraint EvalPositionConstraint(const Specifier& s, int index,
                                            ObjectPlan::OpenTurn open);
  PositionConstraint EvalOnConstraint(const Specifier& s, int index, bool completely,
                                      ObjectPlan::OpenTurn open);
  PositionConstraint EvalSideConstraint(const Specifier& s, int index, ObjectPlan::OpenTurn open);
  // The centres for which the object (its box, or its mesh's hull) lies in `box_region`:
  // exact when the orientation is known, else eroded by the round core every turn it may take
  // keeps inside (a superset; the exact test is kept in c).
  geometry::ConvexRegion ErodeByOwnShapeOrCore(const geometry::ConvexRegion& box_region, int index,
                                       ObjectPlan::OpenTurn open, PositionConstraint& c);
  RoundCore CalcRoundCore(int index, ObjectPlan::OpenTurn open);
  RoundCore CalcMeshRoundCore(int index, ObjectPlan::OpenTurn open);
  // The rotation of the object's known pitch and roll (yaw 0), while its yaw is open.
  Eigen::Matrix3d CalcKnownTilt(int index);
  // --- robot- and camera-aware specifiers (placement_views.cc) ---
  PositionConstraint EvalReachableConstraint(const Specifier& s);
  PositionConstraint EvalViewConstraint(const Specifier& s, int index, ObjectPlan::OpenTurn open);
  // The camera a view specifier names: its pose and intrinsics (from its properties).
  SightCheck EvalCamera(const Specifier& s, int index);
  // A cached fixed object skips its placement: its line-of-sight tests are registered here.
  void RegisterFixedSightChecks(const ObjectPlan& plan, int index);
  // At the end of the attempt: every `visible from` test against the whole scene.
  void CheckSightLines();
  // With RunOptions::record_regions: keeps `pieces_L` (placed by X_WL) in Scene::regions.
  void RecordRegion(int object, std::string what, const std::vector<geometry::ConvexRegion>& pieces_L,
                    const Eigen::Isometry3d& X_WL = Eigen::Isometry3d::Identity());
  // A uniform position in a union of pieces: "position piece", then the position in it.
  Eigen::Vector3d DrawUnionPosition(const geometry::UnionSampler& sampler, int index, SourceSpan span);
  Eigen::Vector3d SampleUnion(const std::vector<PositionConstraint>& constraints,
                              const geometry::RegionUnion& region,
                              const geometry::ConvexRegion* workspace, int index, SourceSpan span);
  // Once the orientation is known: the exact tests the position was drawn without.
  void CheckOpenTurn(int index);
  // Naive mode: whether a violation of KIND becomes the scene's rejection (naive_violation_).
  // Only when none is kept yet, or a relative-position one replaces a containment one: the
  // paper's tool checked the relative-position constraints first, which is what its Table II's
  // split (108 relative position against 6 containment per scene) shows (docs/benchmarks.md).
  bool KeepsNaiveViolation(RejectionKind kind) const;
  Eigen::Vector3d SampleRegion(const std::vector<PositionConstraint>& constraints,
                               const geometry::ConvexRegion& region,
                               const geometry::ConvexRegion* workspace, int index, SourceSpan span);
  void CheckBounded(const std::vector<PositionConstraint>& constraints,
                    const geometry::ConvexRegion& region, int index, SourceSpan span);
  // --- fixed placements (placement_fixed.cc) ---
  const FixedPlacement* CachedPlacement(const ObjectPlan& plan) const;
  Eigen::Vector3d PlaceFixed(const ObjectPlan& plan, const std::vector<PositionConstraint>& constraints,
                             const geometry::RegionUnion& region, int index, SourceSpan span);
  std::shared_ptr<const FixedPlacement> BuildFixedPlacement(
      const std::vector<PositionConstraint>& constraints, const geometry::RegionUnion& region,
      int index, SourceSpan span);
  std::vector<int> FixedObstacles(int index) const;
  Eigen::Vector3d SampleFixed(const FixedPlacement& placement, int index, SourceSpan span);
  // Fixed objects (ObjectPlan::object_fixed) built once per RunCache and copied afterwards.
  const SceneObject* CachedFixedObject(const ObjectPlan& plan) const;
  void StoreFixedObject(const ObjectPlan& plan, int index, int64_t draws_before);
  // Objects fixed but for their position (ObjectPlan::template_fixed): the first one built is
  // kept as a template when its other steps had no effect beyond the object (`effects`: draws
  // and objects made by them); later ones copy it and run only the position step.
  const RunCache::ObjectTemplate* CachedTemplate(const ObjectPlan& plan) const;
  void StoreTemplate(const ObjectPlan& plan, int index, int64_t effects);
  Value CreateFromTemplate(const ObjectPlan& plan, const RunCache::ObjectTemplate& kept,
                           SourceSpan span);
  // An object `on` or `completely on` (its one position specifier) another: drawn from the
  // region made for the target at the origin and moved to it, when that region moved lies
  // inside the workspace; else nothing, and the general path places it. Kept for copies of
  // templates on copies of templates; made anew otherwise, so a cache changes no result.
  std::optional<Eigen::Vector3d> PlaceOnMovedRegion(const ObjectPlan& plan, int index,
                                                    SourceSpan span);
  std::shared_ptr<const OnKeptPlacement> MakeOnKeptPlacement(const Specifier& s, int index,
                                                             int target);
  Eigen::Vector3d SampleNaive(const std::vector<PositionConstraint>& constraints, int index,
                              SourceSpan span);
  // Why no position fits: the empty specifier with the sizes involved, or every region.
  Diagnostic ExplainEmptyRegion(const std::vector<PositionConstraint>& constraints,
                                const geometry::ConvexRegion* workspace, int index, SourceSpan span);
  std::string DescribeFootprintMismatch(const PositionConstraint& c, const SceneObject& o);
  // Fails at once when nothing random ran yet (every attempt would fail the same way);
  // otherwise rejects the attempt with the explanation as the rejection's detail.
  [[noreturn]] void RejectEmptyRegion(RejectionKind kind, std::string culprit, SourceSpan culprit_span,
                                      const std::vector<PositionConstraint>& constraints,
                                      const geometry::ConvexRegion* workspace, int index,
                                      SourceSpan span);
  [[noreturn]] void Reject(RejectionKind kind, std::string culprit, SourceSpan span,
                           std::string detail = "");
  // Whether this scene already reported (kind, culprit), so its detail need not be worked out
  // again (RunOptions::explained). Never true before a draw (a certain failure explains itself).
  bool IsExplained(RejectionKind kind, const std::string& culprit) const {
    return draws_ > 0 && options_.explained && options_.explained->count({kind, culprit}) > 0;
  }

  const CompiledProgram& program_;
  geometry::Rng& rng_;
  RunOptions options_;
  Scene scene_;
  std::vector<bool> completed_;      // per object: fully placed (collision checks use these)
  CollisionGrid collision_grid_;
  std::vector<ModuleEnv> module_envs_;
  std::vector<bool> module_ran_;
  std::vector<bool> module_shared_;     // globals from, or stored in, RunCache::module_globals
  std::vector<bool> imports_unshared_;  // imported a module whose globals are not shared
  int current_module_ = 0;
  Env* locals_ = nullptr;            // the current function's frame, if any
  // The variable a statement `NAME = Class ...` binds, so the object carries its name
  // (in rejection messages) while it is still being placed. Consumed by CreateObject.
  const std::string* pending_name_ = nullptr;
  SourceSpan current_statement_;  // for errors raised below the statement layer
  int self_index_ = -1;              // the object whose defaults are being evaluated
  int call_depth_ = 0;
  int eval_depth_ = 0;  // nested Eval calls, across function calls
  int64_t loop_iterations_ = 0;
  int64_t draws_ = 0;
  size_t creations_ = 0;  // CreateObject calls so far, skipped ones included
  bool stopped_ = false;  // RunOptions::stop_after_object's object is made
  // Scene coordinates (coordinates.cc): the next unread one, whether the stream took over, and
  // the object property being evaluated (for coordinate names).
  const double* TakeCoordinates(int k, const char* draw, SourceSpan span, int object = -1);
  std::string NameCoordinate(const char* draw, SourceSpan span, int object) const;
  int next_coordinate_ = 0;
  bool coordinates_done_ = false;
  int naming_object_ = -1;
  const std::string* naming_property_ = nullptr;
  // While alive, draws are named after `property` of object `index` (scene coordinates); the
  // names in force before come back when it ends, also when a rejection unwinds through it.
  class NamingScope {
   public:
    NamingScope(Interpreter& interpreter, int index, const std::string* property)
        : interpreter_(interpreter),
          saved_object_(interpreter.naming_object_),
          saved_property_(interpreter.naming_property_) {
      interpreter.naming_object_ = index;
      interpreter.naming_property_ = property;
    }
    ~NamingScope() {
      interpreter_.naming_object_ = saved_object_;
      interpreter_.naming_property_ = saved_property_;
    }
    NamingScope(const NamingScope&) = delete;
    NamingScope& operator=(const NamingScope&) = delete;

   private:
    Interpreter& interpreter_;
    int saved_object_;
    const std::string* saved_property_;
  };
  // Naive mode: the specifier that rejects the scene. As in the paper's tool, specifiers are
  // checked as constraints once the scene is complete, after collisions and the workspace, and
  // relative-position ones before containment ones (KeepsNaiveViolation).
  std::optional<Rejection> naive_violation_;
  std::vector<OpenTurnCheck> open_turn_checks_;  // see ObjectPlan::open_turn
  std::vector<SightCheck> sight_checks_;          // tested by CheckSightLines
  Value return_value_;
};

/// The user-facing name of a specifier for messages, e.g. "'completely on tr_1'".
std::string DescribeSpecifier(const Specifier& s, const SourceManager& sources);

}  // namespace prs::lang::internal
