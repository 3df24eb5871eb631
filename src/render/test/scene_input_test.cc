// Scenes to RenderScene: JSON lines, sampled scenes with their workspace, outline edges.
#include "render/scene_input.h"

#include <gtest/gtest.h>

#include "lang/lang.h"
#include "sampling/sampler.h"

namespace prs::render {
namespace {

constexpr char kJsonScene[] =
    R"({"format":"prs-scene/1","seed":0,"index":0,"objects":[)"
    R"({"name":"cup","class":"Cup","position":[1,2,3],)"
    R"("orientation":{"quaternion":[1,0,0,0]},"dimensions":[0.1,0.1,0.2],)"
    R"("properties":{"color":"red","shape_type":"cylinder"}},)"
    R"({"name":null,"class":"Camera","position":[0,0,2],)"
    R"("orientation":{"quaternion":[0.7071068,-0.7071068,0,0]},"dimensions":[0.05,0.05,0.05],)"
    R"("properties":{"color":[0,255,0]}}]})";

TEST(SceneInputTest, ReadsJsonObjectsShapesAndColours) {
  std::vector<std::string> unknown;
  const RenderScene scene = ParseRenderSceneJson(kJsonScene, &unknown);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].name, "cup");
  EXPECT_EQ(scene.objects[0].shape, ObjectShape::kCylinder);
  EXPECT_TRUE(scene.objects[0].p_WO.isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_GT(scene.objects[0].color[0], 0.7f);
  EXPECT_EQ(scene.objects[1].name, "Camera#1");
  EXPECT_EQ(scene.objects[1].shape, ObjectShape::kCamera);
  EXPECT_FLOAT_EQ(scene.objects[1].color[1], 1.0f);
  EXPECT_TRUE(unknown.empty());
}

// A built-in shape as `prs sample` records it ({"primitive": NAME}) is drawn as that shape,
// whatever `shape_type` says; an unknown name leaves the box.
TEST(SceneInputTest, BuiltInShapesAreReadFromTheirRecord) {
  auto object = [](const std::string& shape) {
    return R"({"name":"o","class":"O","position":[0,0,0],"orientation":{"quaternion":[1,0,0,0]},)"
           R"("dimensions":[0.1,0.1,0.2],"properties":{"shape_type":"cylinder","shape":)" + shape + "}}";
  };
  const std::string json = R"({"format":"prs-scene/1","objects":[)" + object(R"({"primitive":"sphere"})") +
                           "," + object(R"({"primitive":"capsule"})") + "," +
                           object(R"({"primitive":"cone"})") + "]}";
  const RenderScene scene = ParseRenderSceneJson(json, nullptr);
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].shape, ObjectShape::kSphere);
  EXPECT_EQ(scene.objects[1].shape, ObjectShape::kCapsule);
  EXPECT_EQ(scene.objects[2].shape, ObjectShape::kCylinder);  // its shape_type
}

TEST(SceneInputTest, ACamerasFieldOfViewComesFromItsProperties) {
  // From a scenes-file line: fovy_deg and aspect are read, and values no program could
  // compile with keep the defaults.
  const auto camera_of = [](const std::string& properties) {
    const std::string line =
        R"({"format":"prs-scene/1","objects":[{"name":"cam","class":"Camera","position":[0,0,2],)"
        R"("orientation":{"quaternion":[1,0,0,0]},"dimensions":[0.05,0.05,0.05],"properties":)" +
        properties + "}]}";
    return ParseRenderSceneJson(line, nullptr).objects.at(0);
  };
  EXPECT_DOUBLE_EQ(camera_of(R"({"fovy_deg":58,"aspect":1.5})").fovy_deg, 58);
  EXPECT_DOUBLE_EQ(camera_of(R"({"fovy_deg":58,"aspect":1.5})").aspect, 1.5);
  EXPECT_DOUBLE_EQ(camera_of(R"({})").fovy_deg, 45);
  EXPECT_DOUBLE_EQ(camera_of(R"({"fovy_deg":190,"aspect":-1})").fovy_deg, 45);
  EXPECT_DOUBLE_EQ(camera_of(R"({"fovy_deg":190,"aspect":-1})").aspect, 4.0 / 3.0);
  EXPECT_DOUBLE_EQ(camera_of(R"({"fovy_deg":"wide"})").fovy_deg, 45);
  // And from a sampled scene, as the language read them.
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileText("c.prs",
                                   "class Camera:\n    fovy_deg: 30\n    aspect: 2\n"
                                   "c = Camera at Vector3D(0, 0, 1)\n",
                                   {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  const RenderScene scene = MakeRenderScene(sampling::SampleScene(*program, 1, 0).scene, nullptr);
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].shape, ObjectShape::kCamera);
  EXPECT_DOUBLE_EQ(scene.objects[0].fovy_deg, 30);
  EXPECT_DOUBLE_EQ(scene.objects[0].aspect, 2);
}

