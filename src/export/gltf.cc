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

int AddMesh(tinygltf::Model& model, const Body& body) {
  const TriangleMesh data = MakeBodyTriangles(body);
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
