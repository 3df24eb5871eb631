// Built-in shapes as circumscribed polytopes (primitive.h). A cylinder's is a prism; the unit
// ball's (scaled for a sphere, stretched for a capsule) is the intersection
// of the true shape's tangent half-spaces n · p <= h(n) for a fixed set of normals n, which
// include ±x, ±y, ±z so that its bounding box is exactly the object's box. Its vertices come
// from the polar: the half-spaces are q · p <= 1 with q = n / h(n), and each facet of the
// convex hull of the q's (qhull), plane m · q = d, is the vertex m / d. A second hull of those
// vertices gives the triangles.
#include "shapes/primitive.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "shapes/hull_planes.h"
#include "shapes/qhull_session.h"
#include "shapes/support.h"

namespace prs::shapes {
namespace {

using Eigen::Vector3d;

constexpr double kPi = std::numbers::pi;
// Around the axis: a multiple of 4, so that ±x and ±y are among the normals. A cylinder's
// side gets 48 faces (its polygon is within 0.22 % of the ellipse); a round surface a grid of
// 24 longitudes by 12 latitude bands (15°), within 1.8 % (kPrimitiveGap; tested).
constexpr int kCylinderSides = 48;
constexpr int kLongitudes = 24;
constexpr int kLatitudeBands = 12;

// A cylinder's polytope directly (the tangent-plane construction below gives the same, but
// through two hulls, and a cylinder's size is often drawn anew in every scene): the prism on
// the polygon whose sides touch the ellipse at angles 2πi/N of the unit circle it is the image
// of, so its corners lie at the angles between, 1/cos(π/N) out. Triangles wound outward: the
// side's quads, and each cap as a fan from its first corner.
void MakeCylinderPrism(const PrimitiveAxes& axes, TriangleMesh& mesh) {
  const int n = kCylinderSides;
  const double out = 1 / std::cos(kPi / n);
  for (const double z : {-axes.straight, axes.straight}) {
    for (int i = 0; i < n; ++i) {
      const double theta = 2 * kPi * (i + 0.5) / n;
      mesh.vertices_O.emplace_back(axes.a * out * std::cos(theta), axes.b * out * std::sin(theta), z);
    }
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    mesh.triangles.emplace_back(i, j, n + j);
    mesh.triangles.emplace_back(i, n + j, n + i);
  }
  for (int i = 1; i + 1 < n; ++i) {
    mesh.triangles.emplace_back(0, i + 1, i);          // bottom, seen from below
    mesh.triangles.emplace_back(n, n + i, n + i + 1);  // top, seen from above
  }
}

// The normals of a round shape's tangent planes, in the object's frame (not unit).
std::vector<Vector3d> MakeNormals(const PrimitiveAxes& axes) {
  std::vector<Vector3d> normals{Vector3d::UnitZ(), -Vector3d::UnitZ()};
  for (int k = 1; k < kLatitudeBands; ++k) {
    const double phi = -kPi / 2 + kPi * k / kLatitudeBands;
    for (int j = 0; j < kLongitudes; ++j) {
      const double theta = 2 * kPi * j / kLongitudes;
      const Vector3d u(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta),
                       std::sin(phi));
      normals.emplace_back(u.x() / axes.a, u.y() / axes.b, u.z() / axes.c);
    }
  }
  return normals;
}

// Points closer than `tolerance` (the polar's facets may repeat a vertex) kept once, sorted.
std::vector<Vector3d> MergeClosePoints(std::vector<Vector3d> points, double tolerance) {
  std::sort(points.begin(), points.end(), [](const Vector3d& p, const Vector3d& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  });
  std::vector<Vector3d> kept;
  for (const Vector3d& p : points) {
    bool seen = false;  // only kept points with x within tolerance can match (sorted by x)
    for (auto q = kept.rbegin(); q != kept.rend() && q->x() >= p.x() - tolerance && !seen; ++q) {
      seen = (p - *q).lpNorm<Eigen::Infinity>() <= tolerance;
    }
    if (!seen) kept.push_back(p);
  }
  return kept;
}

// The convex hull's triangles (qhull, triangulated), wound counter-clockwise seen from outside.
std::vector<Eigen::Vector3i> CalcHullTriangles(const std::vector<Vector3d>& points) {
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Vector3d& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  std::vector<Eigen::Vector3i> triangles;
  internal::RunQhull(3, coordinates, "qhull Qt", [&](qhT* qh) {
    facetT* facet;
    FORALLfacets {
      Eigen::Vector3i t;
      int k = 0;
      vertexT *vertex, **vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k < 3) t[k] = qh_pointid(qh, vertex->point);
        ++k;
      }
      if (k != 3) continue;
      const Vector3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
      const Vector3d winding = (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]);
      if (winding.dot(normal) < 0) std::swap(t[1], t[2]);
      triangles.push_back(t);
    }
  });
  // qhull lists facets in its own order; sorted, the mesh is the same on every platform run.
  std::sort(triangles.begin(), triangles.end(), [](const Eigen::Vector3i& p, const Eigen::Vector3i& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  });
  return triangles;
}

}  // namespace

