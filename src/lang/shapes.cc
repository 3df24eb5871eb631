// Object shapes in the interpreter (spec §10): `Mesh("file", scale=S)` values, sizes read from
// the mesh, and the places where a mesh replaces the box: containment erodes by its convex
// hull (exact), side specifiers use the hull's extent, collisions test the meshes (FCL)
// where the bounding boxes overlap, and `on` a mesh stands on its upward-facing surfaces. Everything else (sight lines, fixed-obstacle cuts) uses
// the bounding box, which holds the mesh, so it stays valid and is only more cautious.
#include <cmath>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Vector3d;

// Touching is not overlapping (geometry::DoBoxesOverlap's convention): meshes are tested
// shrunk so that no surface point moves by more than this (shapes/collide.h).
constexpr double kMeshTouchingM = 1e-6;

Value Interpreter::CallMesh(const std::vector<Value>& args, const std::vector<SourceSpan>& spans,
                            SourceSpan span) {
  if (!args[0].Is<StringPtr>()) {
    Fail(spans[0], "type-error", "Mesh's first argument is the mesh file's path, a string; got a " +
                                     TypeName(args[0]));
  }
  const std::string& name = *args[0].As<StringPtr>();
  auto it = program_.meshes.find(name);
  if (it == program_.meshes.end()) {
    Fail(spans[0], "bad-mesh",
         "the mesh file '" + name + "' was not read when the program was compiled: give the path "
         "as a string literal, Mesh(\"" + name + "\"), so that it is loaded with the program");
  }
  double scale = 1;
  if (args.size() > 1) {
    scale = ToNumber(args[1], spans[1], "Mesh's scale");
    if (!(scale > 0) || !std::isfinite(scale)) {
      Fail(spans[1], "bad-value", "a mesh's scale multiplies its file's coordinates and must be a "
                                  "finite number > 0, got " + Repr(scale));
    }
  }
  (void)span;
  return MeshRef{it->second.shape, scale};
}

Value Interpreter::SizeFromShape(const PlanStep& step, int index, Value value, SourceSpan value_span) {
  const SceneObject& o = scene_.objects[index];
  const int axis = step.property == "width" ? 0 : step.property == "length" ? 1 : 2;
  const double from_mesh = o.mesh->extents[axis] * o.mesh_scale;
  const bool given = !(step.kind == PlanStepKind::kDefault && !step.default_value->expr);
  if (!given) return from_mesh;
  const double x = ToNumber(value, value_span, "'" + step.property + "'");
  if (std::fabs(x - from_mesh) > 1e-9 * std::max(1.0, from_mesh)) {
    Fail(value_span, "conflicting-size",
         "this " + o.cls->name + "'s " + step.property + " is " + FormatNumber(x) +
             " m, but its mesh '" + o.mesh->name + "' is " + FormatNumber(from_mesh) +
             " m along that axis at scale " + FormatNumber(o.mesh_scale),
         {{{}, false, "a mesh's size comes from its file: drop width, length and height, and "
                      "resize it with Mesh(\"" + o.mesh->name + "\", scale=S)"}});
  }
  return value;
}

void Interpreter::SetPrimitiveMesh(int index) {
  SceneObject& o = scene_.objects[index];
  o.mesh = nullptr;
  o.mesh_scale = 1;
  if (!o.cls->has_box) return;
  for (const char* size : {"width", "length", "height"}) {
    if (!o.FindProperty(size)) return;  // the plan sets sizes after the shape: not yet
  }
  if (!(o.dimensions.minCoeff() > 0)) return;  // flat: its box, which holds it
  const auto key = std::make_tuple(*o.primitive, o.dimensions.x(), o.dimensions.y(), o.dimensions.z());
  if (options_.cache) {
    auto it = options_.cache->primitives.find(key);
    if (it != options_.cache->primitives.end()) {
      o.mesh = it->second;
      return;
    }
  }
  o.mesh = shapes::MakePrimitiveShape(*o.primitive, o.dimensions);
  if (options_.cache && options_.cache->primitives.size() < RunCache::kMaxPrimitives) {
    options_.cache->primitives.emplace(key, o.mesh);
  }
}

