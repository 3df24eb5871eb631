// Rendering end to end on the software EGL context: size, content, where a known object lands,
// camera depth against geometry, grids, PNG files, and view/size parsing.
#include "render/render.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <filesystem>

#include "shapes/mesh.h"
#include "shapes/test/test_meshes.h"

namespace prs::render {
namespace {

RenderObject MakeBox(const std::string& name, const Eigen::Vector3d& p_WO,
                     const Eigen::Vector3d& dimensions, const Rgba& color) {
  RenderObject o;
  o.name = name;
  o.class_name = name;
  o.p_WO = p_WO;
  o.dimensions = dimensions;
  o.color = color;
  return o;
}

// A grey table top (2 x 1.2 x 0.1 m, top at z = 0.5) with a red cube off its centre.
RenderScene MakeTableScene() {
  RenderScene scene;
  scene.objects.push_back(MakeBox("table", {0, 0, 0.45}, {2, 1.2, 0.1}, {0.5f, 0.5f, 0.5f, 1}));
  scene.objects.push_back(
      MakeBox("cube", {0.6, 0.3, 0.55}, {0.1, 0.1, 0.1}, {0.9f, 0.05f, 0.05f, 1}));
  return scene;
}

// A camera 2 m above the floor looking straight down (+y onto -z: -90 degrees about x).
RenderObject MakeDownCamera() {
  RenderObject camera = MakeBox("cam", {0.1, -0.1, 2.0}, {0.05, 0.05, 0.05}, {0.2f, 0.2f, 0.2f, 1});
  camera.shape = ObjectShape::kCamera;
  camera.R_WO = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX());
  return camera;
}

RenderScene MakeTableSceneWithCamera() {
  RenderScene scene = MakeTableScene();
  scene.objects.push_back(MakeDownCamera());
  return scene;
}

Renderer& SharedRenderer() {
  static Renderer renderer;  // one EGL context for the whole test program
  return renderer;
}

// Pixel (column, row from the top) where a world point appears under `pose`.
Eigen::Vector2d Project(const Eigen::Vector3d& p_W, const CameraPose& pose,
                        const RenderOptions& options) {
  const Eigen::Vector3d q = p_W - pose.p_WC;
  const Eigen::Vector3d right_W = pose.forward_W.cross(pose.up_W);
  const double depth = q.dot(pose.forward_W);
  const double tan_y = std::tan(options.camera_fovy_deg * M_PI / 360.0);
  const double tan_x = tan_y * options.width / options.height;
  const double x_ndc = q.dot(right_W) / (depth * tan_x);
  const double y_ndc = q.dot(pose.up_W) / (depth * tan_y);
  return {(x_ndc + 1) / 2 * options.width, (1 - y_ndc) / 2 * options.height};
}

std::array<int, 3> PixelAt(const Image& image, int column, int row) {
  const uint8_t* p = &image.rgb[(size_t(row) * image.width + column) * 3];
  return {p[0], p[1], p[2]};
}

bool IsRed(const std::array<int, 3>& rgb) { return rgb[0] > 120 && rgb[1] < 60 && rgb[2] < 60; }

// The red cube's centre (top face at z = 0.6) is red in the picture, in its upper right
// quadrant: views from above show world +x to the right and +y upwards.
void ExpectCubeRedAndUpRight(const Image& image, const CameraPose& pose,
                             const RenderOptions& options) {
  const Eigen::Vector2d at = Project({0.6, 0.3, 0.6}, pose, options);
  EXPECT_TRUE(IsRed(PixelAt(image, int(at.x()), int(at.y()))));
  EXPECT_GT(at.x(), options.width / 2.0);
  EXPECT_LT(at.y(), options.height / 2.0);
}

// Mean brightness (0..255) of the columns [x0, x1) of a picture.
double MeanBrightness(const Image& image, int x0, int x1) {
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) sum += image.rgb[(size_t(y) * image.width + x) * 3 + c];
  return sum / (3.0 * image.height * (x1 - x0));
}

// A light object: a spotlight at p_W shining along `dir_W` (its local +y).
RenderObject MakeLight(const Eigen::Vector3d& p_W, const Eigen::Vector3d& dir_W, double intensity) {
  RenderObject light;
  light.name = light.class_name = "Light";
  light.shape = ObjectShape::kLight;
  light.p_WO = p_W;
  light.R_WO = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), dir_W);
  light.color = {1, 1, 1, 1};
  light.light.intensity = intensity;
  light.light.cutoff_deg = 25;
  return light;
}

