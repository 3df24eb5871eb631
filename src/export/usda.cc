// USD text (.usda) for Isaac Sim and other USD tools: Z-up, metres, one Xform per object under
// /World with its exact translate and orient, a Cube, Cylinder or Mesh child for its shape, and
// the UsdPhysics schemas (collision on shapes, a mesh's by convex decomposition, which USD
// simulators compute themselves; rigid body and mass on free bodies).
// Written as text: no USD library is packaged for Debian 12.
#include <fmt/format.h>

#include "export/writers.h"

namespace prs::exporting::internal {
namespace {

std::string FormatTuple(const Eigen::Vector3d& v) {
  return fmt::format("({})", FormatVector(v, ", "));
}

// The prim's metadata listing its physics schemas; `indent` is the prim's own indentation.
std::string FormatSchemas(bool rigid_body, bool collides, const std::string& indent,
                          bool mesh = false) {
  std::string schemas;
  if (rigid_body) schemas += "\"PhysicsRigidBodyAPI\", \"PhysicsMassAPI\"";
  if (collides) schemas += std::string(schemas.empty() ? "" : ", ") + "\"PhysicsCollisionAPI\"";
  if (collides && mesh) schemas += ", \"PhysicsMeshCollisionAPI\"";
  if (schemas.empty()) return "";
  return " (\n" + indent + "    prepend apiSchemas = [" + schemas + "]\n" + indent + ")";
}

// A mesh's triangles in the body's frame (bounding box centred, scaled).
void AppendMeshData(const Body& body, std::string& out) {
  const shapes::TriangleMesh& mesh = body.mesh->mesh;
  out += "            int[] faceVertexCounts = [";
  for (size_t i = 0; i < mesh.triangles.size(); ++i) out += i > 0 ? ", 3" : "3";
  out += "]\n            int[] faceVertexIndices = [";
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Eigen::Vector3i& t = mesh.triangles[i];
    fmt::format_to(std::back_inserter(out), "{}{}, {}, {}", i > 0 ? ", " : "", t[0], t[1], t[2]);
  }
  out += "]\n            point3f[] points = [";
  for (size_t i = 0; i < mesh.vertices_O.size(); ++i) {
    out += (i > 0 ? ", " : "") + FormatTuple(mesh.vertices_O[i] * body.mesh_scale);
  }
  out += "]\n            uniform token subdivisionScheme = \"none\"\n";
  if (body.collides) out += "            uniform token physics:approximation = \"convexDecomposition\"\n";
}

// The shape prim; a Cube of size 1 scaled to the box, a Cylinder or Capsule along local z, a
// Sphere, or a Mesh (a file's, or a built-in shape's polytope when it is not round).
void AppendShape(const Body& body, std::string& out) {
  const bool mesh = body.shape == Shape::kMesh;
  const std::string schemas = FormatSchemas(false, body.collides, "        ", mesh);
  if (mesh) {
    fmt::format_to(std::back_inserter(out), "\n        def Mesh \"shape\"{}\n        {{\n", schemas);
    AppendMeshData(body, out);
  } else if (body.shape == Shape::kSphere) {
    fmt::format_to(std::back_inserter(out),
                   "\n        def Sphere \"shape\"{}\n        {{\n            double radius = {}\n",
                   schemas, FormatNumber(body.size.x() / 2));
  } else if (body.shape == Shape::kCapsule) {
    // USD's capsule height is its straight part's.
    fmt::format_to(std::back_inserter(out),
                   "\n        def Capsule \"shape\"{}\n        {{\n"
                   "            uniform token axis = \"Z\"\n"
                   "            double height = {}\n            double radius = {}\n",
                   schemas, FormatNumber(body.size.z() - body.size.x()), FormatNumber(body.size.x() / 2));
  } else if (body.shape == Shape::kCylinder) {
    fmt::format_to(std::back_inserter(out),
                   "\n        def Cylinder \"shape\"{}\n        {{\n"
                   "            uniform token axis = \"Z\"\n"
                   "            double height = {}\n            double radius = {}\n",
                   schemas, FormatNumber(body.size.z()), FormatNumber(body.cylinder_radius()));
  } else {
    fmt::format_to(std::back_inserter(out),
                   "\n        def Cube \"shape\"{}\n        {{\n            double size = 1\n"
                   "            double3 xformOp:scale = {}\n"
                   "            uniform token[] xformOpOrder = [\"xformOp:scale\"]\n",
                   schemas, FormatTuple(body.size));
  }
  fmt::format_to(std::back_inserter(out),
                 "            color3f[] primvars:displayColor = [({}, {}, {})]\n"
                 "            float[] primvars:displayOpacity = [{}]\n        }}\n",
                 FormatNumber(body.color.r), FormatNumber(body.color.g), FormatNumber(body.color.b),
                 FormatNumber(body.color.a));
}

void AppendBody(const Body& body, std::string& out) {
  const Eigen::Quaterniond& R = body.R_WO;
  fmt::format_to(std::back_inserter(out),
                 "\n    def Xform \"{}\"{}\n    {{\n"
                 "        custom string prs:class = \"{}\"\n"
                 "        double3 xformOp:translate = {}\n"
                 "        quatd xformOp:orient = ({}, {}, {}, {})\n"
                 "        uniform token[] xformOpOrder = [\"xformOp:translate\", "
                 "\"xformOp:orient\"]\n",
                 body.name, FormatSchemas(body.is_free(), false, "    "), body.class_name,
                 FormatTuple(body.p_WO), FormatNumber(R.w()), FormatNumber(R.x()),
                 FormatNumber(R.y()), FormatNumber(R.z()));
  if (body.is_free()) {
    fmt::format_to(std::back_inserter(out),
                   "        float physics:mass = {}\n        float3 physics:diagonalInertia = {}\n",
                   FormatNumber(body.mass_kg), FormatTuple(body.inertia_diag));
  }
  if (body.shape != Shape::kNone) AppendShape(body, out);
  out += "    }\n";
}

}  // namespace

std::string WriteUsda(const ExportScene& scene) {
  std::string out = fmt::format(
      "#usda 1.0\n(\n    defaultPrim = \"World\"\n"
      "    doc = \"ProbRobScene scene {}\"\n    metersPerUnit = 1\n    upAxis = \"Z\"\n)\n\n"
      "def Xform \"World\"\n{{\n"
      "    def PhysicsScene \"physics\"\n    {{\n"
      "        vector3f physics:gravityDirection = (0, 0, -1)\n"
      "        float physics:gravityMagnitude = {}\n    }}\n"
      "\n    def Cube \"ground\" (\n        prepend apiSchemas = [\"PhysicsCollisionAPI\"]\n    )\n"
      "    {{\n        double size = 1\n        double3 xformOp:translate = (0, 0, {})\n"
      "        double3 xformOp:scale = ({}, {}, {})\n"
      "        uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:scale\"]\n"
      "        color3f[] primvars:displayColor = [(0.9, 0.9, 0.9)]\n    }}\n",
      scene.title, FormatNumber(kGravity), FormatNumber(-kGroundThickness / 2),
      FormatNumber(2 * kGroundHalfWidth), FormatNumber(2 * kGroundHalfWidth),
      FormatNumber(kGroundThickness));
  for (const Body& body : scene.bodies) AppendBody(body, out);
  out += "}\n";
  return out;
}

}  // namespace prs::exporting::internal