bool IsShapeCachedIn(const SceneObject& o, const RunCache* cache) {
  if (!cache) return false;
  if (!o.primitive || !o.mesh) return true;
  auto it = cache->primitives.find(
      std::make_tuple(*o.primitive, o.dimensions.x(), o.dimensions.y(), o.dimensions.z()));
  return it != cache->primitives.end() && it->second == o.mesh;
}

namespace {

std::shared_ptr<const shapes::Collider> ColliderOfObject(const SceneObject& o, RunCache* cache) {
  const auto key = o.mesh ? std::make_tuple(o.mesh.get(), o.mesh_scale, 0.0, 0.0)
                          : std::make_tuple(static_cast<const shapes::MeshShape*>(nullptr),
                                            o.dimensions.x(), o.dimensions.y(), o.dimensions.z());
  const bool cached = IsShapeCachedIn(o, cache);
  if (cached) {
    auto it = cache->colliders.find(key);
    if (it != cache->colliders.end()) return it->second;
  }
  std::shared_ptr<const shapes::Collider> collider =
      o.mesh ? shapes::Collider::MakeMesh(*o.mesh, o.mesh_scale, kMeshTouchingM)
             : shapes::Collider::MakeBox(o.dimensions / 2, kMeshTouchingM);
  if (cached) cache->colliders.emplace(key, collider);
  return collider;
}

}  // namespace

bool DoPlacedObjectsOverlap(const SceneObject& oa, const SceneObject& ob, RunCache* cache) {
  // Objects whose boxes' circumscribed balls are apart cannot meet (a shape lies in its box):
  // most pairs of a scene, decided without building either box.
  const double reach_m = (oa.dimensions.norm() + ob.dimensions.norm()) / 2;
  if ((oa.p_WO - ob.p_WO).squaredNorm() > reach_m * reach_m) return false;
  if (!geometry::DoBoxesOverlap(BoxOfObject(oa), BoxOfObject(ob))) return false;
  if (!oa.mesh && !ob.mesh) return true;
  // FCL fits its bounding volumes through covariance matrices, which overflow for sizes far
  // beyond any scene (and it then prints to stderr): such objects keep the boxes' answer,
  // which holds their shapes, so it is only more cautious.
  constexpr double kMaxMeshCollisionSizeM = 1e6;
  if (std::max(oa.dimensions.maxCoeff(), ob.dimensions.maxCoeff()) > kMaxMeshCollisionSizeM) return true;
  auto pose = [](const SceneObject& o) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = o.R_WO.toRotationMatrix();
    X.translation() = o.p_WO;
    return X;
  };
  return shapes::DoCollidersOverlap(*ColliderOfObject(oa, cache), pose(oa),
                                    *ColliderOfObject(ob, cache), pose(ob));
}

bool Interpreter::IsShapeCached(const SceneObject& o) const {
  return IsShapeCachedIn(o, options_.cache);
}

std::vector<Vector3d> Interpreter::ScaledHull(int index) const {
  const SceneObject& o = scene_.objects[index];
  std::vector<Vector3d> hull;
  if (!o.mesh) return hull;
  hull.reserve(o.mesh->hull_O.size());
  for (const Vector3d& p : o.mesh->hull_O) hull.push_back(p * o.mesh_scale);
  return hull;
}

geometry::ConvexRegion Interpreter::ErodeByOwnShape(const geometry::ConvexRegion& region,
                                                    int index) const {
  const SceneObject& o = scene_.objects[index];
  if (o.mesh) return geometry::ErodeByPoints(region, o.R_WO.toRotationMatrix(), ScaledHull(index));
  const geometry::OrientedBox box = BoxOf(index);
  return geometry::ErodeByBox(region, box.R_WB, box.half_extents);
}

bool Interpreter::RegionContainsObject(const geometry::ConvexRegion& region, int index,
                                       double tolerance) const {
  return ObjectInRegion(region, scene_.objects[index], tolerance);
}

