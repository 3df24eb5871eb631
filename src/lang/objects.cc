// Object creation: runs a creation plan (defaults, `with`, orientation, position in dependency
// order), then the scene constraints that concern the new object: collisions with the objects
// already placed, and (at the end of the attempt) workspace containment.
#include <cmath>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Vector3d;

Value Interpreter::CreateObject(const ObjectPlan& plan, SourceSpan span) {
  const size_t ordinal = creations_++;
  if (options_.skip_objects && ordinal < options_.skip_objects->size() &&
      (*options_.skip_objects)[ordinal]) {
    pending_name_ = nullptr;
    return Value();
  }
  Value made = MakeObject(plan, span);
  if (options_.stop_after_object >= 0 &&
      ordinal == static_cast<size_t>(options_.stop_after_object)) {
    stopped_ = true;  // the statement ends, then everything around it (Flow::kStop)
  }
  return made;
}

Value Interpreter::MakeObject(const ObjectPlan& plan, SourceSpan span) {
  if (static_cast<int>(scene_.objects.size()) >= options_.limits.max_objects) {
    Fail(span, "limit-exceeded", "more than " + std::to_string(options_.limits.max_objects) +
                                     " objects in one scene; is a loop creating too many?");
  }
  const int index = static_cast<int>(scene_.objects.size());
  if (const SceneObject* cached = CachedFixedObject(plan)) {
    pending_name_ = nullptr;
    scene_.objects.push_back(*cached);
    completed_.push_back(false);
    FinishObject(index, span);  // an earlier random object may still collide with it
    RegisterFixedSightChecks(plan, index);
    return ObjectRef{index};
  }
  if (const RunCache::ObjectTemplate* kept = CachedTemplate(plan)) {
    return CreateFromTemplate(plan, *kept, span);
  }
  if (std::optional<Value> reused = ReuseObject(plan, index, span)) return std::move(*reused);
  const ReuseMark reuse = MarkReuse(plan);
  const int64_t draws_before = draws_;
  SceneObject object;
  object.properties.Mutable().reserve(plan.steps.size() + 1);  // each property, the position
  object.cls = plan.cls;
  object.span = span;
  object.fixed = plan.object_fixed;
  if (pending_name_) object.name = *pending_name_;
  pending_name_ = nullptr;  // nested creations inside the specifiers stay anonymous
  scene_.objects.push_back(std::move(object));
  completed_.push_back(false);
  int64_t effects = 0;  // draws and objects made by the steps other than the position
  for (const PlanStep& step : plan.steps) {
    if (step.kind == PlanStepKind::kPosition) {
      SetProperty(index, "position", Value(PlaceObject(plan, index, span)), span);
      continue;
    }
    const int64_t before = draws_ + static_cast<int64_t>(scene_.objects.size());
    RunPlanStep(step, index, span);
    if (step.kind == PlanStepKind::kOrientation && plan.open_turn != ObjectPlan::OpenTurn::kNone) {
      CheckOpenTurn(index);
    }
    effects += draws_ + static_cast<int64_t>(scene_.objects.size()) - before;
  }
  StoreTemplate(plan, index, effects);
  KeepForReuse(plan, index, reuse);
  FinishObject(index, span);
  StoreFixedObject(plan, index, draws_before);
  return ObjectRef{index};
}

int Interpreter::AddObjectCopy(const SceneObject& object, SourceSpan span) {
  const int index = static_cast<int>(scene_.objects.size());
  scene_.objects.push_back(object);
  SceneObject& copy = scene_.objects.back();
  copy.span = span;
  copy.name.reset();
  if (pending_name_) copy.name = *pending_name_;
  pending_name_ = nullptr;
  completed_.push_back(false);
  return index;
}

Vector3d Interpreter::PlaceObject(const ObjectPlan& plan, int index, SourceSpan span) {
  static const std::string kPosition = "position";
  const NamingScope naming(*this, index, &kPosition);  // draws in its specifiers
  const Vector3d p = PlacePosition(plan, index, span);
  scene_.objects[index].p_WO = p;
  return p;
}

void Interpreter::RunPlanStep(const PlanStep& step, int index, SourceSpan span) {
  // Draws made for this step are named after the property (scene coordinates).
  const NamingScope naming(*this, index, &step.property);
  switch (step.kind) {
    case PlanStepKind::kDefault:
    case PlanStepKind::kWith: {
      const bool with = step.kind == PlanStepKind::kWith;
      Value value = with ? Eval(*step.specifier->target) : EvalDefault(*step.default_value, index);
      const SourceSpan value_span = with ? step.specifier->target->span
                                         : step.default_value->expr ? step.default_value->expr->span : span;
      if (scene_.objects[index].mesh && !scene_.objects[index].primitive &&
          (step.property == "width" || step.property == "length" || step.property == "height")) {
        value = SizeFromShape(step, index, std::move(value), value_span);
      }
      SetProperty(index, step.property, std::move(value), value_span);
      break;
    }
    case PlanStepKind::kOrientation:
      SetOrientation(step, index);
      break;
    case PlanStepKind::kPosition:
      break;  // handled by CreateObject
  }
  (void)span;
}

