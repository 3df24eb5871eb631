// Robot- and camera-aware specifiers (spec §10): `reachable by ARM` (the arm's reachable set, a
// union of convex cells placed at the arm's base), `in view of CAMERA` and `completely in view
// of` (the view frustum, an exact convex region, eroded by the object's box for `completely`),
// `not in view of` (the frustum's outside, a union of six pieces), and the line-of-sight tests of
// `visible from`, `completely visible from` and `not visible from`, run once the whole scene
// exists because any object may hide another.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "kinematics/mount.h"
#include "lang/arms.h"
#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Vector3d;
using geometry::ConvexRegion;

namespace {

std::string Format(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

// Why an arm's reachable set can be empty, and what to change.
std::string ExplainEmptyReach(const kinematics::Chain& chain) {
  std::string why =
      "an arm reaches a point when its tool can be put there with the grasp, within the joint "
      "limits (docs/kinematics.md); ";
  if (chain.num_joints() < 3) {
    why += chain.num_joints() == 1 ? "with one movable joint the tool moves on a curve"
                                   : "with two movable joints the tool moves on a surface";
    return why + ", which holds no volume: an arm's chain needs at least three movable joints";
  }
  return why + "check the arm's joint limits, or ask for less: `with grasp \"any\"`, or a "
               "smaller margin or approach";
}

}  // namespace

// ---------------------------------------------------------------------------
// reachable by ARM [with margin M] [with approach D] [with grasp "down"|"side"|"any"]
// ---------------------------------------------------------------------------

PositionConstraint Interpreter::EvalReachableConstraint(const Specifier& s) {
  PositionConstraint c;
  c.specifier = &s;
  const Value target = Eval(*s.target);
  const auto* ref = std::get_if<ObjectRef>(&target.data);
  if (!ref) {
    Fail(s.target->span, "type-error",
         "'reachable by' needs an arm object (a Robot whose class has an 'arm' property), but "
         "this is a " + TypeName(target));
  }
  const SceneObject& arm = scene_.objects[ref->index];
  const std::string arm_name = arm.DisplayName(ref->index);
  auto text_property = [&](const char* name) -> std::string {
    const Value* v = arm.FindProperty(name);
    if (!v) return "";
    if (!v->Is<StringPtr>()) {
      Fail(s.target->span, "type-error", arm_name + "'s '" + name + "' must be a string, but it is a " +
                                             TypeName(*v));
    }
    return *v->As<StringPtr>();
  };
  if (!arm.FindProperty("arm")) {
    Fail(s.target->span, "not-an-arm",
         arm_name + " is a " + arm.cls->name + ", which is not an arm: its class has no 'arm' "
         "property",
         {{{}, false, "give the class `arm: \"panda\"` (the built-in Franka Panda) or "
                      "`arm: \"my_arm.urdf\"` (a URDF file next to the .prs file)"}});
  }
  kinematics::ReachOptions options;
  for (const SpecifierOption& option : s.options) {
    const std::string& name = option.name.name;
    if (name == "grasp") {
      const Value v = Eval(*option.value);
      const std::string grasp = v.Is<StringPtr>() ? *v.As<StringPtr>() : "";
      if (grasp == "down") options.grasp = kinematics::Grasp::kDown;
      else if (grasp == "side") options.grasp = kinematics::Grasp::kSide;
      else if (grasp == "any") options.grasp = kinematics::Grasp::kAny;
      else {
        Fail(option.value->span, "bad-value",
             "the grasp must be \"down\" (the tool pointing down, any turn about it), \"side\" "
             "(pointing horizontally away from the arm's base) or \"any\" (any orientation), not " +
                 Repr(v));
      }
      continue;
    }
    const double x = EvalNumber(*option.value, "the " + name);
    if (!(x >= 0) || !std::isfinite(x)) {
      Fail(option.value->span, "bad-value", "the " + name + " must be a finite distance >= 0 (metres), not " + Repr(x));
    }
    (name == "margin" ? options.margin_m : options.approach_m) = x;
  }
  if (!program_.arms) Fail(s.span, "bad-arm", "this program was compiled without its arms (compile it with lang::CompileFile)");
  std::shared_ptr<const kinematics::Chain> chain;
  std::shared_ptr<const ArmReach> reach;
  try {
    chain = program_.arms->GetChain(text_property("arm"), text_property("arm_base"),
                                    text_property("arm_tool"));
    reach = program_.arms->GetReach(chain, options);
  } catch (const kinematics::KinematicsError& e) {
    Fail(s.span, "bad-arm", arm_name + "'s arm: " + e.what(),
         {{arm.span, true, arm_name + " is created here, with arm \"" + text_property("arm") + "\""}});
  }
  if (reach->cells_Base->size() == 0) {
    // Every attempt would fail on it: say why at once, not after max_attempts empty regions.
    const std::string model = text_property("arm");
    Fail(s.span, "arm-reaches-nothing",
         arm_name + "'s arm \"" + model + "\" reaches nothing: its reachable set (" +
             reach->description + ") is empty, so no position is reachable by " + arm_name,
         {{arm.span, true,
           arm_name + " is created here, with arm \"" + model + "\"" +
               (chain->name != model ? " (" + chain->name + ")" : "")},
          {{}, false, ExplainEmptyReach(*chain)}});
  }
  const Eigen::Isometry3d X_WBase =
      kinematics::CalcArmMount(arm.p_WO, arm.R_WO.toRotationMatrix(), arm.dimensions);
  c.pieces = geometry::RegionUnion(reach->cells_Base, X_WBase);
  c.pieces_description = "the set " + arm_name + " can reach (" + reach->description + ")";
  return c;
}

// ---------------------------------------------------------------------------
// in view of / completely in view of / not in view of / visible from / ... CAMERA
// ---------------------------------------------------------------------------

SightCheck Interpreter::EvalCamera(const Specifier& s, int index) {
  SightCheck view{index, -1, Eigen::Isometry3d::Identity(), {}, &s};
  const Value target = Eval(*s.target);
  const std::string what = "the argument of '" + std::string(SpecifierName(s.kind)) + "'";
  if (const auto* ref = std::get_if<ObjectRef>(&target.data)) {
    const SceneObject& camera = scene_.objects[ref->index];
    view.camera = ref->index;
    view.X_WC = camera::CalcCameraPose(camera.p_WO, camera.R_WO);
    auto number = [&](const char* name, double fallback) {
      const Value* v = camera.FindProperty(name);
      return v ? ToNumber(*v, s.target->span, camera.DisplayName(ref->index) + "'s '" + name + "'")
               : fallback;
    };
    view.intrinsics.fovy_rad = number("fovy_deg", 45.0) * std::numbers::pi / 180;
    view.intrinsics.aspect = number("aspect", view.intrinsics.aspect);
    view.intrinsics.near_m = number("near", view.intrinsics.near_m);
    view.intrinsics.far_m = number("far", view.intrinsics.far_m);
    try {
      camera::CheckIntrinsics(view.intrinsics);
    } catch (const std::invalid_argument& e) {
      Fail(s.target->span, "bad-camera", "camera " + camera.DisplayName(ref->index) + ": " + e.what(),
           {{{}, false, "a camera's view comes from its properties 'fovy_deg' (vertical field of "
                        "view, degrees), 'aspect' (width / height), 'near' and 'far' (metres)"}});
    }
    return view;
  }
  const OrientedPoint frame = ToOrientedPoint(target, s.target->span, what);
  view.X_WC = camera::CalcCameraPose(frame.p_W, frame.R_WF);
  return view;
}

PositionConstraint Interpreter::EvalViewConstraint(const Specifier& s, int index,
                                                   ObjectPlan::OpenTurn open) {
  PositionConstraint c;
  c.specifier = &s;
  const SightCheck view = EvalCamera(s, index);
  const ConvexRegion frustum = camera::CalcViewFrustum(view.X_WC, view.intrinsics);
  if (options_.record_regions && view.camera >= 0) {
    const bool seen = std::any_of(scene_.regions.begin(), scene_.regions.end(), [&](const PlacedRegion& r) {
      return r.object == view.camera && r.what.starts_with("view");
    });
    const ConvexRegion* workspace = Workspace();
    if (!seen) RecordRegion(view.camera, "view", {workspace ? geometry::Intersect(frustum, *workspace) : frustum});
  }
  switch (s.kind) {
    case SpecifierKind::kInViewOf:
    case SpecifierKind::kVisibleFrom:
      c.region = frustum;
      break;
    case SpecifierKind::kCompletelyInViewOf:
    case SpecifierKind::kCompletelyVisibleFrom:
      c.region = ErodeByOwnShapeOrCore(frustum, index, open, c);
      break;
    case SpecifierKind::kNotInViewOf:
      c.pieces = geometry::RegionUnion(std::make_shared<const geometry::PieceSet>(
          camera::CalcOutsideViewPieces(view.X_WC, view.intrinsics)));
      c.pieces_description = "the space outside the view of " + DescribeSpecifier(s, program_.sources);
      break;
    default:  // kNotVisibleFrom: no region, only the line-of-sight test at the end
      break;
  }
  const bool needs_sight = s.kind == SpecifierKind::kVisibleFrom ||
                           s.kind == SpecifierKind::kCompletelyVisibleFrom ||
                           s.kind == SpecifierKind::kNotVisibleFrom;
  if (needs_sight) sight_checks_.push_back(view);
  return c;
}

void Interpreter::RegisterFixedSightChecks(const ObjectPlan& plan, int index) {
  for (const Specifier* s : plan.position_specifiers) {
    const bool needs_sight = s->kind == SpecifierKind::kVisibleFrom ||
                             s->kind == SpecifierKind::kCompletelyVisibleFrom ||
                             s->kind == SpecifierKind::kNotVisibleFrom;
    // The camera of a fixed placement is fixed: evaluating it again draws nothing.
    if (needs_sight) sight_checks_.push_back(EvalCamera(*s, index));
  }
}

void Interpreter::CheckSightLines() {
  for (const SightCheck& check : sight_checks_) {
    const SceneObject& o = scene_.objects[check.index];
    const Vector3d p_eye = check.X_WC.translation();
    const bool not_visible = check.specifier->kind == SpecifierKind::kNotVisibleFrom;
    std::vector<Vector3d> targets{o.p_WO};
    if (check.specifier->kind == SpecifierKind::kCompletelyVisibleFrom && o.cls->has_box) {
      targets = camera::CalcSightTargets(BoxOf(check.index), p_eye);
    }
    // The other objects' boxes that can block a line of sight: only those meeting the lines'
    // bounding box can (in scene order, so the first blocker named does not depend on this).
    Eigen::AlignedBox3d lines(p_eye);
    for (const Vector3d& p_target : targets) lines.extend(p_target);
    std::vector<geometry::OrientedBox> occluders;
    std::vector<int> owners;
    for (int j = 0; j < static_cast<int>(scene_.objects.size()); ++j) {
      const SceneObject& x = scene_.objects[j];
      if (j == check.index || j == check.camera || !x.cls->has_box) continue;
      const geometry::OrientedBox box = BoxOf(j);
      const Vector3d reach = box.R_WB.cwiseAbs() * box.half_extents;
      if (!lines.intersects(Eigen::AlignedBox3d(box.p_center - reach, box.p_center + reach))) continue;
      occluders.push_back(box);
      owners.push_back(j);
    }
    // Names for a rejection's message, made only when one is rejected.
    const auto seen = [&] { return o.DisplayName(check.index); };
    const auto camera_name = [&] {
      return check.camera >= 0 ? scene_.objects[check.camera].DisplayName(check.camera)
                               : DescribeSpecifier(*check.specifier, program_.sources);
    };
    if (not_visible) {
      const bool in_view = camera::CalcViewFrustum(check.X_WC, check.intrinsics).Contains(o.p_WO, 0);
      if (in_view && camera::FindOccluder(p_eye, o.p_WO, occluders) < 0) {
        Reject(RejectionKind::kVisible, seen() + " visible from " + camera_name(),
               check.specifier->span,
               "nothing hides the centre of " + seen() + " from " + camera_name());
      }
      continue;
    }
    for (const Vector3d& p_target : targets) {
      const int blocker = camera::FindOccluder(p_eye, p_target, occluders);
      if (blocker < 0) continue;
      const int j = owners[blocker];
      Reject(RejectionKind::kOccluded,
             seen() + " hidden from " + camera_name() + " by " + scene_.objects[j].DisplayName(j),
             check.specifier->span,
             DescribeBox(j) + " stands between " + camera_name() + " and " +
                 (targets.size() == 1 ? "the centre of " : "a point of ") + seen() + " at (" +
                 Format(p_target.x()) + ", " + Format(p_target.y()) + ", " + Format(p_target.z()) +
                 ")");
    }
  }
}

}  // namespace prs::lang::internal
