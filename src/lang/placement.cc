// Placement: turns an object's position specifiers into points and exact convex regions
// (spec §5), intersects them with the workspace eroded by the object's box, and samples the
// result uniformly. In naive mode, positions come from the workspace (or from the region of a
// lower-dimensional specifier such as `on`) and every specifier is checked afterwards instead
// (the paper's baseline).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using geometry::ConvexRegion;

namespace {

std::string Format(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

bool IsRelativeSpecifier(SpecifierKind kind) {
  return IsSideSpecifier(kind) || kind == SpecifierKind::kAlignedWith;
}

// The region moved by t (exact: every constraint is shifted).
ConvexRegion TranslateRegion(const ConvexRegion& region, const Vector3d& t) {
  std::vector<geometry::HalfSpace> half_spaces = region.half_spaces();
  for (geometry::HalfSpace& h : half_spaces) h.offset += h.normal.dot(t);
  ConvexRegion result = ConvexRegion::FromHalfSpaces(half_spaces);
  for (const geometry::HalfSpace& h : region.equalities()) {
    const Vector3d p_on_plane = h.normal * h.offset + t;
    result = geometry::Intersect(result, ConvexRegion::MakePlane(p_on_plane, h.normal));
  }
  for (const geometry::Ball& b : region.balls()) {
    result = geometry::Intersect(result, ConvexRegion::MakeSphere(b.p_center + t, b.radius));
  }
  return result;
}

}  // namespace

std::string DescribeSpecifier(const Specifier& s, const SourceManager& sources) {
  const std::string_view text = sources.text(s.span.file).substr(s.span.begin, s.span.end - s.span.begin);
  std::string quoted = "'";  // appended: "'" + std::string(...) draws GCC 12's false -Wrestrict
  quoted += text;
  quoted += '\'';
  return quoted;
}

Vector3d Interpreter::PlacePosition(const ObjectPlan& plan, int index, SourceSpan span) {
  if (const FixedPlacement* cached = CachedPlacement(plan)) {
    RegisterFixedSightChecks(plan, index);  // the tests its skipped specifiers would register
    return SampleFixed(*cached, index, span);
  }
  if (const std::optional<Vector3d> p = PlaceOnMovedRegion(plan, index, span)) return *p;
  if (plan.position_specifiers.empty()) {
    const PropertyDefault* d = plan.cls->FindDefault("position");
    return ToVector(EvalDefault(*d, index), d->expr ? d->expr->span : span, "the default position");
  }
  std::vector<PositionConstraint> constraints;
  for (const Specifier* s : plan.position_specifiers) {
    constraints.push_back(EvalPositionConstraint(*s, index, plan.open_turn));
    if (constraints.back().box_region) {
      open_turn_checks_.push_back({index, s, *constraints.back().box_region});
    }
  }
  if (options_.mode == SamplingMode::kNaive) return SampleNaive(constraints, index, span);
  ConvexRegion region = ConvexRegion::All();
  const ConvexRegion* workspace = plan.fold_workspace ? Workspace() : nullptr;
  if (workspace) {
    ConvexRegion storage = ConvexRegion::All();
    region = ErodeWorkspace(*workspace, index, storage);
  }
  for (const PositionConstraint& c : constraints) {
    if (!c.is_point) region = geometry::Intersect(region, c.region);
  }
  const PositionConstraint* point = nullptr;
  for (const PositionConstraint& c : constraints) {
    if (!c.is_point) continue;
    if (!point) point = &c;  // every other point, and every region, must hold it
    if (!region.Contains(c.p_W, 1e-9) || (c.p_W - point->p_W).norm() > 1e-9) {
      RejectEmptyRegion(RejectionKind::kOutsideRegion,
                        scene_.objects[index].DisplayName(index) + " " +
                            DescribeSpecifier(*c.specifier, program_.sources),
                        c.specifier->span, constraints, workspace, index, span);
    }
  }
  if (point) {
    for (const PositionConstraint& c : constraints) {
      if (!c.pieces || c.pieces->Contains(point->p_W, 1e-9)) continue;
      RejectEmptyRegion(RejectionKind::kOutsideRegion,
                        scene_.objects[index].DisplayName(index) + " " +
                            DescribeSpecifier(*c.specifier, program_.sources),
                        c.specifier->span, constraints, workspace, index, span);
    }
    return point->p_W;
  }
  // Without folding (no box, or an orientation that depends on the position), the centre
  // must still lie in the workspace: bounding the region by it is exact, as the workspace
  // check at the end of the scene rejects every centre outside it anyway.
  if (!workspace && Workspace()) region = geometry::Intersect(region, *Workspace());
  // Specifiers whose regions are unions of pieces: intersected with the rest piece by piece.
  std::optional<geometry::RegionUnion> pieces;
  for (const PositionConstraint& c : constraints) {
    if (!c.pieces) continue;
    pieces = pieces ? geometry::Intersect(*pieces, *c.pieces) : geometry::Intersect(*c.pieces, region);
  }
  if (!pieces) {
    CheckBounded(constraints, region, index, span);
    if (plan.region_fixed) {
      return PlaceFixed(plan, constraints, geometry::RegionUnion::FromConvex(region), index, span);
    }
    return SampleRegion(constraints, region, workspace, index, span);
  }
  if (!pieces->IsBounded()) CheckBounded(constraints, ConvexRegion::All(), index, span);
  if (plan.region_fixed) return PlaceFixed(plan, constraints, *pieces, index, span);
  return SampleUnion(constraints, *pieces, workspace, index, span);
}

void Interpreter::CheckBounded(const std::vector<PositionConstraint>& constraints,
                               const ConvexRegion& region, int index, SourceSpan span) {
  if (region.IsEmpty() || region.IsBounded()) return;
  std::vector<DiagnosticNote> notes;
  for (const PositionConstraint& c : constraints) {
    notes.push_back({c.specifier->span, true, "this specifier's region is " +
                                                  (c.pieces ? c.pieces_description : c.region.Describe())});
  }
  notes.push_back({{}, false, "add a bounded specifier such as 'on', 'completely on' or 'in', "
                              "or bind 'workspace' to a bounded region"});
  Fail(span, "unbounded-region",
       "the position of this " + scene_.objects[index].cls->name +
           " is unbounded: its specifiers leave it free to be arbitrarily far away",
       std::move(notes));
}

Vector3d Interpreter::SampleRegion(const std::vector<PositionConstraint>& constraints,
                                   const ConvexRegion& region, const ConvexRegion* workspace,
                                   int index, SourceSpan span) {
  if (region.IsEmpty()) {
    RejectEmptyRegion(RejectionKind::kEmptyRegion, "no room for " + scene_.objects[index].DisplayName(index),
                      span, constraints, workspace, index, span);
  }
  if (options_.record_regions) RecordRegion(index, "position", {region});
  try {
    return DrawPosition(geometry::RegionSampler(region), index, span);
  } catch (const std::domain_error&) {
    Reject(RejectionKind::kEmptyRegion, "no room for " + scene_.objects[index].DisplayName(index), span);
  }
}

Vector3d Interpreter::SampleUnion(const std::vector<PositionConstraint>& constraints,
                                  const geometry::RegionUnion& region, const ConvexRegion* workspace,
                                  int index, SourceSpan span) {
  if (region.IsEmpty()) {
    RejectEmptyRegion(RejectionKind::kEmptyRegion, "no room for " + scene_.objects[index].DisplayName(index),
                      span, constraints, workspace, index, span);
  }
  if (options_.record_regions) RecordRegion(index, "position", region.piece_set().pieces(), region.X_WL());
  try {
    return DrawUnionPosition(geometry::UnionSampler(region), index, span);
  } catch (const std::domain_error&) {
    Reject(RejectionKind::kEmptyRegion, "no room for " + scene_.objects[index].DisplayName(index), span);
  }
}

PositionConstraint Interpreter::EvalPositionConstraint(const Specifier& s, int index,
                                                       ObjectPlan::OpenTurn open) {
  PositionConstraint c;
  c.specifier = &s;
  switch (s.kind) {
    case SpecifierKind::kWith:
    case SpecifierKind::kAt:
      c.is_point = true;
      c.p_W = EvalVector(*s.target, "the position");
      return c;
    case SpecifierKind::kIn: {
      const Value target = Eval(*s.target);
      if (!target.Is<RegionPtr>()) {
        Fail(s.target->span, "type-error", "'in' needs a region, but this is a " + TypeName(target));
      }
      c.region = *target.As<RegionPtr>();
      return c;
    }
    case SpecifierKind::kOn:
    case SpecifierKind::kCompletelyOn:
      return EvalOnConstraint(s, index, s.kind == SpecifierKind::kCompletelyOn, open);
    case SpecifierKind::kAlignedWith: {
      const Vector3d p = EvalVector(*s.target, "the argument of 'aligned with'");
      const std::string& axis = s.axis ? s.axis->name : "";
      if (axis != "x" && axis != "y" && axis != "z") {
        Fail(s.axis ? s.axis->span : s.span, "bad-specifier",
             "'aligned with' needs an axis: x, y or z");
      }
      c.region = ConvexRegion::MakePlane(p, Vector3d::Unit(axis[0] - 'x'));
      return c;
    }
    case SpecifierKind::kBeyond: {
      const Vector3d p_x = EvalVector(*s.target, "the argument of 'beyond'");
      const Vector3d p_y = EvalVector(*s.from, "the argument of 'from'");
      const Vector3d direction = p_x - p_y;
      if (direction.norm() < 1e-12) {
        Fail(s.span, "bad-value", "'beyond X ... from Y' needs X and Y at different places");
      }
      const Value d = Eval(*s.distance);
      c.is_point = true;
      if (d.Is<Vector3d>()) {
        c.p_W = p_x + geometry::CalcRotationFacing(direction) * d.As<Vector3d>();
      } else {
        c.p_W = p_x + ToNumber(d, s.distance->span, "the distance") * direction.normalized();
      }
      return c;
    }
    case SpecifierKind::kReachableBy:
      return EvalReachableConstraint(s);
    default:
      if (IsViewSpecifier(s.kind)) return EvalViewConstraint(s, index, open);
      return EvalSideConstraint(s, index, open);
  }
}

// The centres where the object's whole box is inside the workspace. A kept workspace eroded by
// one box (size and orientation) is the same in every scene, so it is made once and kept.
const ConvexRegion& Interpreter::ErodeWorkspace(const ConvexRegion& workspace, int index,
                                                ConvexRegion& storage) {
  const geometry::OrientedBox box = BoxOf(index);
  if (!IsWorkspaceKept(workspace))
    return storage = geometry::ErodeByBox(workspace, box.R_WB, box.half_extents);
  RunCache::ErodedKey key{&workspace, {}};  // bit patterns: -0 and 0 stay apart
  std::memcpy(key.second.data(), box.R_WB.data(), 9 * sizeof(double));
  std::memcpy(key.second.data() + 9, box.half_extents.data(), 3 * sizeof(double));
  auto& kept = options_.cache->eroded_workspaces;
  if (auto it = kept.find(key); it != kept.end()) return it->second;
  storage = geometry::ErodeByBox(workspace, box.R_WB, box.half_extents);
  if (kept.size() >= RunCache::kMaxEroded) return storage;
  return kept.emplace(key, storage).first->second;
}

// `on X` / `completely on X`: X's top face (or a planar region) lifted by half the height.
PositionConstraint Interpreter::EvalOnConstraint(const Specifier& s, int index, bool completely,
                                                 ObjectPlan::OpenTurn open) {
  PositionConstraint c;
  c.specifier = &s;
  const SceneObject& self = scene_.objects[index];
  const double half_height = self.dimensions.z() / 2;
  const Value target = Eval(*s.target);
  if (const auto* ref = std::get_if<ObjectRef>(&target.data)) {
    c.target_object = ref->index;
    const SceneObject& x = scene_.objects[ref->index];
    if (x.mesh) {
      SetOnMeshSurfaces(c, index, ref->index, completely, open);
      return c;
    }
    const Matrix3d R_WX = x.R_WO.toRotationMatrix();
    const Vector3d up = R_WX.col(2);
    const Vector3d p_top = x.p_WO + up * (x.dimensions.z() / 2 + half_height);
    c.region = ConvexRegion::MakeRect3D(p_top, R_WX, x.dimensions.x(), x.dimensions.y());
  } else if (const auto* region = std::get_if<RegionPtr>(&target.data)) {
    if ((*region)->dimension() != 2) {
      Fail(s.target->span, "type-error",
           "'" + std::string(SpecifierName(s.kind)) + "' needs an object, a vector or a planar "
           "region (Rect3D, ConvexPolygon3D), but this region is " + (*region)->Describe());
    }
    c.region = TranslateRegion(**region, (*region)->CalcPlaneNormal() * half_height);
  } else {
    c.is_point = true;
    const Vector3d up = target.Is<OrientedPoint>()
                            ? Vector3d(target.As<OrientedPoint>().R_WF.toRotationMatrix().col(2))
                            : Vector3d::UnitZ();
    c.p_W = ToVector(target, s.target->span,
                     "the argument of '" + std::string(SpecifierName(s.kind)) + "'") +
            up * half_height;
    if (completely) {
      Fail(s.span, "bad-specifier", "'completely on' needs an object or a planar region to "
                                    "contain the object's footprint; use 'on' for a point");
    }
    return c;
  }
  if (completely) {
    if (options_.mode == SamplingMode::kNaive) c.naive_domain = c.region;
    c.region = ErodeByOwnShapeOrCore(c.region, index, open, c);
  }
  return c;
}

// left of / right of / ahead of / behind / above / below X [by d]: a half-space beyond the
// plane through X's centre, pushed out by d plus the object's own extent along the normal.
PositionConstraint Interpreter::EvalSideConstraint(const Specifier& s, int index,
                                                   ObjectPlan::OpenTurn open) {
  PositionConstraint c;
  c.specifier = &s;
  const Value target = Eval(*s.target);
  const OrientedPoint frame = ToOrientedPoint(target, s.target->span,
                                              "the argument of '" + std::string(SpecifierName(s.kind)) + "'");
  const Matrix3d R = frame.R_WF.toRotationMatrix();
  Vector3d normal = Vector3d::Zero();
  switch (s.kind) {
    case SpecifierKind::kLeftOf: normal = -R.col(0); break;
    case SpecifierKind::kRightOf: normal = R.col(0); break;
    case SpecifierKind::kAheadOf: normal = R.col(1); break;
    case SpecifierKind::kBehind: normal = -R.col(1); break;
    case SpecifierKind::kAbove: normal = R.col(2); break;
    default: normal = -R.col(2); break;
  }
  const double d = s.distance ? EvalNumber(*s.distance, "the distance after 'by'") : 0.0;
  // The whole box beyond the plane pushed out by d: its centre beyond it by the box's extent
  // (while the orientation is open, by the extent of a round core inside every turn of it).
  double extent = 0;
  if (open == ObjectPlan::OpenTurn::kNone) {
    extent = CalcObjectSupport(index, normal);
  } else {
    c.box_region = ConvexRegion::MakeHalfSpace(frame.p_W + normal * d, normal);
    const RoundCore core = CalcRoundCore(index, open);
    extent = core.radius * (normal - normal.dot(core.axis) * core.axis).norm();
  }
  c.region = ConvexRegion::MakeHalfSpace(frame.p_W + normal * (d + extent), normal);
  return c;
}

ConvexRegion Interpreter::ErodeByOwnShapeOrCore(const ConvexRegion& box_region, int index,
                                        ObjectPlan::OpenTurn open, PositionConstraint& c) {
  if (open == ObjectPlan::OpenTurn::kNone) return ErodeByOwnShape(box_region, index);
  c.box_region = box_region;
  const RoundCore core = CalcRoundCore(index, open);
  return geometry::ErodeByRound(box_region, core.axis, core.radius);
}

RoundCore Interpreter::CalcRoundCore(int index, ObjectPlan::OpenTurn open) {
  const SceneObject& o = scene_.objects[index];
  if (o.mesh) return CalcMeshRoundCore(index, open);
  const Vector3d half_extents = o.dimensions / 2;
  if (open == ObjectPlan::OpenTurn::kAny) return {Vector3d::Zero(), half_extents.minCoeff()};
  // Pitch and roll are known: the largest horizontal disk about the centre inside the tilted
  // box is inside it for every turn about z.
  const Matrix3d R_tilt = CalcKnownTilt(index);
  double radius = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double horizontal = R_tilt.col(i).head<2>().norm();
    if (horizontal > 1e-12) radius = std::min(radius, half_extents[i] / horizontal);
  }
  return {Vector3d::UnitZ(), radius};
}

