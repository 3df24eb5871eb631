// glTF read back by tinygltf, as text (.gltf, buffer embedded) and binary (.glb): the Z-up to
// Y-up root, one node per object with the scene's translation and rotation, and a mesh whose
// vertices span exactly the object's box.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>

#include "export/test/example_scenes.h"

namespace prs::exporting {
namespace {

using testing_scenes::ExampleScenes;
using testing_scenes::SameRotation;
using testing_scenes::SameVector;

tinygltf::Model Load(const std::string& data, bool binary) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                           reinterpret_cast<const unsigned char*>(data.data()),
                                           unsigned(data.size()), "")
             : loader.LoadASCIIFromString(&model, &error, &warning, data.data(),
                                          unsigned(data.size()), "");
  EXPECT_TRUE(ok) << error;
  EXPECT_EQ(warning, "");
  return model;
}

// The values of an accessor (float VEC3 or uint32 SCALAR), read from its buffer view.
template <typename T>
std::vector<T> ReadAccessor(const tinygltf::Model& model, int index, int components) {
  const tinygltf::Accessor& accessor = model.accessors[index];
  const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
  std::vector<T> values(accessor.count * components);
  std::memcpy(values.data(),
              model.buffers[view.buffer].data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(T));
  return values;
}

// The bounding box of the mesh's vertices, read from the buffer (not from the accessor's own
// min and max, which the writer also wrote).
Eigen::Vector3d MeasureMeshHalfSize(const tinygltf::Model& model, int mesh) {
  const auto p =
      ReadAccessor<float>(model, model.meshes[mesh].primitives[0].attributes.at("POSITION"), 3);
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < p.size(); ++i) half[i % 3] = std::max(half[i % 3], double(std::abs(p[i])));
  return half;
}

// Every triangle winds counter-clockwise seen from outside (its normal agrees with its
// vertices' normals), so viewers that cull back faces show the outside. A cylinder's side
// triangles take the sum of their vertices' normals, which points outward too.
void ExpectOutwardTriangles(const tinygltf::Model& model, int mesh, const std::string& name) {
  const tinygltf::Primitive& primitive = model.meshes[mesh].primitives[0];
  const auto p = ReadAccessor<float>(model, primitive.attributes.at("POSITION"), 3);
  const auto n = ReadAccessor<float>(model, primitive.attributes.at("NORMAL"), 3);
  const auto indices = ReadAccessor<uint32_t>(model, primitive.indices, 1);
  auto vertex = [](const std::vector<float>& v, uint32_t i) {
    return Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  };
  ASSERT_EQ(indices.size() % 3, 0u);
  for (size_t t = 0; t < indices.size(); t += 3) {
    const Eigen::Vector3d a = vertex(p, indices[t]), b = vertex(p, indices[t + 1]),
                          c = vertex(p, indices[t + 2]);
    const Eigen::Vector3d normal =
        vertex(n, indices[t]) + vertex(n, indices[t + 1]) + vertex(n, indices[t + 2]);
    EXPECT_GT((b - a).cross(c - a).dot(normal), 0) << name << " triangle " << t / 3;
  }
}

void ExpectNodeAsInScene(const tinygltf::Model& model, const tinygltf::Node& node, const Body& body,
                         const std::string& label) {
  EXPECT_EQ(node.name, body.name);
  ASSERT_EQ(node.translation.size(), 3u) << body.name;
  ASSERT_EQ(node.rotation.size(), 4u) << body.name;
  const auto& t = node.translation;
  const auto& r = node.rotation;  // x y z w
  EXPECT_TRUE(SameVector({t[0], t[1], t[2]}, body.p_WO, 0)) << label << " " << body.name;
  EXPECT_TRUE(SameRotation(Eigen::Quaterniond(r[3], r[0], r[1], r[2]), body.R_WO))
      << label << " " << body.name;
  EXPECT_EQ(node.extras.Get("static").Get<bool>(), !body.is_free());
  if (body.shape == Shape::kNone) return;
  ASSERT_GE(node.mesh, 0) << body.name;
  const Eigen::Vector3d half = MeasureMeshHalfSize(model, node.mesh);
  if (body.shape == Shape::kMesh) {
    // The mesh itself, every triangle, its bounding box the object's (float precision).
    const tinygltf::Primitive& primitive = model.meshes[node.mesh].primitives[0];
    EXPECT_EQ(model.accessors[primitive.indices].count, 3 * body.mesh->mesh.triangles.size());
    EXPECT_TRUE(SameVector(half, body.size / 2, 1e-6)) << body.name;
    return;
  }
  ExpectOutwardTriangles(model, node.mesh, body.name);  // convex shapes: normals point out
  if (body.shape == Shape::kBox) {
    EXPECT_TRUE(SameVector(half, body.size / 2, 1e-6)) << body.name;
  } else {
    EXPECT_NEAR(half.z(), body.size.z() / 2, 1e-6) << body.name;
    EXPECT_NEAR(half.x(), std::min(body.size.x(), body.size.y()) / 2, 1e-6) << body.name;
  }
  const int material = model.meshes[node.mesh].primitives[0].material;
  ASSERT_GE(material, 0);
  EXPECT_DOUBLE_EQ(model.materials[material].pbrMetallicRoughness.baseColorFactor[0], body.color.r);
}

void ExpectSceneAsSampled(const tinygltf::Model& model, const ExportScene& scene,
                          const std::string& label) {
  ASSERT_EQ(model.scenes.size(), 1u);
  ASSERT_EQ(model.scenes[0].nodes.size(), 1u);
  const tinygltf::Node& root = model.nodes[model.scenes[0].nodes[0]];
  // The root turns world +z (up) into glTF +y (up).
  ASSERT_EQ(root.rotation.size(), 4u);
  const Eigen::Quaterniond R(root.rotation[3], root.rotation[0], root.rotation[1],
                             root.rotation[2]);
  EXPECT_TRUE(SameVector(R * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(), 1e-12));
  ASSERT_EQ(root.children.size(), scene.bodies.size()) << label;
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    ExpectNodeAsInScene(model, model.nodes[root.children[i]], scene.bodies[i], label);
}

TEST(GltfTest, TinygltfReadsEveryExampleSceneAsSampled) {
  ASSERT_FALSE(ExampleScenes().empty());
  for (const auto& example : ExampleScenes()) {
    const std::string text = WriteScene(example.exported, Format::kGltf);
    EXPECT_NE(text.find("\"data:application/octet-stream;base64,"), std::string::npos);
    ExpectSceneAsSampled(Load(text, false), example.exported, example.label);
  }
}

TEST(GltfTest, BinaryGlbReadsBackTheSame) {
  const auto& example = ExampleScenes().front();
  const std::string glb = WriteScene(example.exported, Format::kGlb);
  ASSERT_GE(glb.size(), 12u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  ExpectSceneAsSampled(Load(glb, true), example.exported, example.label);
}

TEST(GltfTest, AnEmptySceneIsStillValid) {
  ExportScene scene;
  const tinygltf::Model model = Load(WriteScene(scene, Format::kGltf), false);
  EXPECT_TRUE(model.buffers.empty());
  EXPECT_EQ(model.nodes.size(), 1u);
}

}  // namespace
}  // namespace prs::exporting
