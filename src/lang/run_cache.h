// Per-thread caches for RunAttempt: work that gives the same result in every scene, done once.
// A RunCache never changes what a run produces, only how fast; it is not thread-safe, so each
// sampling thread owns one (sampling::SceneSampler does).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "geometry/sampling.h"
#include "geometry/union.h"
#include "lang/lang.h"
#include "lang/value.h"
#include "shapes/collide.h"
#include "shapes/hull_planes.h"

namespace prs::lang {

/// The position sampler of a creation site whose region and obstacles are fixed (see
/// ObjectPlan::region_fixed): the region minus the fixed obstacles, as disjoint convex pieces
/// (every piece's sampler built, so the placement may be read by any thread).
struct FixedPlacement {
  geometry::UnionSampler sampler;
};

/// `on` / `completely on` an object: the region of centres for the target moved to the world
/// origin (frame L), its vertices and its sampler. Where the region moved to the target lies
/// inside the workspace, it is the whole position region (placement_fixed.cc).
struct OnKeptPlacement {
  geometry::ConvexRegion region_L;
  std::vector<Eigen::Vector3d> vertices_L;
  geometry::RegionSampler sampler;
};

class RunCache {
 public:
  std::unordered_map<const ObjectPlan*, std::shared_ptr<const FixedPlacement>> placements;
  /// The globals of imported modules whose run drew nothing, created no object or param and
  /// left only immutable values, by module index: such a module binds the same values in every
  /// scene, and sharing them keeps derived data (a workspace's vertices) across scenes.
  std::unordered_map<int, std::unordered_map<std::string, Value>> module_globals;
  /// Objects of fixed creation sites (ObjectPlan::object_fixed), as first built.
  std::unordered_map<const ObjectPlan*, SceneObject> fixed_objects;
  /// Objects of creation sites fixed but for their position (ObjectPlan::template_fixed), as
  /// first built; `position_slot` is where "position" is in their properties.
  struct ObjectTemplate {
    SceneObject object;
    size_t position_slot = 0;
  };
  std::unordered_map<const ObjectPlan*, ObjectTemplate> object_templates;
  /// Kept fixed objects (by SceneObject::fixed_id) found inside a kept workspace (a region
  /// in module_globals, alive as long as this cache): not tested again.
  std::set<std::pair<uint64_t, const geometry::ConvexRegion*>> fixed_inside_workspace;
  /// A kept workspace eroded by a box (the bits of its rotation's 9 entries, then of its
  /// half-extents), at most kMaxEroded of them (sizes drawn anew in every scene would
  /// otherwise grow it without end).
  using ErodedKey = std::pair<const geometry::ConvexRegion*, std::array<uint64_t, 12>>;
  static constexpr size_t kMaxEroded = 256;
  std::map<ErodedKey, geometry::ConvexRegion> eroded_workspaces;
  /// For copies of templates (ObjectPlan::template_fixed) on copies of templates, by creation
  /// site and the target's SceneObject::template_id; null when the region cannot be used so
  /// (empty, unbounded, with balls).
  std::map<std::pair<const ObjectPlan*, uint64_t>, std::shared_ptr<const OnKeptPlacement>>
      on_kept;
  /// Region constructors called with plain numbers, vectors and orientations (a main-module
  /// `workspace = Cuboid(...)`), by call: the region the first call made, and the bits of its
  /// arguments. A later call with the same bits gets that region again, which lives as long as
  /// this cache, so what is worked out from it may be kept like a shared module's workspace
  /// (`kept_regions`). A call that once gets other arguments is `varying` and makes its region
  /// anew from then on (its first region stays alive, so no other region takes its address).
  struct RegionCall {
    std::vector<uint64_t> argument_bits;
    RegionPtr region;
    bool varying = false;
  };
  std::unordered_map<const CallExpr*, RegionCall> region_calls;
  /// Regions that live as long as this cache, finalized (geometry::ConvexRegion::Finalize):
  /// those of region_calls and the regions among module_globals.
  std::set<const geometry::ConvexRegion*> kept_regions;
  /// Collision shapes of meshes (by mesh and scale) and of boxes that meet a mesh (by size).
  std::map<std::tuple<const shapes::MeshShape*, double, double, double>,
           std::shared_ptr<const shapes::Collider>> colliders;
  /// The facet planes of meshes' convex hulls at scale 1, for footprints of open turns.
  std::unordered_map<const shapes::MeshShape*, std::vector<shapes::HullPlane>> hull_planes;
  /// Built-in shapes' polytopes by kind and size, at most kMaxPrimitives of them: sizes drawn
  /// anew in every scene would otherwise grow it without end. A polytope not kept here is made
  /// for its scene only and is never a key of `colliders` or `hull_planes` (its address may be
  /// reused once it is gone).
  static constexpr size_t kMaxPrimitives = 256;
  /// The last object each own-draws creation site made at each scene index, before its scene
  /// checks, with the coordinates its draws took (RunOptions::reuse_objects): made from the
  /// same numbers again, it would be the same object.
  struct ReusableObject {
    std::vector<double> u;
    int64_t draws = 0;
    SceneObject object;
  };
  std::map<std::pair<const ObjectPlan*, int>, ReusableObject> reusable;
  std::map<std::tuple<shapes::Primitive, double, double, double>,
           std::shared_ptr<const shapes::MeshShape>> primitives;
};

}  // namespace prs::lang