Matrix3d Interpreter::CalcKnownTilt(int index) {
  const SceneObject& o = scene_.objects[index];
  auto angle = [&](const char* name) {
    return o.cls->FindDefault(name) ? ToNumber(GetProperty(index, name, {}), o.span, name) : 0.0;
  };
  return geometry::CalcRotationFromYawPitchRoll(0, angle("pitch"), angle("roll"));
}

// A mesh's round core: the largest ball (any turn) or horizontal disk (turns about z) about
// the centre of its bounding box inside its convex hull, from the hull's facet planes: a plane
// n · p <= d leaves a disk of radius d / |n's horizontal part| (a ball of radius d) inside it.
// The core need only lie inside the hull, not the mesh: a convex region holds the mesh iff it
// holds the hull, so eroding by the core still gives a superset of the valid centres.
RoundCore Interpreter::CalcMeshRoundCore(int index, ObjectPlan::OpenTurn open) {
  const SceneObject& o = scene_.objects[index];
  const std::vector<shapes::HullPlane>* planes = nullptr;
  std::vector<shapes::HullPlane> computed;
  if (IsShapeCached(o)) {
    auto it = options_.cache->hull_planes.find(o.mesh.get());
    if (it == options_.cache->hull_planes.end())
      it = options_.cache->hull_planes.emplace(o.mesh.get(), shapes::CalcHullPlanes(o.mesh->hull_O)).first;
    planes = &it->second;
  } else {
    computed = shapes::CalcHullPlanes(o.mesh->hull_O);
    planes = &computed;
  }
  const bool any_turn = open == ObjectPlan::OpenTurn::kAny;
  const Matrix3d R_tilt = any_turn ? Matrix3d::Identity() : CalcKnownTilt(index);
  double radius = planes->empty() ? 0 : std::numeric_limits<double>::infinity();
  for (const shapes::HullPlane& plane : *planes) {
    const double d = plane.offset_m * o.mesh_scale;
    const double across = any_turn ? 1.0 : (R_tilt * plane.normal_O).head<2>().norm();
    if (across > 1e-12) radius = std::min(radius, d / across);
  }
  if (!(radius > 0)) {
    // The centre is on or outside the hull (or the mesh is flat): no footprint is common to
    // every turn, so no superset to draw from; said rather than sampled wrongly.
    Fail(o.span, "bad-mesh",
         "this " + o.cls->name + "'s orientation depends on its position (e.g. 'facing "
         "toward') while a specifier needs its footprint, and its mesh's convex hull leaves no "
         "room about the centre of its bounding box (a flat mesh, or a centre outside the "
         "hull), so no footprint is common to every turn; give the orientation directly "
         "(facing V, with yaw θ) or drop 'completely'/the side specifier");
  }
  return {any_turn ? Vector3d(Vector3d::Zero()) : Vector3d(Vector3d::UnitZ()), radius};
}

