// Tests of mesh loading: frame convention (bounding box centred), formats, checks (open
// edges, zero-area triangles, units), errors in our words, and convex hulls against brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shapes/mesh.h"
#include "shapes/test/test_meshes.h"

namespace prs::shapes {
namespace {

using testing::BoxObj;

std::string LoadError(const std::string& bytes, const std::string& name) {
  try {
    LoadMeshShape(bytes, name, name);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshTest, ABoxIsCentredOnItsBoundingBoxAndClosed) {
  const auto shape = LoadMeshShape(BoxObj({1, 2, 3}, {1.4, 2.2, 3.1}), "box.obj", "dir/box.obj");
  EXPECT_EQ(shape->name, "box.obj");
  EXPECT_EQ(shape->path, "dir/box.obj");
  EXPECT_TRUE(shape->extents.isApprox(Eigen::Vector3d(0.4, 0.2, 0.1), 1e-12));
  EXPECT_TRUE(shape->p_FileCenter.isApprox(Eigen::Vector3d(1.2, 2.1, 3.05), 1e-12));
  EXPECT_EQ(shape->mesh.vertices_O.size(), 8u);
  EXPECT_EQ(shape->mesh.triangles.size(), 12u);
  EXPECT_EQ(shape->open_edges, 0);
  EXPECT_EQ(shape->degenerate_triangles, 0);
  EXPECT_EQ(shape->hull_O.size(), 8u);
  for (const Eigen::Vector3d& p : shape->mesh.vertices_O) {
    EXPECT_NEAR(std::abs(p.x()), 0.2, 1e-12);
    EXPECT_NEAR(std::abs(p.z()), 0.05, 1e-12);
  }
  EXPECT_TRUE(DescribeMeshWarnings(*shape, 1).empty());
}

// A binary glTF 2.0 file of one triangle: a JSON chunk, then a BIN chunk of nine floats.
std::string MakeTriangleGlb() {
  std::string json =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"accessors":[{"bufferView":0,)"
      R"("componentType":5126,"count":3,"type":"VEC3","max":[1,1,0],"min":[0,0,0]}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36}]})";
  while (json.size() % 4 != 0) json += ' ';
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  auto word = [](uint32_t w) { return std::string(reinterpret_cast<const char*>(&w), 4); };
  const uint32_t length = uint32_t(12 + 8 + json.size() + 8 + sizeof xyz);
  return "glTF" + word(2) + word(length) + word(uint32_t(json.size())) + "JSON" + json +
         word(uint32_t(sizeof xyz)) + std::string("BIN\0", 4) +
         std::string(reinterpret_cast<const char*>(xyz), sizeof xyz);
}

TEST(MeshTest, BinaryGltfLoadsAndLyingLengthsAreRefusedBeforeAssimp) {
  const std::string glb = MakeTriangleGlb();
  EXPECT_EQ(LoadMeshShape(glb, "tri.glb", "tri.glb")->mesh.triangles.size(), 1u);
  // prs_mesh_fuzz's find: a JSON chunk declared 2 GiB long made assimp allocate 2 GiB.
  std::string huge_chunk = glb;
  huge_chunk[12 + 3] = '\x80';
  std::string error = LoadError(huge_chunk, "x.glb");
  EXPECT_NE(error.find("is not a complete binary glTF file: a chunk of 2147483"), std::string::npos)
      << error;
  EXPECT_NE(error.find("runs past the file's end"), std::string::npos) << error;
  error = LoadError(glb.substr(0, glb.size() - 10), "x.glb");
  EXPECT_NE(error.find("declares"), std::string::npos) << error;
  error = LoadError(glb.substr(0, 10), "x.gltf");  // recognised by its content
  EXPECT_NE(error.find("header is cut off"), std::string::npos) << error;
  std::string version3 = glb;
  version3[4] = 3;
  EXPECT_NE(LoadError(version3, "x.glb").find("version 3"), std::string::npos);
}

TEST(MeshTest, ReadsStlAndPlyAsWellAsObj) {
  const std::string stl =
      "solid t\n"
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
      "  endloop\n endfacet\n"
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n   vertex 0 0 2\n"
      "  endloop\n endfacet\n"
      "endsolid t\n";
  const auto from_stl = LoadMeshShape(stl, "t.STL", "t.STL");
  EXPECT_EQ(from_stl->mesh.triangles.size(), 2u);
  EXPECT_TRUE(from_stl->extents.isApprox(Eigen::Vector3d(1, 1, 2)));
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const auto from_ply = LoadMeshShape(ply, "tet.ply", "tet.ply");
  EXPECT_EQ(from_ply->mesh.triangles.size(), 4u);
  EXPECT_EQ(from_ply->open_edges, 0);
  EXPECT_EQ(from_ply->hull_O.size(), 4u);
}

TEST(MeshTest, WarnsAboutOpenSurfacesZeroAreaTrianglesAndUnits) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> t;
  testing::AppendBox({0, 0, 0}, {1, 1, 1}, v, t);
  t.pop_back();                   // a hole: three edges now belong to one triangle
  t.emplace_back(0, 1, 1);        // zero area
  const auto shape = LoadMeshShape(testing::FormatObj(v, t), "open.obj", "open.obj");
  EXPECT_EQ(shape->open_edges, 3);
  EXPECT_EQ(shape->degenerate_triangles, 1);
  EXPECT_EQ(shape->mesh.triangles.size(), 11u);
  const std::vector<std::string> warnings = DescribeMeshWarnings(*shape, 1);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("not closed (3 edges"), std::string::npos);
  EXPECT_NE(warnings[1].find("1 triangles of zero area"), std::string::npos);
  // A 1 m box read as if in millimetres, or scaled as if it were.
  const auto big = DescribeMeshWarnings(*shape, 100);
  EXPECT_NE(big.back().find("scale=0.001"), std::string::npos) << big.back();
  const auto tiny = DescribeMeshWarnings(*shape, 0.001);
  EXPECT_NE(tiny.back().find("only 0.001 m across"), std::string::npos) << tiny.back();
}

TEST(MeshTest, BadFilesGetMessagesInOurWords) {
  EXPECT_NE(LoadError("solid", "mug.fbx").find("not a mesh format ProbRobScene reads (.fbx)"),
            std::string::npos);
  EXPECT_NE(LoadError("x", "mug").find("(no extension)"), std::string::npos);
  EXPECT_EQ(LoadError("", "mug.obj"), "is empty");
  const std::string points = LoadError("v 0 0 0\nv 1 0 0\n", "points.obj");
  EXPECT_TRUE(points.find("has no triangles") != std::string::npos ||
              points.find("cannot be read as a .obj mesh") != std::string::npos) << points;
  EXPECT_NE(LoadError("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "flat.obj").find("zero area"),
            std::string::npos);
  const std::string garbage = LoadError(std::string("\x01\x02\x03 not a model \xff", 18), "x.glb");
  EXPECT_NE(garbage.find("cannot be read as a .glb mesh"), std::string::npos) << garbage;
  const std::string out_of_range = LoadError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "bad.obj");
  EXPECT_FALSE(out_of_range.empty());
}

TEST(MeshTest, AVertexThatIsNotANumberIsNamed) {
  // Joining identical vertices merged the NaN vertex with another one, so the file was said to
  // have "only triangles of zero area".
  const std::string obj =
      "# a tetrahedron\nv 0 0 0\nv 1 0 0\n\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\n"
      "f 2 3 4\n";
  EXPECT_EQ(LoadError(obj, "tet.obj"),
            "has a vertex that is not a number: vertex 3 (counting from 1, as the file's faces "
            "do), line 5: 'v nan 1 0'");
  const std::string infinite = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 inf\nf 1 2 3\nf 1 2 4\n";
  EXPECT_EQ(LoadError(infinite, "tet.obj"),
            "has a vertex that is not a finite number: vertex 4 (counting from 1, as the file's "
            "faces do), line 4: 'v 0 0 inf'");
  const std::string stl =
      "solid t\n"
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
      "  endloop\n endfacet\n"
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex NaN 1 0\n   vertex 0 0 2\n"
      "  endloop\n endfacet\n"
      "endsolid t\n";
  EXPECT_EQ(LoadError(stl, "t.stl"),
            "has a vertex that is not a number: vertex 5 (counting from 1: corner 2 of facet 2), "
            "(nan, 1, 0)");
  // A binary STL: an 80-byte header, a count, and 50 bytes a facet.
  std::string binary(80, ' ');
  const uint32_t facets = 1;
  binary.append(reinterpret_cast<const char*>(&facets), 4);
  const float facet[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, std::nanf("")};
  binary.append(reinterpret_cast<const char*>(facet), sizeof facet);
  binary.append(2, '\0');
  EXPECT_EQ(LoadError(binary, "b.stl"),
            "has a vertex that is not a number: vertex 3 (counting from 1: corner 3 of facet 1), "
            "(0, 1, nan)");
}

// PLY headers are checked before assimp reads the file (its reader loops forever on some
// malformed ones): each malformation is refused, naming the line.
TEST(MeshTest, MalformedPlyHeadersAreRefusedBeforeReading) {
  const std::string good_header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(LoadMeshShape(good_header + body, "t.ply", "t.ply")->mesh.triangles.size(), 1u);
  // The fuzzer's hang: a header cut inside a property line, then other bytes.
  EXPECT_NE(LoadError("ply\nformat ascii 1.0\nelement vertex 4\nproperty floatbglTF", "t.ply")
                .find("no end_header"),
            std::string::npos);
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = good_header + body;
    text.replace(text.find(from), from.size(), to);
    return LoadError(text, "t.ply");
  };
  EXPECT_NE(with("property float y", "property floaty y").find("line 5"), std::string::npos);
  EXPECT_NE(with("element vertex 3", "element vertex three").find("line 3"), std::string::npos);
  EXPECT_NE(with("element vertex 3", "element vertex 3000000").find("more elements than"),
            std::string::npos);
  EXPECT_NE(with("format ascii 1.0", "format text 1.0").find("line 2"), std::string::npos);
  EXPECT_NE(with("ply\n", "plyx\n").find("does not start with \"ply\""), std::string::npos);
  EXPECT_NE(with("property list uchar int", "property list uchar").find("line 8"),
            std::string::npos);
  EXPECT_NE(with("format ascii 1.0\n", "").find("without a format line"), std::string::npos);
  // The fuzzer's abort: a face line assimp misreads ("~3 ...") as a face without vertices.
  std::string misread = good_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  misread.replace(misread.find("element vertex 3"), 16, "element vertex 4");
  misread.replace(misread.find("element face 1"), 14, "element face 4");
  misread += "~3 0 3 2\n3 1 2 3\n";
  misread.insert(misread.find("3 0 1 2"), "0 0 1\n3 0 2 1\n");
  EXPECT_NE(LoadError(misread, "t.ply").find("face without vertices"), std::string::npos)
      << LoadError(misread, "t.ply");
  // The fuzzer's second hang: "end_header" glued to the last property's name.
  EXPECT_NE(with("vertex_indices\nend_header", "verteend_header").find("no end_header line"),
            std::string::npos);
}

// The hull's vertices have the same support function as the whole set, in every direction.
TEST(MeshTest, ConvexHullKeepsTheSupportFunction) {
  std::mt19937 gen(5);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 400; ++i) {
    Eigen::Vector3d p(normal(gen), normal(gen), normal(gen));
    points.push_back(p.normalized() * std::pow(std::uniform_real_distribution<>(0, 1)(gen), 0.3));
  }
  const std::vector<Eigen::Vector3d> hull = CalcConvexHullVertices(points);
  EXPECT_LT(hull.size(), points.size());
  EXPECT_GT(hull.size(), 20u);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d n = Eigen::Vector3d(normal(gen), normal(gen), normal(gen)).normalized();
    double all = -INFINITY, of_hull = -INFINITY;
    for (const auto& p : points) all = std::max(all, n.dot(p));
    for (const auto& p : hull) of_hull = std::max(of_hull, n.dot(p));
    EXPECT_NEAR(all, of_hull, 1e-12);
  }
  // Flat sets are kept whole (qhull needs three dimensions).
  const std::vector<Eigen::Vector3d> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  EXPECT_EQ(CalcConvexHullVertices(square).size(), 5u);
}

}  // namespace
}  // namespace prs::shapes