const char* PrimitiveName(Primitive kind) {
  switch (kind) {
    case Primitive::kCylinder: return "cylinder";
    case Primitive::kSphere: return "sphere";
    case Primitive::kCapsule: return "capsule";
  }
  return "cylinder";
}

std::optional<Primitive> ParsePrimitive(std::string_view name) {
  for (Primitive kind : {Primitive::kCylinder, Primitive::kSphere, Primitive::kCapsule}) {
    if (name == PrimitiveName(kind)) return kind;
  }
  return std::nullopt;
}

PrimitiveAxes CalcPrimitiveAxes(Primitive kind, const Vector3d& size_m) {
  PrimitiveAxes axes;
  axes.a = size_m.x() / 2;
  axes.b = size_m.y() / 2;
  const double half_height = size_m.z() / 2;
  switch (kind) {
    case Primitive::kCylinder: axes.straight = half_height; break;
    case Primitive::kSphere: axes.c = half_height; break;
    case Primitive::kCapsule:
      axes.c = std::min({axes.a, axes.b, half_height});
      axes.straight = half_height - axes.c;
      break;
  }
  return axes;
}

double CalcPrimitiveSupport(const PrimitiveAxes& axes, const Vector3d& n_O) {
  return std::hypot(axes.a * n_O.x(), axes.b * n_O.y(), axes.c * n_O.z()) +
         axes.straight * std::fabs(n_O.z());
}

std::shared_ptr<MeshShape> MakePrimitiveShape(Primitive kind, const Vector3d& size_m) {
  const PrimitiveAxes axes = CalcPrimitiveAxes(kind, size_m);
  auto shape = std::make_shared<MeshShape>();
  const char* names[] = {"Cylinder()", "Sphere()", "Capsule()"};
  shape->name = names[static_cast<int>(kind)];
  if (kind == Primitive::kCylinder) {
    MakeCylinderPrism(axes, shape->mesh);
  } else {
    // The unit ball's polytope, made once. Its normals are the grid's own directions, and
    // those of the ellipsoid (a, b, c) are their images under diag(1/a, 1/b, 1/c), so the
    // ellipsoid's polytope is the unit one scaled by (a, b, c). A capsule's (support h_E(n) +
    // straight |n_z|) is that plus the segment ±straight along z: the unit polytope has an
    // equator band of vertical faces and no vertex at z = 0, so the upper vertices move up and
    // the lower down, and the band's faces stretch (the tests check the result against the
    // true shape).
    static const TriangleMesh unit = [] {
      const PrimitiveAxes ball{1, 1, 1, 0};
      std::vector<Vector3d> polar;
      for (const Vector3d& n : MakeNormals(ball)) polar.push_back(n / CalcPrimitiveSupport(ball, n));
      std::vector<Vector3d> vertices;
      for (const HullPlane& plane : CalcHullPlanes(polar)) vertices.push_back(plane.normal_O / plane.offset_m);
      TriangleMesh mesh;
      mesh.vertices_O = MergeClosePoints(std::move(vertices), 1e-12);
      mesh.triangles = CalcHullTriangles(mesh.vertices_O);
      return mesh;
    }();
    shape->mesh = unit;
    for (Vector3d& v : shape->mesh.vertices_O) {
      v = v.cwiseProduct(Vector3d(axes.a, axes.b, axes.c));
      v.z() += v.z() > 0 ? axes.straight : -axes.straight;
    }
  }
  // Rounding may put a vertex a few ulps outside the box it must fill exactly.
  const Vector3d half = size_m / 2;
  for (Vector3d& v : shape->mesh.vertices_O) v = v.cwiseMax(-half).cwiseMin(half);
  shape->extents = size_m;
  shape->hull_O = shape->mesh.vertices_O;
  if (kind == Primitive::kCylinder) {
    SupportPolygon top;
    for (int i = 0; i < kCylinderSides; ++i) {
      const double theta = 2 * kPi * i / kCylinderSides;
      top.vertices_O.emplace_back(axes.a * std::cos(theta), axes.b * std::sin(theta), half.z());
    }
    top.area = kCylinderSides / 2.0 * std::sin(2 * kPi / kCylinderSides) * axes.a * axes.b;
    shape->supports_O.push_back(std::move(top));
  }
  return shape;
}

}  // namespace prs::shapes