Value Interpreter::EvalDefault(const PropertyDefault& d, int index) {
  if (!d.expr) {
    if (d.name == "position") return Value(Vector3d(Vector3d::Zero()));
    if (d.name == "orientation") return Orientation{Eigen::Quaterniond::Identity()};
    if (d.name == "width" || d.name == "length" || d.name == "height") return 1.0;
    if (d.name == "allowCollisions") return false;
    return 0.0;  // yaw, pitch, roll
  }
  const int saved_module = current_module_, saved_self = self_index_;
  Env* saved_locals = locals_;
  current_module_ = d.module_index;
  self_index_ = index;
  locals_ = nullptr;
  Value value = Eval(*d.expr);
  current_module_ = saved_module;
  self_index_ = saved_self;
  locals_ = saved_locals;
  return value;
}

// Orientation = base (facing / facing toward / with orientation / default) · yaw·pitch·roll.
void Interpreter::SetOrientation(const PlanStep& step, int index) {
  Eigen::Quaterniond R_base = Eigen::Quaterniond::Identity();
  const Specifier* s = step.specifier;
  if (s && s->kind == SpecifierKind::kFacing) {
    const Value target = Eval(*s->target);
    if (target.Is<Vector3d>()) {
      const Vector3d direction = target.As<Vector3d>();
      if (!(direction.norm() > 1e-12)) Fail(s->target->span, "bad-value", "cannot face a zero vector");
      R_base = Eigen::Quaterniond(geometry::CalcRotationFacing(direction));
    } else {
      R_base = ToOrientation(target, s->target->span, "the argument of 'facing'");
    }
  } else if (s && s->kind == SpecifierKind::kFacingToward) {
    const Vector3d p_target = EvalVector(*s->target, "the argument of 'facing toward'");
    R_base = Eigen::Quaterniond(
        geometry::CalcRotationFacingToward(scene_.objects[index].p_WO, p_target));
  } else if (s) {
    R_base = ToOrientation(Eval(*s->target), s->target->span, "the orientation");
  } else if (step.default_value && step.default_value->expr) {
    R_base = ToOrientation(EvalDefault(*step.default_value, index), step.default_value->span,
                           "the default orientation");
  }
  auto angle = [&](const char* name) {
    return ToNumber(GetProperty(index, name, {}), scene_.objects[index].span, name);
  };
  const Eigen::Matrix3d R_local =
      geometry::CalcRotationFromYawPitchRoll(angle("yaw"), angle("pitch"), angle("roll"));
  const Eigen::Quaterniond R_WO(R_base.toRotationMatrix() * R_local);
  if (!R_WO.coeffs().allFinite()) {
    // Only reachable through extreme coordinates whose differences overflow.
    Fail(s ? s->span : scene_.objects[index].span, "bad-value",
         "this orientation cannot be computed: its inputs are too large to be finite");
  }
  scene_.objects[index].R_WO = R_WO.normalized();
  SetProperty(index, "orientation", Orientation{scene_.objects[index].R_WO},
              scene_.objects[index].span);
}

void Interpreter::SetProperty(int index, const std::string& name, Value value,
                              SourceSpan value_span) {
  SceneObject& o = scene_.objects[index];
  using namespace std::literals;  // string_view comparisons: length first, then bytes
  const std::string_view key = name;
  const bool numeric = key == "width"sv || key == "length"sv || key == "height"sv ||
                       key == "yaw"sv || key == "pitch"sv || key == "roll"sv;
  if (numeric) {
    const double x = ToNumber(value, value_span, "'" + name + "'");
    if (!std::isfinite(x) || (name[0] != 'y' && name[0] != 'p' && name[0] != 'r' && x < 0)) {
      Fail(value_span, "bad-value", "the " + name + " of this " + o.cls->name + " is " + Repr(x) +
                                    "; sizes must be finite and >= 0");
    }
    value = Value(x);
    if (key == "width"sv) o.dimensions.x() = x;
    if (key == "length"sv) o.dimensions.y() = x;
    if (key == "height"sv) o.dimensions.z() = x;
  }
  if (key == "shape"sv) {
    const MeshRef* mesh = std::get_if<MeshRef>(&value.data);
    const PrimitiveRef* primitive = std::get_if<PrimitiveRef>(&value.data);
    o.mesh = mesh ? mesh->mesh : nullptr;
    o.mesh_scale = mesh ? mesh->scale : 1;
    o.primitive = primitive ? std::optional(primitive->kind) : std::nullopt;
  }
  bool replaced = false;
  std::vector<PropertyList::Entry>& properties = o.properties.Mutable();
  for (auto& [existing, v] : properties) {
    if (std::string_view(existing) == key) {
      v = std::move(value);
      replaced = true;
      break;
    }
  }
  if (!replaced) properties.emplace_back(name, std::move(value));
  const bool size = key == "width"sv || key == "length"sv || key == "height"sv;
  if (o.primitive && (size || key == "shape"sv)) SetPrimitiveMesh(index);
}

