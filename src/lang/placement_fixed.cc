// Fixed placements: an object whose position region, box and orientation are the same in
// every scene (ObjectPlan::region_fixed) is placed in its region minus the fixed obstacles
// placed before it, sampled exactly from disjoint convex pieces. This is exact conditioning
// (spec §7): the fraction of the region cut away is the same in every scene, so removing it
// changes no scene's weight, only the number of rejected attempts. The pieces are built once
// per thread and cached (RunCache); building or reusing them consumes the same random draws.
// Objects that are wholly fixed (ObjectPlan::object_fixed) are likewise built once and copied,
// and objects fixed but for their position (ObjectPlan::template_fixed) copied, then placed.
// An object `on` another is drawn from the region made for the target at the origin, moved
// (PlaceOnMovedRegion), and kept when both are copies of templates.
#include <algorithm>
#include <atomic>

#include "geometry/difference.h"
#include "lang/interp_internal.h"

namespace prs::lang {

void RunCacheDeleter::operator()(RunCache* cache) const { delete cache; }

std::unique_ptr<RunCache, RunCacheDeleter> MakeRunCache() {
  return std::unique_ptr<RunCache, RunCacheDeleter>(new RunCache());
}

}  // namespace prs::lang

namespace prs::lang::internal {

using Eigen::Vector3d;
using geometry::ConvexRegion;

namespace {

// Past this many pieces, further obstacles are left to the collision check (still exact).
constexpr size_t kMaxPieces = 256;

// A counter, not random state: ids only tell copies of one kept object apart from others
// (SceneObject::fixed_id and template_id share it, so no two kept objects share an id).
uint64_t NextKeptId() {
  static std::atomic<uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

const FixedPlacement* Interpreter::CachedPlacement(const ObjectPlan& plan) const {
  if (!plan.region_fixed || !options_.cache || options_.mode != SamplingMode::kRegion) return nullptr;
  auto it = options_.cache->placements.find(&plan);
  return it == options_.cache->placements.end() ? nullptr : it->second.get();
}

Vector3d Interpreter::PlaceFixed(const ObjectPlan& plan,
                                 const std::vector<PositionConstraint>& constraints,
                                 const geometry::RegionUnion& region, int index, SourceSpan span) {
  std::shared_ptr<const FixedPlacement> placement =
      BuildFixedPlacement(constraints, region, index, span);
  if (options_.cache) options_.cache->placements[&plan] = placement;
  return SampleFixed(*placement, index, span);
}

// Earlier fixed objects this one could collide with.
std::vector<int> Interpreter::FixedObstacles(int index) const {
  std::vector<int> obstacles;
  const SceneObject& o = scene_.objects[index];
  if (!o.cls->has_box || o.allow_collisions) return obstacles;
  for (int j = 0; j < index; ++j) {
    const SceneObject& x = scene_.objects[j];
    // A mesh is cut out by its collision test, not its box: the box would forbid places where
    // only the boxes overlap (a mug's handle over a bowl).
    if (completed_[j] && x.fixed && x.cls->has_box && !x.allow_collisions && !x.mesh && !o.mesh) {
      obstacles.push_back(j);
    }
  }
  return obstacles;
}

std::shared_ptr<const FixedPlacement> Interpreter::BuildFixedPlacement(
    const std::vector<PositionConstraint>& constraints, const geometry::RegionUnion& region,
    int index, SourceSpan span) {
  if (region.IsEmpty()) {
    // Everything involved is fixed, so every scene would fail the same way.
    throw ScenarioError(ExplainEmptyRegion(constraints, Workspace(), index, span));
  }
  // The pieces live in the region's frame L; obstacles are moved there to be cut out.
  std::vector<ConvexRegion> pieces = region.piece_set().pieces();
  const Eigen::Isometry3d X_LW = region.X_WL().inverse();
  std::vector<int> cut;
  // Balls have no exact measure for weighting pieces: leave obstacles to the collision check.
  const bool has_balls = std::any_of(pieces.begin(), pieces.end(),
                                     [](const ConvexRegion& p) { return !p.balls().empty(); });
  const std::vector<int> obstacles = has_balls ? std::vector<int>{} : FixedObstacles(index);
  const geometry::OrientedBox box = BoxOf(index);
  for (int j : obstacles) {
    const ConvexRegion forbidden = geometry::TransformRegion(
        geometry::CalcBoxOverlapRegion(BoxOf(j), box.R_WB, box.half_extents), X_LW);
    std::vector<ConvexRegion> next;
    bool overlaps = false;
    for (const ConvexRegion& piece : pieces) {
      if (!geometry::DoesRegionOverlap(piece, forbidden)) {
        next.push_back(piece);
        continue;
      }
      overlaps = true;
      for (ConvexRegion& part : geometry::CalcRegionDifference(piece, forbidden)) {
        next.push_back(std::move(part));
      }
    }
    if (next.size() > std::max(kMaxPieces, pieces.size())) break;
    if (overlaps) cut.push_back(j);
    pieces = std::move(next);
    if (pieces.empty()) break;
  }
  if (pieces.empty()) {
    std::string names;
    for (int j : cut) names += (names.empty() ? "" : ", ") + scene_.objects[j].DisplayName(j);
    Fail(span, "empty-region",
         "every position that satisfies the specifiers of this " + scene_.objects[index].cls->name +
             " collides with " + names + ", which " + (cut.size() == 1 ? "is" : "are") +
             " the same in every scene",
         {{{}, false, "move the object's region or those objects apart"}});
  }
  auto placement = std::make_shared<FixedPlacement>(FixedPlacement{geometry::UnionSampler(
      geometry::RegionUnion(std::make_shared<const geometry::PieceSet>(std::move(pieces)), region.X_WL()))});
  placement->sampler.BuildAll();
  return placement;
}

Vector3d Interpreter::SampleFixed(const FixedPlacement& placement, int index, SourceSpan span) {
  if (options_.record_regions) {
    RecordRegion(index, "position", placement.sampler.pieces(), placement.sampler.X_WL());
  }
  return DrawUnionPosition(placement.sampler, index, span);
}

void Interpreter::RecordRegion(int object, std::string what, const std::vector<ConvexRegion>& pieces_L,
                               const Eigen::Isometry3d& X_WL) {
  PlacedRegion record;
  record.object = object;
  record.what = what + " of " + scene_.objects[object].DisplayName(object);
  for (const ConvexRegion& piece : pieces_L) {
    record.pieces_W.push_back(X_WL.isApprox(Eigen::Isometry3d::Identity())
                                  ? piece
                                  : geometry::TransformRegion(piece, X_WL));
  }
  scene_.regions.push_back(std::move(record));
}

const SceneObject* Interpreter::CachedFixedObject(const ObjectPlan& plan) const {
  if (!plan.object_fixed || !options_.cache || options_.mode != SamplingMode::kRegion) return nullptr;
  auto it = options_.cache->fixed_objects.find(&plan);
  return it == options_.cache->fixed_objects.end() ? nullptr : &it->second;
}

// Keeps a fixed object for later scenes when building it provably had no effect but the object
// itself: no draw, no nested object, and no property that refers to this scene's objects
// (whose indices may differ in another scene).
void Interpreter::StoreFixedObject(const ObjectPlan& plan, int index, int64_t draws_before) {
  if (!plan.object_fixed || !options_.cache || options_.mode != SamplingMode::kRegion) return;
  if (draws_ != draws_before || index + 1 != static_cast<int>(scene_.objects.size())) return;
  SceneObject& object = scene_.objects[index];
  for (const auto& [name, value] : object.properties) {
    if (!IsSameInEveryScene(value)) return;
  }
  object.fixed_id = NextKeptId();
  options_.cache->fixed_objects.emplace(&plan, object);
}

const RunCache::ObjectTemplate* Interpreter::CachedTemplate(const ObjectPlan& plan) const {
  if (!plan.template_fixed || !options_.cache) return nullptr;
  auto it = options_.cache->object_templates.find(&plan);
  return it == options_.cache->object_templates.end() ? nullptr : &it->second;
}

// Keeps the object as its site's template when its steps but the position drew nothing, made
// no object and left no property that refers to this scene's objects. Called once the steps
// have run and before the scene checks (FinishObject), so the template is the object exactly
// as the position step of a later copy finds it, but for properties the placement never reads
// (ObjectPlan::template_fixed).
void Interpreter::StoreTemplate(const ObjectPlan& plan, int index, int64_t effects) {
  if (!plan.template_fixed || !options_.cache || effects != 0) return;
  SceneObject& object = scene_.objects[index];
  size_t position_slot = object.properties.size();
  for (size_t i = 0; i < object.properties.size(); ++i) {
    const auto& [name, value] = object.properties[i];
    if (name == "position") {
      position_slot = i;
    } else if (!IsSameInEveryScene(value)) {
      return;
    }
  }
  if (position_slot == object.properties.size()) return;
  object.template_id = NextKeptId();
  options_.cache->object_templates.emplace(&plan, RunCache::ObjectTemplate{object, position_slot});
}

// A copy of the template, placed: the same as running every step, since the other steps give
// the template's values in every scene. The scene checks follow as for any object.
Value Interpreter::CreateFromTemplate(const ObjectPlan& plan, const RunCache::ObjectTemplate& kept,
                                      SourceSpan span) {
  const int index = AddObjectCopy(kept.object, span);
  const Vector3d p = PlaceObject(plan, index, span);
  scene_.objects[index].properties.SetValue(kept.position_slot, Value(p));
  FinishObject(index, span);
  return ObjectRef{index};
}

std::optional<Vector3d> Interpreter::PlaceOnMovedRegion(const ObjectPlan& plan, int index,
                                                         SourceSpan span) {
  if (!options_.move_on_regions || options_.mode != SamplingMode::kRegion || plan.region_fixed ||
      plan.open_turn != ObjectPlan::OpenTurn::kNone || plan.position_specifiers.size() != 1) {
    return std::nullopt;
  }
  const Specifier& s = *plan.position_specifiers.front();
  // A name only: evaluating it has no effect, so the general path may evaluate it again.
  if ((s.kind != SpecifierKind::kOn && s.kind != SpecifierKind::kCompletelyOn) ||
      !std::holds_alternative<NameRef>(s.target->node) || scene_.objects[index].mesh) {
    return std::nullopt;
  }
  const Value target = Eval(*s.target);
  const ObjectRef* ref = std::get_if<ObjectRef>(&target.data);
  if (!ref || ref->index == index || scene_.objects[ref->index].mesh) return std::nullopt;
  const SceneObject& x = scene_.objects[ref->index];
  // Both boxes the same in every scene: the region at the origin is kept (RunCache::on_kept).
  std::shared_ptr<const OnKeptPlacement> placement;
  if (options_.cache && plan.template_fixed && x.template_id != 0) {
    auto& kept = options_.cache->on_kept;
    auto it = kept.find({&plan, x.template_id});
    if (it == kept.end()) {
      it = kept.emplace(std::pair(&plan, x.template_id), MakeOnKeptPlacement(s, index, ref->index))
               .first;
    }
    placement = it->second;
  } else {
    placement = MakeOnKeptPlacement(s, index, ref->index);
  }
  if (!placement) return std::nullopt;
  const Vector3d p_WX = x.p_WO;
  std::vector<Vector3d> vertices_W = placement->vertices_L;
  for (Vector3d& v : vertices_W) v += p_WX;
  // Inside the region the general path intersects with (the workspace, eroded by the box when
  // it is folded in), the region moved is the whole position region.
  if (const ConvexRegion* workspace = Workspace()) {
    ConvexRegion storage = ConvexRegion::All();
    const ConvexRegion& bound = plan.fold_workspace ? ErodeWorkspace(*workspace, index, storage)
                                                    : *workspace;
    if (!bound.ContainsAll(vertices_W, 0)) return std::nullopt;
  }
  if (options_.record_regions) {
    RecordRegion(index, "position", {placement->region_L},
                 Eigen::Isometry3d(Eigen::Translation3d(p_WX)));
  }
  return DrawPosition(placement->sampler, index, span) + p_WX;
}

// The region of centres for the target moved to the world origin: the same for every copy of
// the target's template, so samples moved by the target's position are uniform in the region
// for that copy. Made by the general code, with the target's position set aside meanwhile.
std::shared_ptr<const OnKeptPlacement> Interpreter::MakeOnKeptPlacement(const Specifier& s,
                                                                        int index, int target) {
  struct MovedToOrigin {  // by index: the object list may grow meanwhile
    std::vector<SceneObject>& objects;
    int target;
    Vector3d p_saved;
    ~MovedToOrigin() { objects[target].p_WO = p_saved; }
  } moved{scene_.objects, target, scene_.objects[target].p_WO};
  scene_.objects[target].p_WO.setZero();
  const PositionConstraint c = EvalPositionConstraint(s, index, ObjectPlan::OpenTurn::kNone);
  if (c.is_point || c.pieces || c.box_region || !c.region.balls().empty() || c.region.IsEmpty() ||
      !c.region.IsBounded()) {
    return nullptr;  // the general path places (or rejects) it
  }
  try {
    return std::make_shared<const OnKeptPlacement>(
        OnKeptPlacement{c.region, c.region.CalcVertices(), geometry::RegionSampler(c.region)});
  } catch (const std::domain_error&) {
    return nullptr;
  }
}

}  // namespace prs::lang::internal
