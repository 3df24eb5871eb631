// Triangle meshes of bodies in their own frame (metres): glTF's meshes and a dataset's model
// files (src/dataset) are made here.
#include <cmath>
#include <numbers>

#include "export/export.h"

namespace prs::exporting {
namespace {

constexpr int kCylinderSegments = 32;

// Four vertices per face so that each face has its own normal.
TriangleMesh MakeBoxMesh(const Eigen::Vector3d& size) {
  TriangleMesh mesh;
  const Eigen::Vector3d half = size / 2;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      const Eigen::Vector3d n = sign * Eigen::Vector3d::Unit(axis);
      const Eigen::Vector3d u = Eigen::Vector3d::Unit((axis + 1) % 3);
      const Eigen::Vector3d v = n.cross(u);  // (u, v, n) right-handed: counter-clockwise outside
      const uint32_t first = mesh.vertex_count();
      for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        mesh.AddVertex((n + a * u + b * v).cwiseProduct(half), n);
      }
      for (const uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + i);
    }
  }
  return mesh;
}

void AddCylinderCap(TriangleMesh& mesh, double radius, double z, double sign) {
  const Eigen::Vector3d n(0, 0, sign);
  const uint32_t centre = mesh.vertex_count();
  mesh.AddVertex(Eigen::Vector3d(0, 0, z), n);
  for (int i = 0; i < kCylinderSegments; ++i) {
    const double angle = 2 * std::numbers::pi * i / kCylinderSegments;
    mesh.AddVertex(Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle), z), n);
  }
  for (uint32_t i = 0; i < kCylinderSegments; ++i) {
    const uint32_t a = centre + 1 + i, b = centre + 1 + (i + 1) % kCylinderSegments;
    mesh.indices.insert(mesh.indices.end(), {centre, sign > 0 ? a : b, sign > 0 ? b : a});
  }
}

TriangleMesh MakeCylinderMesh(double radius, double height) {
  TriangleMesh mesh;
  const double h = height / 2;
  for (int i = 0; i <= kCylinderSegments; ++i) {
    const double angle = 2 * std::numbers::pi * i / kCylinderSegments;
    const Eigen::Vector3d n(std::cos(angle), std::sin(angle), 0);
    mesh.AddVertex(radius * n + Eigen::Vector3d(0, 0, -h), n);
    mesh.AddVertex(radius * n + Eigen::Vector3d(0, 0, h), n);
  }
  for (uint32_t i = 0; i < kCylinderSegments; ++i) {
    const uint32_t b0 = 2 * i, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    mesh.indices.insert(mesh.indices.end(), {b0, b1, t1, b0, t1, t0});
  }
  AddCylinderCap(mesh, radius, h, 1);
  AddCylinderCap(mesh, radius, -h, -1);
  return mesh;
}

// The mesh itself, scaled, in the body's frame; three vertices per triangle so that each
// triangle has its own (flat) normal.
TriangleMesh MakeTriangleMesh(const shapes::MeshShape& shape, double scale) {
  TriangleMesh mesh;
  const std::vector<Eigen::Vector3d>& p = shape.mesh.vertices_O;
  for (const Eigen::Vector3i& t : shape.mesh.triangles) {
    const Eigen::Vector3d n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).normalized();
    const uint32_t first = mesh.vertex_count();
    for (int k = 0; k < 3; ++k) mesh.AddVertex(p[t[k]] * scale, n);
    for (const uint32_t i : {0u, 1u, 2u}) mesh.indices.push_back(first + i);
  }
  return mesh;
}

}  // namespace

TriangleMesh MakeBodyTriangles(const Body& body) {
  // A sphere or capsule: its polytope (shapes/primitive.h), like any mesh.
  const bool polytope = body.shape == Shape::kSphere || body.shape == Shape::kCapsule;
  if ((body.shape == Shape::kMesh || polytope) && body.mesh)
    return MakeTriangleMesh(*body.mesh, body.mesh_scale);
  if (body.shape == Shape::kCylinder)
    return MakeCylinderMesh(body.cylinder_radius(), body.size.z());
  if (body.shape == Shape::kNone) return {};
  return MakeBoxMesh(body.size);
}

}  // namespace prs::exporting