void Interpreter::CheckOpenTurn(int index) {
  const geometry::OrientedBox box = BoxOf(index);
  for (const OpenTurnCheck& check : open_turn_checks_) {
    if (check.index != index) continue;
    const RejectionKind kind = IsSideSpecifier(check.specifier->kind)
                                   ? RejectionKind::kRelativePosition
                                   : RejectionKind::kContainment;
    const bool naive = options_.mode == SamplingMode::kNaive;
    if (naive && !KeepsNaiveViolation(kind)) continue;  // another violation already counts
    // The exact test now that the orientation is known (a mesh's by its hull).
    if (ErodeByOwnShape(check.box_region, index).Contains(box.p_center, 1e-9)) {
      continue;
    }
    std::string culprit = scene_.objects[index].DisplayName(index) + " " +
                          DescribeSpecifier(*check.specifier, program_.sources);
    const std::string detail = "with the orientation it turned to, " + DescribeBox(index) +
                               " does not fit " +
                               DescribeSpecifier(*check.specifier, program_.sources);
    if (naive) {
      naive_violation_ = Rejection{kind, std::move(culprit), check.specifier->span, detail};
      continue;
    }
    open_turn_checks_.clear();
    Reject(kind, std::move(culprit), check.specifier->span, detail);
  }
  std::erase_if(open_turn_checks_, [&](const OpenTurnCheck& c) { return c.index == index; });
}

