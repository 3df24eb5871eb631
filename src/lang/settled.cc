// Requirements on the settled scene: `require settled` statements are recorded as the attempt
// runs, with the names they saw, and evaluated once a simulator has moved the free bodies to
// where they come to rest (--settle), with the workspace check (docs/physics.md).
#include <fmt/format.h>

#include <algorithm>

#include "lang/interp_internal.h"

namespace prs::lang {

std::optional<Rejection> CheckSettledScene(const Scene& settled) {
  return internal::Interpreter::CheckSettled(settled);
}

void MoveObject(SceneObject& o, const Eigen::Vector3d& p_WO, const Eigen::Quaterniond& R_WO) {
  // yaw, pitch and roll turn the object from a base orientation (R_WO = R_base R_local): keep
  // the base, and give them the turn that now leads to R_WO.
  const auto angle = [&](const char* name) {
    const Value* v = o.FindProperty(name);
    return v && v->Is<double>() ? v->As<double>() : 0.0;
  };
  const Eigen::Matrix3d R_local_drawn =
      geometry::CalcRotationFromYawPitchRoll(angle("yaw"), angle("pitch"), angle("roll"));
  const Eigen::Matrix3d R_base = o.R_WO.toRotationMatrix() * R_local_drawn.transpose();
  const Eigen::Vector3d ypr =
      geometry::CalcYawPitchRoll(R_base.transpose() * R_WO.toRotationMatrix());
  o.p_WO = p_WO;
  o.R_WO = R_WO.normalized();
  for (auto& [name, value] : o.properties.Mutable()) {
    if (name == "position") value = Value(p_WO);
    if (name == "orientation") value = Orientation{o.R_WO};
    if (name == "yaw") value = ypr.x();
    if (name == "pitch") value = ypr.y();
    if (name == "roll") value = ypr.z();
  }
  o.fixed = false;  // no longer the same in every scene, nor equal to its template
  o.fixed_id = 0;
  o.template_id = 0;
}

namespace internal {
namespace {

// Soft contacts: a body at rest sinks this far into what it rests on.
constexpr double kSettledTolerance_m = 0.005;

std::string FormatPoint(const Eigen::Vector3d& p) {
  return fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x(), p.y(), p.z());
}

// The names `expr` reads, each once, in the order they appear.
void CollectNames(const Expr& expr, std::vector<std::string>& names) {
  if (const auto* ref = std::get_if<NameRef>(&expr.node)) {
    if (std::find(names.begin(), names.end(), ref->name) == names.end()) {
      names.push_back(ref->name);
    }
  }
  ForEachChild(expr, [&](const Expr& child) { CollectNames(child, names); });
}

}  // namespace

void Interpreter::RecordSettledRequirement(const RequireStmt& node, SourceSpan span) {
  if (current_module_ != program_.main_module) {
    // A module other than the main one may run once for every scene (RunCache::module_globals),
    // so its statements would not be recorded in later scenes.
    Fail(span, "misplaced-statement",
         "'require settled' belongs in the scenario file, not in an imported module");
  }
  SettledRequirement r;
  r.program = &program_;
  r.module = current_module_;
  r.condition = node.condition.get();
  r.span = span;
  Env names = module_envs_[current_module_].Flatten();
  if (locals_) {
    for (const auto& [name, value] : *locals_) names[name] = value;
  }
  r.names = std::make_shared<const Env>(std::move(names));
  scene_.settled_requirements.push_back(std::move(r));
}

std::optional<Rejection> Interpreter::CheckSettledRequirement(const SettledRequirement& r) {
  current_module_ = r.module;
  module_envs_[r.module].own = *r.names;
  current_statement_ = r.span;
  const int64_t draws_before = draws_;
  const LineColumn where = program_.sources.CalcLineColumn(r.span.file, r.span.begin);
  Rejection rejection;
  rejection.kind = RejectionKind::kUnsettled;
  rejection.culprit = "require settled at " + program_.sources.path(r.span.file) + ":" +
                      std::to_string(where.line);
  rejection.span = r.span;
  bool holds = false;
  try {
    holds = Truthy(Eval(*r.condition), r.condition->span);
  } catch (RejectSignal& signal) {
    rejection.detail = signal.rejection.culprit;
    return rejection;
  }
  if (draws_ != draws_before) {
    Fail(r.condition->span, "bad-value",
         "a 'require settled' condition cannot draw a random value (the scene is already made); "
         "draw it before, into a variable");
  }
  if (holds) return std::nullopt;
  // Where the objects it names came to rest, for the message.
  std::vector<std::string> names;
  CollectNames(*r.condition, names);
  std::vector<std::string> places;
  for (const std::string& name : names) {
    const auto it = r.names->find(name);
    if (it == r.names->end() || !it->second.Is<ObjectRef>()) continue;
    const int index = it->second.As<ObjectRef>().index;
    const SceneObject& o = scene_.objects[index];
    places.push_back(o.DisplayName(index) + " rests at " + FormatPoint(o.p_WO));
  }
  rejection.detail = "after settling";
  for (size_t i = 0; i < places.size(); ++i) rejection.detail += (i ? ", " : " ") + places[i];
  return rejection;
}

std::optional<Rejection> Interpreter::CheckSettled(const Scene& settled) {
  if (settled.workspace) {
    for (int i = 0; i < static_cast<int>(settled.objects.size()); ++i) {
      const SceneObject& o = settled.objects[i];
      const bool inside = o.cls->has_box
                              ? ObjectInRegion(*settled.workspace, o, kSettledTolerance_m)
                              : settled.workspace->Contains(o.p_WO, kSettledTolerance_m);
      if (inside) continue;
      Rejection rejection;
      rejection.kind = RejectionKind::kUnsettled;
      rejection.culprit = o.DisplayName(i) + " outside the workspace";
      rejection.span = o.span;
      rejection.detail = o.DisplayName(i) + " came to rest at " + FormatPoint(o.p_WO) +
                         ", outside the workspace";
      return rejection;
    }
  }
  if (settled.settled_requirements.empty()) return std::nullopt;
  geometry::Rng rng(0, 0);  // never drawn from (CheckSettledRequirement)
  const RunOptions options;
  Interpreter checker(*settled.settled_requirements.front().program, rng, options);
  checker.scene_ = settled;
  for (const SettledRequirement& r : settled.settled_requirements) {
    if (std::optional<Rejection> rejection = checker.CheckSettledRequirement(r)) return rejection;
  }
  return std::nullopt;
}

}  // namespace internal
}  // namespace prs::lang
