// RunOptions::reuse_objects: objects of own-draws sites (own_draws.cc) copied from an earlier
// run that made them from the same numbers. Such an object is a function of the coordinates
// its draws take, so the copy is the object the steps would make; its scene checks
// (FinishObject: collisions with what this run made before it) run as for any object.
#include <algorithm>

#include "lang/interp_internal.h"

namespace prs::lang::internal {
namespace {

bool IsSameStream(geometry::Rng a, geometry::Rng b) { return a.NextU64() == b.NextU64(); }

// Whether a value is plain data: no reference to a scene object (an index, which another
// run's scene may give to another object), and no container that could hold one.
bool IsPlainValue(const Value& value) {
  return !value.Is<ObjectRef>() && !value.Is<BoundMethod>() &&
         !value.Is<std::shared_ptr<TupleData>>() && !value.Is<std::shared_ptr<ListData>>() &&
         !value.Is<std::shared_ptr<DictData>>();
}

}  // namespace

bool Interpreter::CanReuse(const ObjectPlan& plan) const {
  const CoordinateInput& in = options_.coordinates;
  return options_.reuse_objects && plan.own_draws_only && options_.cache && in.values && !in.log &&
         !options_.record_regions && !coordinates_done_;
}

Interpreter::ReuseMark Interpreter::MarkReuse(const ObjectPlan& plan) const {
  ReuseMark mark;
  mark.active = CanReuse(plan);
  if (!mark.active) return mark;
  mark.first_coordinate = next_coordinate_;
  mark.draws_before = draws_;
  mark.stream_before = rng_;
  return mark;
}

void Interpreter::KeepForReuse(const ObjectPlan& plan, int index, const ReuseMark& mark) {
  if (!mark.active || coordinates_done_ || !IsSameStream(*mark.stream_before, rng_)) return;
  const SceneObject& object = scene_.objects[index];
  for (const auto& [name, value] : object.properties) {
    if (!IsPlainValue(value)) return;
  }
  RunCache::ReusableObject& kept = options_.cache->reusable[{&plan, index}];
  const double* u = options_.coordinates.values;
  kept.u.assign(u + mark.first_coordinate, u + next_coordinate_);
  kept.draws = draws_ - mark.draws_before;
  kept.object = object;
}

std::optional<Value> Interpreter::ReuseObject(const ObjectPlan& plan, int index, SourceSpan span) {
  if (!CanReuse(plan)) return std::nullopt;
  auto it = options_.cache->reusable.find({&plan, index});
  if (it == options_.cache->reusable.end()) return std::nullopt;
  const RunCache::ReusableObject& kept = it->second;
  const CoordinateInput& in = options_.coordinates;
  const auto n = static_cast<int>(kept.u.size());
  if (next_coordinate_ + n > in.size ||
      !std::equal(kept.u.begin(), kept.u.end(), in.values + next_coordinate_)) {
    return std::nullopt;
  }
  next_coordinate_ += n;
  draws_ += kept.draws;
  AddObjectCopy(kept.object, span);
  FinishObject(index, span);
  return Value(ObjectRef{index});
}

}  // namespace prs::lang::internal