Diagnostic Interpreter::ExplainEmptyRegion(const std::vector<PositionConstraint>& constraints,
                                           const ConvexRegion* workspace, int index,
                                           SourceSpan span) {
  const SceneObject& o = scene_.objects[index];
  Diagnostic d;
  d.id = "empty-region";
  d.span = span;
  d.message = "no position satisfies every specifier of this " + o.cls->name;
  for (const PositionConstraint& c : constraints) {
    if (c.pieces && c.pieces->IsEmpty()) {
      d.span = c.specifier->span;
      d.message = DescribeSpecifier(*c.specifier, program_.sources) + " leaves no room for this " +
                  o.cls->name + ": " + c.pieces_description + " is empty";
      return d;
    }
    if (!c.is_point && !c.pieces && c.region.IsEmpty()) {
      d.span = c.specifier->span;
      d.message = DescribeSpecifier(*c.specifier, program_.sources) + " leaves no room for this " +
                  o.cls->name;
      if (c.specifier->kind == SpecifierKind::kCompletelyOn) {
        d.message += DescribeFootprintMismatch(c, o);
        d.notes = {{{}, false, "make the object smaller or the surface larger, or use 'on' to "
                               "allow overhang"}};
      }
      return d;
    }
    std::string kind = c.is_point ? "the point (" + Format(c.p_W.x()) + ", " + Format(c.p_W.y()) +
                                        ", " + Format(c.p_W.z()) + ")"
                       : c.pieces ? c.pieces_description
                                  : c.region.Describe();
    d.notes.push_back({c.specifier->span, true, "this specifier gives " + kind});
  }
  if (workspace) {
    d.notes.push_back({{}, false, "the workspace is " + workspace->Describe() +
                                      ", and the object's whole box must fit inside it"});
  }
  d.notes.push_back({{}, false, "these regions do not overlap; loosen one of them"});
  return d;
}