TEST(SceneInputTest, JsonErrorsSayWhere) {
  EXPECT_THROW(ParseRenderSceneJson("{not json", nullptr), std::invalid_argument);
  EXPECT_THROW(ParseRenderSceneJson(R"({"objects":[]})", nullptr), std::invalid_argument);
  try {
    ParseRenderSceneJson(R"({"format":"prs-scene/1","objects":[{"position":[1,2]}]})", nullptr);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("object 0: 'position'"), std::string::npos) << e.what();
  }
}

TEST(SceneInputTest, SampledSceneKeepsItsWorkspaceOutline) {
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileText("w.prs",
                                   "workspace = Cuboid(Vector3D(0, 0, 1), Vector3D(0, 0, 0), 4, "
                                   "3, 2)\nclass Box:\n    color: \"nocolour\"\nb = Box at "
                                   "Vector3D(0, 0, 1)\n",
                                   {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  const sampling::SampledScene sampled = sampling::SampleScene(*program, 1, 0);
  std::vector<std::string> unknown;
  const RenderScene scene = MakeRenderScene(sampled.scene, &unknown);
  ASSERT_EQ(scene.workspace_edges.size(), 12u);
  double total_m = 0;
  for (const auto& [a, b] : scene.workspace_edges) total_m += (b - a).norm();
  EXPECT_NEAR(total_m, 4 * (4 + 3 + 2), 1e-9);
  ASSERT_EQ(unknown.size(), 1u);
  EXPECT_NE(unknown[0].find("nocolour"), std::string::npos);
}

TEST(SceneInputTest, RecordedRegionsBecomeOutlines) {
  // With record_regions, the cube's region (the rectangle it may sit on) and the camera's view
  // become outlines; without it, none.
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileText(
      "r.prs",
      "class Board:\n    width: 1\n    length: 0.5\n    height: 0.1\nclass Cube:\n    width: 0.1\n"
      "    length: 0.1\n    height: 0.1\nb = Board at Vector3D(0, 0, 0.05)\n"
      "cam = Cube at Vector3D(0, 0, 2), facing Vector3D(0, 0, -1), with allowCollisions True\n"
      "c = Cube on b, in view of cam\n",
      {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  EXPECT_TRUE(MakeRenderScene(sampling::SampleScene(*program, 1, 0).scene).regions.empty());
  sampling::SampleOptions options;
  options.run.record_regions = true;
  const RenderScene scene = MakeRenderScene(sampling::SampleScene(*program, 1, 0, options).scene);
  ASSERT_EQ(scene.regions.size(), 2u);
  EXPECT_EQ(scene.regions[0].what, "view of cam");
  EXPECT_TRUE(scene.regions[0].is_view);
  EXPECT_EQ(scene.regions[0].edges.size(), 12u);  // a frustum: a truncated pyramid
  EXPECT_EQ(scene.regions[1].what, "position of c");
  EXPECT_FALSE(scene.regions[1].is_view);
  double perimeter = 0;
  for (const auto& [a, b] : scene.regions[1].edges) perimeter += (b - a).norm();
  EXPECT_NEAR(perimeter, 2 * (1 + 0.5), 1e-9);  // the board's top (wholly in view)
}

TEST(SceneInputTest, OutlineOfARectangleAndOfUnboundedRegions) {
  const auto rect = geometry::ConvexRegion::MakeRect3D(Eigen::Vector3d::Zero(),
                                                       Eigen::Matrix3d::Identity(), 2, 1);
  EXPECT_EQ(CalcOutlineEdges(rect).size(), 4u);
  EXPECT_TRUE(CalcOutlineEdges(geometry::ConvexRegion::All()).empty());
}

}  // namespace
}  // namespace prs::render
