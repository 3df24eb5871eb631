// USD text checked by structure (no USD library is packaged for Debian 12): the layer header,
// balanced brackets outside strings, and per object one Xform whose translate, orient, shape
// and physics schemas read back to the scene's values.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>

#include "export/test/example_scenes.h"

namespace prs::exporting {
namespace {

using testing_scenes::ExampleScenes;
using testing_scenes::SameRotation;
using testing_scenes::SameVector;

::testing::AssertionResult IsBalanced(const std::string& text) {
  std::string open;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') in_string = !in_string;
    if (in_string) continue;
    if (c == '(' || c == '[' || c == '{') open += c;
    if (c == ')' || c == ']' || c == '}') {
      const char expected = c == ')' ? '(' : c == ']' ? '[' : '{';
      if (open.empty() || open.back() != expected)
        return ::testing::AssertionFailure() << "unbalanced '" << c << "' at offset " << i;
      open.pop_back();
    }
  }
  if (in_string) return ::testing::AssertionFailure() << "unterminated string";
  if (!open.empty()) return ::testing::AssertionFailure() << "unclosed '" << open << "'";
  return ::testing::AssertionSuccess();
}

// The text of the prim `def TYPE "NAME"`, from its def to its closing brace; "" if absent, and
// a failure if there are several.
std::string FindPrim(const std::string& text, const std::string& type, const std::string& name) {
  const std::string def = "def " + type + " \"" + name + "\"";
  const size_t begin = text.find(def);
  if (begin == std::string::npos) return "";
  EXPECT_EQ(text.find(def, begin + 1), std::string::npos) << "two prims " << name;
  size_t depth = 0, i = text.find('{', begin);
  for (; i < text.size(); ++i) {
    depth += text[i] == '{';
    if (text[i] == '}' && --depth == 0) break;
  }
  return text.substr(begin, i + 1 - begin);
}

// The numbers of `ATTRIBUTE = (a, b, ...)` in `prim`.
std::vector<double> ReadTuple(const std::string& prim, const std::string& attribute) {
  const std::regex pattern(attribute + " = \\(([^)]*)\\)");
  std::smatch match;
  if (!std::regex_search(prim, match, pattern)) return {};
  std::vector<double> numbers;
  std::stringstream items(match[1].str());
  for (std::string item; std::getline(items, item, ',');) numbers.push_back(std::stod(item));
  return numbers;
}

// The number of `ATTRIBUTE = x` in `prim`; NaN when it has none.
double ReadScalar(const std::string& prim, const std::string& attribute) {
  const std::regex pattern(attribute + " = ([-+0-9.eE]+)");
  std::smatch match;
  return std::regex_search(prim, match, pattern) ? std::stod(match[1].str()) : std::nan("");
}

// The numbers of `ATTRIBUTE = [...]` in `prim`, tuples flattened: "[(1, 2, 3), (4, 5, 6)]"
// gives 1, ..., 6.
std::vector<double> ReadArray(const std::string& prim, const std::string& attribute) {
  // By hand: std::regex recurses per character and overflows on a mesh's long arrays.
  const size_t at = prim.find(attribute + " = [");
  if (at == std::string::npos) return {};
  const size_t begin = at + attribute.size() + 4, end = prim.find(']', begin);
  std::string items = prim.substr(begin, end - begin);
  for (char& c : items) c = (c == '(' || c == ')') ? ' ' : c;
  std::vector<double> numbers;
  std::stringstream stream(items);
  for (std::string item; std::getline(stream, item, ',');) numbers.push_back(std::stod(item));
  return numbers;
}

// A mesh's prim carries its triangles, in the body's frame: their bounding box is the body's.
void ExpectMeshPrim(const std::string& prim, const Body& body) {
  const std::string mesh = FindPrim(prim, "Mesh", "shape");
  ASSERT_FALSE(mesh.empty()) << body.name;
  const std::vector<double> counts = ReadArray(mesh, "int[] faceVertexCounts");
  const std::vector<double> indices = ReadArray(mesh, "int[] faceVertexIndices");
  const std::vector<double> points = ReadArray(mesh, "point3f[] points");
  ASSERT_EQ(counts.size(), body.mesh->mesh.triangles.size()) << body.name;
  ASSERT_EQ(indices.size(), 3 * counts.size()) << body.name;
  ASSERT_EQ(points.size(), 3 * body.mesh->mesh.vertices_O.size()) << body.name;
  for (double index : indices) EXPECT_LT(index, double(points.size() / 3));
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (size_t i = 0; i < points.size(); i += 3) {
    const Eigen::Vector3d p(points[i], points[i + 1], points[i + 2]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  EXPECT_TRUE(SameVector(hi, body.size / 2)) << body.name;
  EXPECT_TRUE(SameVector(lo, -body.size / 2)) << body.name;
  EXPECT_EQ(mesh.find("physics:approximation = \"convexDecomposition\"") != std::string::npos,
            body.collides) << body.name;
}

void ExpectPrimAsInScene(const std::string& text, const Body& body, const std::string& label) {
  const std::string prim = FindPrim(text, "Xform", body.name);
  ASSERT_FALSE(prim.empty()) << label << ": no Xform " << body.name;
  const std::vector<double> p = ReadTuple(prim, "double3 xformOp:translate");
  const std::vector<double> q = ReadTuple(prim, "quatd xformOp:orient");
  ASSERT_EQ(p.size(), 3u) << body.name;
  ASSERT_EQ(q.size(), 4u) << body.name;
  EXPECT_TRUE(SameVector({p[0], p[1], p[2]}, body.p_WO, 0)) << label << " " << body.name;
  EXPECT_TRUE(SameRotation(Eigen::Quaterniond(q[0], q[1], q[2], q[3]), body.R_WO));
  EXPECT_NE(prim.find("xformOpOrder = [\"xformOp:translate\", \"xformOp:orient\"]"),
            std::string::npos);
  EXPECT_EQ(prim.find("PhysicsRigidBodyAPI") != std::string::npos, body.is_free()) << body.name;
  EXPECT_EQ(prim.find("PhysicsCollisionAPI") != std::string::npos, body.collides) << body.name;
  if (body.shape == Shape::kMesh) ExpectMeshPrim(prim, body);
  if (body.shape == Shape::kSphere) {
    const std::string sphere = FindPrim(prim, "Sphere", "shape");
    ASSERT_FALSE(sphere.empty()) << body.name;
    EXPECT_NEAR(ReadScalar(sphere, "double radius"), body.size.x() / 2, 1e-15) << body.name;
  }
  if (body.shape == Shape::kCapsule) {
    const std::string capsule = FindPrim(prim, "Capsule", "shape");
    ASSERT_FALSE(capsule.empty()) << body.name;
    EXPECT_NE(capsule.find("uniform token axis = \"Z\""), std::string::npos) << body.name;
    EXPECT_NEAR(ReadScalar(capsule, "double height"), body.size.z() - body.size.x(), 1e-15) << body.name;
    EXPECT_NEAR(ReadScalar(capsule, "double radius"), body.size.x() / 2, 1e-15) << body.name;
  }
  if (body.shape == Shape::kBox) {
    const std::string cube = FindPrim(prim, "Cube", "shape");
    const std::vector<double> scale = ReadTuple(cube, "double3 xformOp:scale");
    ASSERT_EQ(scale.size(), 3u) << body.name;
    EXPECT_TRUE(SameVector({scale[0], scale[1], scale[2]}, body.size, 0)) << body.name;
  }
  if (body.shape == Shape::kCylinder) {
    EXPECT_FALSE(FindPrim(prim, "Cylinder", "shape").empty()) << body.name;
  }
}

TEST(UsdaTest, EveryExampleSceneIsWellFormedWithExactPoses) {
  ASSERT_FALSE(ExampleScenes().empty());
  for (const auto& example : ExampleScenes()) {
    const std::string text = WriteScene(example.exported, Format::kUsda);
    ASSERT_EQ(text.rfind("#usda 1.0\n", 0), 0u);
    EXPECT_NE(text.find("upAxis = \"Z\""), std::string::npos);
    EXPECT_NE(text.find("metersPerUnit = 1"), std::string::npos);
    EXPECT_TRUE(IsBalanced(text)) << example.label;
    size_t xforms = 0;
    for (size_t at = text.find("def Xform "); at != std::string::npos;
         at = text.find("def Xform ", at + 1)) {
      ++xforms;
    }
    EXPECT_EQ(xforms, example.exported.bodies.size() + 1) << example.label;  // + /World
    for (const Body& body : example.exported.bodies) ExpectPrimAsInScene(text, body, example.label);
  }
}

TEST(UsdaTest, TheBracketCheckCatchesBrokenText) {
  EXPECT_FALSE(IsBalanced("def Xform \"a\" { ( }"));
  EXPECT_FALSE(IsBalanced("def Xform \"a\" {"));
  EXPECT_TRUE(IsBalanced("def Xform \"a{\" { x = [(1, 2)] }"));
}

}  // namespace
}  // namespace prs::exporting