std::string Interpreter::DescribeFootprintMismatch(const PositionConstraint& c, const SceneObject& o) {
  const Vector3d& dims = o.dimensions;
  std::string text = ": its footprint (" + Format(dims.x()) + " m x " + Format(dims.y()) +
                     " m for its orientation) does not fit on the surface below it";
  if (c.target_object >= 0) {
    const SceneObject& x = scene_.objects[c.target_object];
    text += " (" + x.DisplayName(c.target_object) + "'s top is " + Format(x.dimensions.x()) +
            " m x " + Format(x.dimensions.y()) + " m)";
  }
  return text;
}

void Interpreter::RejectEmptyRegion(RejectionKind kind, std::string culprit, SourceSpan culprit_span,
                                    const std::vector<PositionConstraint>& constraints,
                                    const ConvexRegion* workspace, int index, SourceSpan span) {
  // Explained once per scene: an attempt rejected the same way again only counts.
  if (IsExplained(kind, culprit)) Reject(kind, std::move(culprit), culprit_span);
  Diagnostic why = ExplainEmptyRegion(constraints, workspace, index, span);
  // Before any random draw the failure repeats in every attempt: report it at once.
  if (draws_ == 0) throw ScenarioError(std::move(why));
  std::string detail = why.message;
  for (const DiagnosticNote& note : why.notes) detail += "; " + note.message;
  // An empty region is best pointed at by the specifier that emptied it, when there is one.
  const SourceSpan where = kind == RejectionKind::kEmptyRegion ? why.span : culprit_span;
  Reject(kind, std::move(culprit), where, std::move(detail));
}

