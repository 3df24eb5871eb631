// Built-in object shapes (spec §10): `Cylinder()`, `Sphere()`, `Capsule()`. Each fills the
// object's box as a mesh's bounding box does (docs/language.md §5): axis along the object's z,
// semi-axes a = width/2, b = length/2 across it, so a width that differs from the length gives
// an elliptic cylinder, an ellipsoid, an elliptic capsule. The sampler places them through a
// convex polytope that circumscribes the true shape (tangent planes, exact bounding box), so
// containment and collisions are conservative by at most kPrimitiveGap of the size, never
// wrong; exports that have the shape natively write the true one (docs/export.md).
//
// Frames and units: `_O` is the object's frame (box centre at the origin), metres.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string_view>

#include "shapes/mesh.h"

namespace prs::shapes {

enum class Primitive { kCylinder, kSphere, kCapsule };

/// "cylinder", "sphere", "capsule": the names scene files record.
const char* PrimitiveName(Primitive kind);
/// The kind a recorded name stands for; nullopt for any other text.
std::optional<Primitive> ParsePrimitive(std::string_view name);

/// The true shape's semi-axes and straight part, from the box size (metres):
/// points p with (x/a)² + (y/b)² + ((z - t)/c)² <= 1 for some t in [-straight, straight].
/// A cylinder has c = 0 and straight = height/2; a sphere c = height/2 and straight = 0; a
/// capsule c = min(a, b, height/2) (round caps) and straight = height/2 - c.
struct PrimitiveAxes {
  double a = 0, b = 0, c = 0, straight = 0;
};
PrimitiveAxes CalcPrimitiveAxes(Primitive kind, const Eigen::Vector3d& size_m);

/// The true shape's support function max over the shape of n · p (n need not be unit).
double CalcPrimitiveSupport(const PrimitiveAxes& axes, const Eigen::Vector3d& n_O);

/// How far the polytope reaches beyond the true shape, as a fraction of its semi-axes: every
/// polytope vertex v has (v_x/a, v_y/b, …) within 1 + kPrimitiveGap of the shape (tested).
inline constexpr double kPrimitiveGap = 0.02;

/// The circumscribed polytope of `kind` filling a box of `size_m` (every entry > 0), as a
/// closed convex MeshShape: `extents` is exactly `size_m`, `hull_O` every vertex, and a
/// cylinder's `supports_O` its top ellipse's inscribed polygon (inside the true top, so
/// objects on it stand on the cylinder); a sphere and a capsule have no flat top. `name`
/// reads "Cylinder()" and so on; `path` is empty. Deterministic: equal inputs, equal output.
std::shared_ptr<MeshShape> MakePrimitiveShape(Primitive kind, const Eigen::Vector3d& size_m);

}  // namespace prs::shapes