TEST(RenderTest, LightObjectsReplaceTheSunAndLightWhereTheyPoint) {
  RenderOptions options;
  options.width = 200;
  options.height = 150;
  options.view = ParseView("camera:cam");
  options.decorations = false;
  RenderScene base = MakeTableSceneWithCamera();
  // Spotlights 1.5 m above the table, aimed at its left (-x) or right (+x) half.
  const auto lit = [&](double x, double intensity) {
    RenderScene scene = base;
    scene.objects.push_back(MakeLight({x, -0.1, 2.0}, {0, 0, -1}, intensity));
    return SharedRenderer().Render(scene, options);
  };
  const Image left = lit(-0.5, 1.0), right = lit(0.5, 1.0), dim = lit(-0.5, 0.2);
  // Looking down with +x to the right: the lit half is the brighter one.
  EXPECT_GT(MeanBrightness(left, 0, 100), MeanBrightness(left, 100, 200) + 20);
  EXPECT_GT(MeanBrightness(right, 100, 200), MeanBrightness(right, 0, 100) + 20);
  EXPECT_LT(MeanBrightness(dim, 0, 100), MeanBrightness(left, 0, 100) - 20);
  // The light is not drawn, and it changes nothing the segmentation sees.
  RenderScene with_light = base;
  with_light.objects.push_back(MakeLight({-0.5, -0.1, 2.0}, {0, 0, -1}, 1.0));
  const LabelledPicture a = SharedRenderer().RenderLabelled(base, options, {0, 1});
  const LabelledPicture b = SharedRenderer().RenderLabelled(with_light, options, {0, 1});
  EXPECT_EQ(a.visible.object, b.visible.object);
  EXPECT_EQ(a.silhouettes, b.silhouettes);
}

TEST(RenderTest, ImageHasTheRequestedSizeAndIsNotBlank) {
  RenderOptions options;
  options.width = 320;
  options.height = 200;
  const Image image = SharedRenderer().Render(MakeTableScene(), options);
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 200);
  ASSERT_EQ(image.rgb.size(), 320u * 200u * 3u);
  int darkest = 255, brightest = 0;
  for (uint8_t v : image.rgb) {
    darkest = std::min<int>(darkest, v);
    brightest = std::max<int>(brightest, v);
  }
  EXPECT_GT(brightest - darkest, 100);
}

TEST(RenderTest, RedCubeSeenFromTopAppearsAtItsProjectedCentre) {
  RenderOptions options;
  options.view = ParseView("top");
  const RenderScene scene = MakeTableScene();
  const Image image = SharedRenderer().Render(scene, options);
  const CameraPose pose = CalcViewPose(scene, options);
  ExpectCubeRedAndUpRight(image, pose, options);
  // And nowhere near the opposite corner of the table.
  const Eigen::Vector2d away = Project({-0.6, -0.3, 0.5}, pose, options);
  EXPECT_FALSE(IsRed(PixelAt(image, int(away.x()), int(away.y()))));
}

// A red ring (a square frame 0.4 m across with a 0.2 m hole) lying on the table, its hole
// over the table's centre: as a mesh the hole shows the grey table, as a box it is red.
TEST(RenderTest, AMeshIsDrawnAsItsShapeNotItsBox) {
  const auto ring = shapes::LoadMeshShape(shapes::testing::RingObj(0.4, 0.1, 0.05), "ring.obj",
                                          "ring.obj");
  RenderScene scene = MakeTableScene();
  RenderObject& frame = scene.objects.emplace_back(
      MakeBox("ring", {0, 0, 0.525}, {0.4, 0.4, 0.05}, {0.9f, 0.05f, 0.05f, 1}));
  frame.R_WO = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX());  // the hole along z
  frame.dimensions = {0.4, 0.05, 0.4};  // the ring's own axes: its bounding box
  RenderOptions options;
  options.view = ParseView("top");
  const CameraPose pose = CalcViewPose(scene, options);
  const Eigen::Vector2d hole = Project({0, 0, 0.55}, pose, options);
  const Eigen::Vector2d bar = Project({0.15, 0, 0.55}, pose, options);

  const Image as_box = SharedRenderer().Render(scene, options);
  EXPECT_TRUE(IsRed(PixelAt(as_box, int(hole.x()), int(hole.y()))));
  frame.mesh = ring;
  frame.shape = ObjectShape::kMesh;
  const Image as_mesh = SharedRenderer().Render(scene, options);
  EXPECT_FALSE(IsRed(PixelAt(as_mesh, int(hole.x()), int(hole.y()))));
  EXPECT_TRUE(IsRed(PixelAt(as_mesh, int(bar.x()), int(bar.y()))));
  // The renderer goes back to boxes-only scenes without trouble.
  const RenderScene boxes = MakeTableScene();
  ExpectCubeRedAndUpRight(SharedRenderer().Render(boxes, options), CalcViewPose(boxes, options),
                          options);
}

