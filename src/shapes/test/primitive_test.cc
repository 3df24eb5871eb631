// Tests of the built-in shapes' polytopes (primitive.h): they hold the true shape (every
// tangent plane bounds them, checked on a fine grid of directions), reach beyond it by at most
// kPrimitiveGap, fill the object's box exactly, are closed and convex, and a cylinder's top is
// inside the true top.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "shapes/collide.h"
#include "shapes/primitive.h"

namespace prs::shapes {
namespace {

using Eigen::Vector3d;

// How far v is from the shape in its own gauge: 1 on the surface, > 1 outside.
double CalcGauge(const PrimitiveAxes& axes, const Vector3d& v) {
  const double t = std::clamp(v.z(), -axes.straight, axes.straight);
  const double across = std::hypot(v.x() / axes.a, v.y() / axes.b);
  if (axes.c == 0) return std::max(across, std::fabs(v.z()) / axes.straight);
  return std::hypot(across, (v.z() - t) / axes.c);
}

struct Case {
  Primitive kind;
  Vector3d size;
};

const Case kCases[] = {
    {Primitive::kCylinder, {0.08, 0.08, 0.12}}, {Primitive::kCylinder, {0.3, 0.1, 0.05}},
    {Primitive::kSphere, {0.1, 0.1, 0.1}},      {Primitive::kSphere, {0.4, 0.2, 0.1}},
    {Primitive::kCapsule, {0.05, 0.05, 0.2}},   {Primitive::kCapsule, {0.2, 0.1, 0.06}},
};

TEST(PrimitiveTest, PolytopeHoldsTheShapeAndFitsItsBox) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(PrimitiveName(c.kind) + std::string(" ") + std::to_string(c.size.x()));
    const auto shape = MakePrimitiveShape(c.kind, c.size);
    const PrimitiveAxes axes = CalcPrimitiveAxes(c.kind, c.size);
    EXPECT_EQ(shape->extents, c.size);
    Vector3d lo = Vector3d::Constant(1e9), hi = -lo;
    double worst_gauge = 0;
    for (const Vector3d& v : shape->hull_O) {
      lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
      worst_gauge = std::max(worst_gauge, CalcGauge(axes, v));
    }
    EXPECT_EQ(hi - lo, c.size);  // the box is filled exactly, both sides
    EXPECT_EQ(lo, -c.size / 2);
    EXPECT_LE(worst_gauge, 1 + kPrimitiveGap);
    EXPECT_GT(worst_gauge, 1.0);  // circumscribed: corners stand out
    // The true shape lies inside: in every direction the polytope reaches at least as far.
    for (int i = 0; i < 40; ++i) {
      for (int j = 0; j <= 20; ++j) {
        const double theta = 2 * std::numbers::pi * i / 40, phi = std::numbers::pi * (j / 20.0 - 0.5);
        const Vector3d n(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
        double reach = -1e9;
        for (const Vector3d& v : shape->hull_O) reach = std::max(reach, n.dot(v));
        EXPECT_GE(reach, CalcPrimitiveSupport(axes, n) - 1e-12) << n.transpose();
      }
    }
  }
}

TEST(PrimitiveTest, SurfaceIsClosedAndWoundOutward) {
  for (const Case& c : kCases) {
    const auto shape = MakePrimitiveShape(c.kind, c.size);
    std::map<std::pair<int, int>, int> edges;  // directed edge -> count
    double volume = 0;
    for (const Eigen::Vector3i& t : shape->mesh.triangles) {
      for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
      const auto& p = shape->mesh.vertices_O;
      volume += p[t[0]].dot(p[t[1]].cross(p[t[2]])) / 6;
    }
    for (const auto& [edge, count] : edges) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << "open edge";
    }
    EXPECT_GT(volume, 0);  // outward winding gives a positive volume
    EXPECT_LT(volume, c.size.prod());
  }
}

TEST(PrimitiveTest, OnlyACylinderHasATopAndItIsInsideTheTrueTop) {
  const Vector3d size(0.3, 0.1, 0.05);
  const auto cylinder = MakePrimitiveShape(Primitive::kCylinder, size);
  ASSERT_EQ(cylinder->supports_O.size(), 1u);
  const PrimitiveAxes axes = CalcPrimitiveAxes(Primitive::kCylinder, size);
  for (const Vector3d& v : cylinder->supports_O[0].vertices_O) {
    EXPECT_DOUBLE_EQ(v.z(), 0.025);
    EXPECT_LE(std::hypot(v.x() / axes.a, v.y() / axes.b), 1 + 1e-12);
  }
  EXPECT_NEAR(cylinder->supports_O[0].area, std::numbers::pi * 0.15 * 0.05, 0.01 * 0.15 * 0.05);
  EXPECT_TRUE(MakePrimitiveShape(Primitive::kSphere, size)->supports_O.empty());
  EXPECT_TRUE(MakePrimitiveShape(Primitive::kCapsule, size)->supports_O.empty());
}

TEST(PrimitiveTest, ACapsuleHasRoundCapsAndAStraightPart) {
  const PrimitiveAxes axes = CalcPrimitiveAxes(Primitive::kCapsule, {0.06, 0.06, 0.2});
  EXPECT_DOUBLE_EQ(axes.c, 0.03);
  EXPECT_DOUBLE_EQ(axes.straight, 0.07);
  // Squat: the caps meet, as an ellipsoid.
  const PrimitiveAxes squat = CalcPrimitiveAxes(Primitive::kCapsule, {0.2, 0.2, 0.06});
  EXPECT_DOUBLE_EQ(squat.c, 0.03);
  EXPECT_DOUBLE_EQ(squat.straight, 0);
}

TEST(PrimitiveTest, SpheresSideBySideDoNotCollideWhereTheirBoxesWould) {
  const auto ball = MakePrimitiveShape(Primitive::kSphere, {0.1, 0.1, 0.1});
  const auto collider = Collider::MakeMesh(*ball, 1, 1e-6);
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity(), X_WB = X_WA;
  X_WB.translation() = Vector3d(0.09, 0.09, 0);  // boxes overlap by 1 cm; balls 2.7 cm apart
  EXPECT_FALSE(DoCollidersOverlap(*collider, X_WA, *collider, X_WB));
  X_WB.translation() = Vector3d(0.09, 0, 0);
  EXPECT_TRUE(DoCollidersOverlap(*collider, X_WA, *collider, X_WB));
}

TEST(PrimitiveTest, NamesRoundTrip) {
  for (Primitive kind : {Primitive::kCylinder, Primitive::kSphere, Primitive::kCapsule}) {
    EXPECT_EQ(ParsePrimitive(PrimitiveName(kind)), kind);
  }
  EXPECT_FALSE(ParsePrimitive("cone"));
  EXPECT_FALSE(ParsePrimitive("Cylinder"));
}

}  // namespace
}  // namespace prs::shapes