Vector3d Interpreter::SampleNaive(const std::vector<PositionConstraint>& constraints, int index,
                                  SourceSpan span) {
  const ConvexRegion* workspace = Workspace();
  if (!workspace || !workspace->IsBounded()) {
    Fail(span, "naive-needs-workspace",
         "naive sampling draws positions from the workspace, but this program has no bounded "
         "'workspace' region");
  }
  Vector3d p = Vector3d::Zero();
  bool have_point = false;
  ConvexRegion domain = *workspace;
  for (const PositionConstraint& c : constraints) {
    if (c.is_point) {
      p = c.p_W;
      have_point = true;
    } else if (c.naive_domain) {
      domain = geometry::Intersect(domain, *c.naive_domain);
    } else if (c.region.dimension() < 3) {
      domain = geometry::Intersect(domain, c.region);
    }
  }
  if (!have_point) {
    if (domain.IsEmpty()) {
      Reject(RejectionKind::kContainment, scene_.objects[index].DisplayName(index) +
                                              " has no room in the workspace", span);
    }
    p = DrawPosition(geometry::RegionSampler(domain), index, span);
  }
  for (const PositionConstraint& c : constraints) {
    if (c.is_point) continue;
    if (c.pieces) {
      if (!KeepsNaiveViolation(RejectionKind::kContainment) || c.pieces->Contains(p, 1e-9)) continue;
      naive_violation_ = Rejection{RejectionKind::kContainment,
                                   scene_.objects[index].DisplayName(index) + " " +
                                       DescribeSpecifier(*c.specifier, program_.sources),
                                   c.specifier->span, ""};
      continue;
    }
    const RejectionKind kind = IsRelativeSpecifier(c.specifier->kind)
                                   ? RejectionKind::kRelativePosition
                                   : RejectionKind::kContainment;
    if (!KeepsNaiveViolation(kind) || c.region.Contains(p, 1e-9)) continue;
    naive_violation_ = Rejection{kind,
                                 scene_.objects[index].DisplayName(index) + " " +
                                     DescribeSpecifier(*c.specifier, program_.sources),
                                 c.specifier->span, ""};
  }
  return p;
}

bool Interpreter::KeepsNaiveViolation(RejectionKind kind) const {
  return !naive_violation_ || (naive_violation_->kind == RejectionKind::kContainment &&
                               kind == RejectionKind::kRelativePosition);
}

}  // namespace prs::lang::internal