// Built-in shapes in a 0.3 m box seen from the top: the box's corner shows the grey table for a
// sphere, a cylinder and a capsule (round in plan), the centre their red; a box is red at both.
TEST(RenderTest, BuiltInShapesAreDrawnRoundNotAsTheirBox) {
  RenderScene scene = MakeTableScene();
  RenderObject& ball = scene.objects.emplace_back(
      MakeBox("ball", {-0.4, -0.2, 0.65}, {0.3, 0.3, 0.3}, {0.9f, 0.05f, 0.05f, 1}));
  RenderOptions options;
  options.view = ParseView("top");
  const CameraPose pose = CalcViewPose(scene, options);
  const Eigen::Vector2d centre = Project({-0.4, -0.2, 0.8}, pose, options);
  const Eigen::Vector2d corner = Project({-0.4 + 0.14, -0.2 + 0.14, 0.8}, pose, options);
  EXPECT_TRUE(IsRed(PixelAt(SharedRenderer().Render(scene, options), int(corner.x()), int(corner.y()))));
  for (ObjectShape shape : {ObjectShape::kSphere, ObjectShape::kCylinder, ObjectShape::kCapsule}) {
    ball.shape = shape;
    const Image image = SharedRenderer().Render(scene, options);
    const auto at_centre = PixelAt(image, int(centre.x()), int(centre.y()));
    EXPECT_TRUE(IsRed(at_centre)) << int(shape) << ": " << at_centre[0] << " " << at_centre[1] << " " << at_centre[2];
    EXPECT_FALSE(IsRed(PixelAt(image, int(corner.x()), int(corner.y())))) << int(shape);
  }
}

TEST(RenderTest, RegionOutlinesAreDrawnInTheirColours) {
  // A 0.6 m square outline on the table top, left of the cube: green where its edge is, and
  // the table's grey there without it. A view outline is orange.
  RenderOptions options;
  options.view = ParseView("top");
  RenderScene scene = MakeTableScene();
  const Image plain = SharedRenderer().Render(scene, options);
  RegionOutline square{"position of c", false, {}};
  const Eigen::Vector3d corners[4] = {{-0.8, -0.3, 0.5}, {-0.2, -0.3, 0.5}, {-0.2, 0.3, 0.5}, {-0.8, 0.3, 0.5}};
  for (int i = 0; i < 4; ++i) square.edges.emplace_back(corners[i], corners[(i + 1) % 4]);
  scene.regions.push_back(square);
  const Image drawn = SharedRenderer().Render(scene, options);
  const CameraPose pose = CalcViewPose(scene, options);
  const Eigen::Vector2d edge = Project({-0.5, 0.3, 0.5}, pose, options);  // middle of the top edge
  auto is_green = [](const std::array<int, 3>& c) { return c[1] > 120 && c[1] > c[0] + 40 && c[1] > c[2] + 40; };
  bool green = false;
  for (int dy = -2; dy <= 2; ++dy) green = green || is_green(PixelAt(drawn, int(edge.x()), int(edge.y()) + dy));
  EXPECT_TRUE(green);
  EXPECT_FALSE(is_green(PixelAt(plain, int(edge.x()), int(edge.y()))));
  scene.regions.back().is_view = true;
  const Image view = SharedRenderer().Render(scene, options);
  bool orange = false;
  for (int dy = -2; dy <= 2; ++dy) {
    const auto c = PixelAt(view, int(edge.x()), int(edge.y()) + dy);
    orange = orange || (c[0] > 150 && c[1] > 60 && c[2] < 80 && c[0] > c[1] + 40);
  }
  EXPECT_TRUE(orange);
}

TEST(RenderTest, CameraDepthAtTheCentreIsTheDistanceToTheSurfaceBelow) {
  const RenderScene scene = MakeTableSceneWithCamera();
  RenderOptions options;
  options.view = ParseView("camera:cam");
  DepthImage depth;
  const Image image = SharedRenderer().Render(scene, options, &depth);
  ASSERT_EQ(depth.width, options.width);
  ASSERT_EQ(depth.depth_m.size(), size_t(options.width) * options.height);
  const float centre_m =
      depth.depth_m[size_t(options.height / 2) * options.width + options.width / 2];
  EXPECT_NEAR(centre_m, 2.0 - 0.5, 0.01);  // the table top
  // The cube's top (z = 0.6) where the cube's centre projects, and red there.
  const CameraPose pose = CalcViewPose(scene, options);
  const Eigen::Vector2d at = Project({0.6, 0.3, 0.6}, pose, options);
  ASSERT_GT(at.x(), 0);
  ASSERT_LT(at.y(), options.height);
  EXPECT_NEAR(depth.depth_m[size_t(at.y()) * options.width + size_t(at.x())], 2.0 - 0.6, 0.01);
  // The camera sees +x to the right and +y (its up axis) upwards.
  ExpectCubeRedAndUpRight(image, pose, options);
}