bool ObjectInRegion(const geometry::ConvexRegion& region, const SceneObject& o, double tolerance) {
  if (!o.mesh) return region.ContainsBox(BoxOfObject(o), tolerance);
  const Eigen::Matrix3d R = o.R_WO.toRotationMatrix();
  std::vector<Vector3d> hull_W;
  hull_W.reserve(o.mesh->hull_O.size());
  for (const Vector3d& p : o.mesh->hull_O) hull_W.push_back(o.p_WO + R * (p * o.mesh_scale));
  return region.ContainsAll(hull_W, tolerance);
}

double Interpreter::CalcObjectSupport(int index, const Vector3d& normal) const {
  const SceneObject& o = scene_.objects[index];
  if (!o.mesh) {
    const geometry::OrientedBox box = BoxOf(index);
    return geometry::CalcBoxSupport(box.R_WB, box.half_extents, normal);
  }
  const Vector3d n_O = o.R_WO.toRotationMatrix().transpose() * normal;
  double support = -INFINITY;
  for (const Vector3d& p : o.mesh->hull_O) support = std::max(support, n_O.dot(p) * o.mesh_scale);
  return support;
}

bool Interpreter::DoObjectsOverlap(int a, int b) {
  return DoPlacedObjectsOverlap(scene_.objects[a], scene_.objects[b], options_.cache);
}

void Interpreter::SetOnMeshSurfaces(PositionConstraint& c, int index, int target, bool completely,
                                    ObjectPlan::OpenTurn open) {
  const SceneObject& self = scene_.objects[index];
  const SceneObject& x = scene_.objects[target];
  if (completely && open != ObjectPlan::OpenTurn::kNone) {
    Fail(c.specifier->span, "bad-mesh",
         "'completely on' a mesh-shaped object needs this " + self.cls->name + "'s orientation "
         "before its position, but the orientation depends on the position (e.g. 'facing "
         "toward'); give it directly (facing V, with yaw θ), or use 'on'");
  }
  const double half_height = self.dimensions.z() / 2;
  const Eigen::Matrix3d R_WX = x.R_WO.toRotationMatrix();
  const Eigen::Matrix3d R_XO = R_WX.transpose() * self.R_WO.toRotationMatrix();
  const std::vector<Vector3d> hull = completely ? ScaledHull(index) : std::vector<Vector3d>{};
  std::vector<geometry::ConvexRegion> pieces_X;
  for (const shapes::SupportPolygon& support : x.mesh->supports_O) {
    std::vector<Vector3d> points;
    points.reserve(support.vertices_O.size());
    for (const Vector3d& p : support.vertices_O) points.push_back(p * x.mesh_scale + support.normal_O * half_height);
    geometry::ConvexRegion piece = geometry::ConvexRegion::MakeConvexPolygon3D(points);
    if (completely) {
      piece = self.mesh ? geometry::ErodeByPoints(piece, R_XO, hull)
                        : geometry::ErodeByBox(piece, R_XO, self.dimensions / 2);
      if (piece.IsEmpty()) continue;  // too small for the object's footprint
    }
    pieces_X.push_back(std::move(piece));
  }
  Eigen::Isometry3d X_WX = Eigen::Isometry3d::Identity();
  X_WX.linear() = R_WX;
  X_WX.translation() = x.p_WO;
  c.pieces = geometry::RegionUnion(std::make_shared<const geometry::PieceSet>(std::move(pieces_X)), X_WX);
  if (x.primitive) {  // a cylinder's top, or none: a sphere and a capsule have no flat top
    c.pieces_description = "the top of " + x.DisplayName(target) + " (a " + x.mesh->name +
                           (x.mesh->supports_O.empty() ? ", which has no flat top to stand on)" : ")");
  } else {
    c.pieces_description = "the upward-facing surfaces of " + x.DisplayName(target) + " (its mesh '" +
                           x.mesh->name + "', " + std::to_string(x.mesh->supports_O.size()) + " pieces)";
  }
  if (completely) c.pieces_description += " with room for the whole footprint";
}

}  // namespace prs::lang::internal
