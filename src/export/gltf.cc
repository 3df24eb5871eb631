// glTF 2.0 for viewers, built as a tinygltf model and serialised by tinygltf: a root node that
// turns the scene's Z-up world into glTF's Y-up, and under it one node per object with its exact
// translation and rotation and a triangle mesh of its box, cylinder or mesh shape, coloured by a
// material.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "export/writers.h"

namespace prs::exporting::internal {
namespace {

constexpr int kCylinderSegments = 32;

// A triangle mesh in the object's frame.
struct MeshData {
  std::vector<float> positions;  // x y z per vertex
  std::vector<float> normals;
  std::vector<uint32_t> indices;

  void AddVertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    for (int i = 0; i < 3; ++i) positions.push_back(float(p[i]));
    for (int i = 0; i < 3; ++i) normals.push_back(float(n[i]));
  }
  uint32_t vertex_count() const { return uint32_t(positions.size() / 3); }
};

// Four vertices per face so that each face has its own normal.
MeshData MakeBoxMesh(const Eigen::Vector3d& size) {
  MeshData mesh;
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

void AddCylinderCap(MeshData& mesh, double radius, double z, double sign) {
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

MeshData MakeCylinderMesh(double radius, double height) {
  MeshData mesh;
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

// Appends `data` to the buffer as a new view and returns the view's index.
template <typename T>
int AddBufferView(tinygltf::Model& model, const std::vector<T>& data, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = data.size() * sizeof(T);
  view.target = target;
  buffer.resize(buffer.size() + view.byteLength);
  std::memcpy(buffer.data() + view.byteOffset, data.data(), view.byteLength);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

int AddAccessor(tinygltf::Model& model, int view, int component, int type, size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.componentType = component;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return int(model.accessors.size() - 1);
}

int AddMaterial(tinygltf::Model& model, const Body& body) {
  tinygltf::Material material;
  material.name = body.name;
  material.pbrMetallicRoughness.baseColorFactor = {body.color.r, body.color.g, body.color.b,
                                                   body.color.a};
  material.pbrMetallicRoughness.metallicFactor = 0;
  material.pbrMetallicRoughness.roughnessFactor = 0.8;
  if (body.color.a < 1) material.alphaMode = "BLEND";
  model.materials.push_back(material);
  return int(model.materials.size() - 1);
}

// The mesh itself, scaled, in the body's frame; three vertices per triangle so that each
// triangle has its own (flat) normal.
MeshData MakeTriangleMesh(const shapes::MeshShape& shape, double scale) {
  MeshData mesh;
  const std::vector<Eigen::Vector3d>& p = shape.mesh.vertices_O;
  for (const Eigen::Vector3i& t : shape.mesh.triangles) {
    const Eigen::Vector3d n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).normalized();
    const uint32_t first = mesh.vertex_count();
    for (int k = 0; k < 3; ++k) mesh.AddVertex(p[t[k]] * scale, n);
    for (const uint32_t i : {0u, 1u, 2u}) mesh.indices.push_back(first + i);
  }
  return mesh;
}

int AddMesh(tinygltf::Model& model, const Body& body) {
  // A sphere or capsule: its polytope (shapes/primitive.h), like any mesh.
  const bool polytope = body.shape == Shape::kSphere || body.shape == Shape::kCapsule;
  const MeshData data = body.shape == Shape::kMesh || polytope ? MakeTriangleMesh(*body.mesh, body.mesh_scale)
                        : body.shape == Shape::kCylinder
                            ? MakeCylinderMesh(body.cylinder_radius(), body.size.z())
                            : MakeBoxMesh(body.size);
  const size_t n = data.vertex_count();
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  const int position =
      AddAccessor(model, AddBufferView(model, data.positions, TINYGLTF_TARGET_ARRAY_BUFFER),
                  TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  // The spec requires bounds on positions: those of the float vertices themselves.
  std::vector<double> low(3, HUGE_VAL), high(3, -HUGE_VAL);
  for (size_t i = 0; i < data.positions.size(); ++i) {
    low[i % 3] = std::min(low[i % 3], double(data.positions[i]));
    high[i % 3] = std::max(high[i % 3], double(data.positions[i]));
  }
  model.accessors[position].minValues = low;
  model.accessors[position].maxValues = high;
  primitive.attributes["POSITION"] = position;
  primitive.attributes["NORMAL"] =
      AddAccessor(model, AddBufferView(model, data.normals, TINYGLTF_TARGET_ARRAY_BUFFER),
                  TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  primitive.indices =
      AddAccessor(model, AddBufferView(model, data.indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, data.indices.size());
  primitive.material = AddMaterial(model, body);
  tinygltf::Mesh mesh;
  mesh.name = body.name;
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  return int(model.meshes.size() - 1);
}

tinygltf::Value MakeExtras(const Body& body) {
  tinygltf::Value::Object extras;
  extras["class"] = tinygltf::Value(body.class_name);
  extras["static"] = tinygltf::Value(!body.is_free());
  extras["mass_kg"] = tinygltf::Value(body.mass_kg);
  return tinygltf::Value(extras);
}

int AddBodyNode(tinygltf::Model& model, const Body& body) {
  tinygltf::Node node;
  node.name = body.name;
  node.translation = {body.p_WO.x(), body.p_WO.y(), body.p_WO.z()};
  node.rotation = {body.R_WO.x(), body.R_WO.y(), body.R_WO.z(), body.R_WO.w()};
  if (body.shape != Shape::kNone) node.mesh = AddMesh(model, body);
  node.extras = MakeExtras(body);
  model.nodes.push_back(node);
  return int(model.nodes.size() - 1);
}

tinygltf::Model MakeModel(const ExportScene& scene) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "ProbRobScene prs export";
  model.buffers.resize(1);
  tinygltf::Node root;
  root.name = "prs_scene";
  // The scene is Z-up, glTF Y-up: a quarter turn about x maps world +z onto glTF +y.
  root.rotation = {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)};
  model.nodes.push_back(root);
  for (const Body& body : scene.bodies) {
    const int child = AddBodyNode(model, body);
    model.nodes[0].children.push_back(child);
  }
  tinygltf::Scene gltf_scene;
  gltf_scene.name = scene.title;
  gltf_scene.nodes = {0};
  model.scenes.push_back(gltf_scene);
  if (model.buffers[0].data.empty()) model.buffers.clear();  // glTF forbids empty buffers
  model.defaultScene = 0;
  return model;
}

}  // namespace

std::string WriteGltf(const ExportScene& scene, bool binary) {
  const tinygltf::Model model = MakeModel(scene);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/true, binary))
    throw std::runtime_error("tinygltf could not serialise the scene");
  return out.str();
}

}  // namespace prs::exporting::internal