TEST(RenderTest, ACameraViewOpensAtTheCamerasOwnFieldOfView) {
  // The same camera with fovy_deg 60: the cube's top lands where a 60° pinhole puts it
  // (about 60 px from where 45° would), red there and not at the 45° pixel.
  RenderScene scene = MakeTableSceneWithCamera();
  scene.objects.back().fovy_deg = 60;
  RenderOptions options;
  options.view = ParseView("camera:cam");
  const Image image = SharedRenderer().Render(scene, options);
  const CameraPose pose = CalcViewPose(scene, options);
  RenderOptions at_60 = options, at_45 = options;
  at_60.camera_fovy_deg = 60;
  at_45.camera_fovy_deg = 45;
  const Eigen::Vector2d seen = Project({0.6, 0.3, 0.6}, pose, at_60);
  const Eigen::Vector2d not_seen = Project({0.6, 0.3, 0.6}, pose, at_45);
  ASSERT_GT((seen - not_seen).norm(), 40);
  EXPECT_TRUE(IsRed(PixelAt(image, int(seen.x()), int(seen.y()))));
  EXPECT_FALSE(IsRed(PixelAt(image, int(not_seen.x()), int(not_seen.y()))));
}

TEST(RenderTest, UnknownCameraNameListsTheCameras) {
  const RenderScene scene = MakeTableSceneWithCamera();
  RenderOptions options;
  options.view = ParseView("camera:nope");
  try {
    SharedRenderer().Render(scene, options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'nope'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("camera objects: cam"), std::string::npos) << e.what();
  }
}

TEST(RenderTest, SizeChangesBetweenRenders) {
  RenderOptions small;
  small.width = 64;
  small.height = 48;
  EXPECT_EQ(SharedRenderer().Render(MakeTableScene(), small).rgb.size(), 64u * 48u * 3u);
  RenderOptions large;
  large.width = 800;
  large.height = 600;
  EXPECT_EQ(SharedRenderer().Render(MakeTableScene(), large).width, 800);
}

Image MakeSolidTile(int width, int height, uint8_t value) {
  return Image{width, height, std::vector<uint8_t>(size_t(width) * height * 3, value)};
}

TEST(RenderTest, GridLaysTilesOutRowByRow) {
  EXPECT_EQ(CalcGridShape(9), std::make_pair(3, 3));
  EXPECT_EQ(CalcGridShape(5), std::make_pair(3, 2));
  EXPECT_EQ(CalcGridShape(1), std::make_pair(1, 1));
  std::vector<Image> tiles;
  for (int i = 0; i < 5; ++i) tiles.push_back(MakeSolidTile(20, 10, uint8_t(10 * i)));
  const Image grid = ComposeGrid(tiles);
  const int g = kGridGutter;
  EXPECT_EQ(grid.width, 60 + 2 * g);
  EXPECT_EQ(grid.height, 20 + g);
  EXPECT_EQ(PixelAt(grid, 45 + 2 * g, 5)[0], 20);        // tile 2: first row, third column
  EXPECT_EQ(PixelAt(grid, 25 + g, 15 + g)[0], 40);       // tile 4: second row, second column
  EXPECT_EQ(PixelAt(grid, 20, 5)[0], 255);               // the gutter after tile 0
  EXPECT_EQ(PixelAt(grid, 55 + 2 * g, 15 + g)[0], 255);  // the empty cell stays white
  tiles.push_back(MakeSolidTile(21, 10, 0));
  EXPECT_THROW(ComposeGrid(tiles), std::invalid_argument);
}

TEST(RenderTest, PngFilesReadBackWithTheirSize) {
  const std::string path = ::testing::TempDir() + "/prs_render_test.png";
  WritePng(MakeSolidTile(30, 20, 7), path);
  png_image read{};
  read.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&read, path.c_str())) << read.message;
  EXPECT_EQ(read.width, 30u);
  EXPECT_EQ(read.height, 20u);
  png_image_free(&read);
  std::filesystem::remove(path);
  EXPECT_THROW(WritePng(MakeSolidTile(4, 4, 0), "/nonexistent-dir/x.png"), std::runtime_error);
}

TEST(RenderTest, ParsesViewsAndSizes) {
  EXPECT_EQ(ParseView("front").kind, ViewKind::kFront);
  EXPECT_EQ(ParseView("camera:Camera#5").camera_name, "Camera#5");
  EXPECT_THROW(ParseView("side"), std::invalid_argument);
  EXPECT_THROW(ParseView("camera:"), std::invalid_argument);
  EXPECT_EQ(ParseSize("640x480"), std::make_pair(640, 480));
  EXPECT_THROW(ParseSize("640"), std::invalid_argument);
  EXPECT_THROW(ParseSize("640x480x2"), std::invalid_argument);
  EXPECT_THROW(ParseSize("8x8"), std::invalid_argument);
}

}  // namespace
}  // namespace prs::render