Value Interpreter::GetProperty(int index, const std::string& name, SourceSpan span) {
  const SceneObject& o = scene_.objects[index];
  for (const auto& [existing, v] : o.properties) {
    if (existing == name) return v;
  }
  std::vector<std::string> names{"x", "y", "z"};
  for (const auto& [existing, v] : o.properties) names.push_back(existing);
  const std::string suggestion = SuggestClosest(name, names);
  Fail(span, "unknown-property",
       "this " + o.cls->name + " has no property '" + name + "'" +
           (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?"));
}

void Interpreter::FinishObject(int index, SourceSpan span) {
  SceneObject& o = scene_.objects[index];
  if (const Value* allow = o.FindProperty("allowCollisions")) {
    o.allow_collisions = Truthy(*allow, span);
  }
  if (!o.cls->has_box) o.dimensions.setZero();
  completed_[index] = true;
  CheckCollisions(index);
}

geometry::OrientedBox BoxOfObject(const SceneObject& o) {
  return {o.p_WO, o.R_WO.toRotationMatrix(), o.dimensions / 2};
}

geometry::OrientedBox Interpreter::BoxOf(int index) const {
  return BoxOfObject(scene_.objects[index]);
}

std::string Interpreter::DescribeBox(int index) const {
  const SceneObject& o = scene_.objects[index];
  const Vector3d& p = o.p_WO;
  const Vector3d& d = o.dimensions;
  return o.DisplayName(index) + " (" + FormatNumber(d.x()) + " x " + FormatNumber(d.y()) + " x " +
         FormatNumber(d.z()) + " m at (" + FormatNumber(p.x()) + ", " + FormatNumber(p.y()) + ", " +
         FormatNumber(p.z()) + "))";
}

const geometry::ConvexRegion* Interpreter::Workspace() const {
  const RegionPtr* workspace = FindWorkspace();
  return workspace ? workspace->get() : nullptr;
}

const RegionPtr* Interpreter::FindWorkspace() const {
  const Value* workspace = module_envs_[current_module_].Find("workspace");
  if (!workspace || !workspace->Is<RegionPtr>()) return nullptr;
  return &workspace->As<RegionPtr>();
}

// A workspace bound by a shared module (ModuleEnv::shared), or made by a region call with the
// same arguments in every scene (RunCache::region_calls), is the same region in every scene and
// lives as long as the cache (RunCache::kept_regions): what is worked out from it may be kept.
bool Interpreter::IsWorkspaceKept(const geometry::ConvexRegion& workspace) const {
  return options_.cache && options_.cache->kept_regions.count(&workspace) > 0;
}

// Every object's whole box inside the workspace (spec §6), checked once the program has run.
void Interpreter::CheckWorkspace() {
  current_module_ = program_.main_module;
  const RegionPtr* found = FindWorkspace();
  if (!found) return;
  scene_.workspace = *found;  // kept for drawing
  const geometry::ConvexRegion* workspace = found->get();
  const RejectionKind kind = options_.mode == SamplingMode::kNaive ? RejectionKind::kContainment
                                                                   : RejectionKind::kWorkspace;
  // A kept fixed object found inside a kept workspace once is inside it in every scene.
  const bool workspace_kept = IsWorkspaceKept(*workspace);
  for (int i = 0; i < static_cast<int>(scene_.objects.size()); ++i) {
    const SceneObject& o = scene_.objects[i];
    const bool keep = workspace_kept && o.fixed_id != 0;
    const std::pair<uint64_t, const geometry::ConvexRegion*> key{o.fixed_id, workspace};
    if (keep && options_.cache->fixed_inside_workspace.count(key)) continue;
    const bool inside = o.cls->has_box ? RegionContainsObject(*workspace, i, 1e-9)
                                       : workspace->Contains(o.p_WO);
    if (!inside) Reject(kind, o.DisplayName(i) + " outside the workspace", o.span);
    if (keep) options_.cache->fixed_inside_workspace.insert(key);
  }
}

}  // namespace prs::lang::internal

namespace prs::lang {

const Value* SceneObject::FindProperty(const std::string& property) const {
  for (const auto& [name, value] : properties) {
    if (name == property) return &value;
  }
  return nullptr;
}

std::string SceneObject::DisplayName(int index) const {
  return name ? *name : cls->name + "#" + std::to_string(index);
}

}  // namespace prs::lang
