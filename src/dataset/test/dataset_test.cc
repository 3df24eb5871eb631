// The dataset's labels against geometry computed here, independently of the renderer and of
// the writer: a pinhole camera derived in this file from the camera object's pose, box corners
// projected and rays cast at boxes by this file's own code, PNG files read back with libpng,
// COCO's RLE decoded by a decoder written here, and PLY models parsed here.
#include "dataset/dataset.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "lang/lang.h"
#include "sampling/sampler.h"

namespace prs::dataset {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A red crate turned 0.4 rad, a blue lid floating above part of it, and a camera looking down
// from 1.6 m, off centre, turned too (its image axes are not the world's).
constexpr char kProgram[] = R"(
class Camera:
    width: 0.05
    length: 0.05
    height: 0.05
    allowCollisions: True
    fovy_deg: 50
    aspect: 4 / 3
    near: 0.05
    far: 10
class Crate:
    width: 0.3
    length: 0.2
    height: 0.15
    color: "red"
class Lid:
    width: 0.12
    length: 0.12
    height: 0.02
    color: "blue"
c = Crate at V3D(0.1, -0.05, 0.075), with yaw 0.4
l = Lid at V3D(0.16, -0.02, 0.6), with yaw -0.2
cam = Camera at V3D(0.05, 0.02, 1.6), with yaw 0.3, with pitch -1.5707963267948966
)";

std::unique_ptr<lang::CompiledProgram> Compile(const std::string& text) {
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileText("scene.prs", text, lang::CompileOptions{}, diagnostics);
  EXPECT_TRUE(program && !diagnostics.has_errors());
  return program;
}

sampling::SampledScene SampleScene(const lang::CompiledProgram& program, uint64_t index = 0) {
  sampling::SceneSampler sampler(program);
  return sampler.Sample(1, index);
}

const lang::SceneObject& FindObject(const lang::Scene& scene, const std::string& name) {
  for (const lang::SceneObject& o : scene.objects) {
    if (o.name == name) return o;
  }
  throw std::runtime_error("no object " + name);
}

// This file's own pinhole camera for a camera object: it looks along its local +y with its
// local +z up (docs/language.md), and a picture of height H spans its vertical field of view.
struct TestCamera {
  Eigen::Matrix3d R_CW;  // rows: image right, image down, forward
  Eigen::Vector3d p_WC;
  double f, cx, cy;
  int width, height;

  TestCamera(const lang::SceneObject& camera, double fovy_deg, int w, int h) : width(w), height(h) {
    const Eigen::Matrix3d R_WO = camera.R_WO.toRotationMatrix();
    const Eigen::Vector3d forward = R_WO.col(1), up = R_WO.col(2);
    R_CW.row(0) = forward.cross(up);
    R_CW.row(1) = -up;
    R_CW.row(2) = forward;
    p_WC = camera.p_WO;
    f = h / 2.0 / std::tan(fovy_deg * M_PI / 360);
    cx = w / 2.0 - 0.5;  // pixel centres at whole numbers
    cy = h / 2.0 - 0.5;
  }
  Eigen::Vector3d ToCamera(const Eigen::Vector3d& p_W) const { return R_CW * (p_W - p_WC); }
  Eigen::Vector2d Project(const Eigen::Vector3d& p_W) const {
    const Eigen::Vector3d q = ToCamera(p_W);
    return {f * q.x() / q.z() + cx, f * q.y() / q.z() + cy};
  }
  // The ray through pixel (u, v), in world coordinates (not normalised).
  Eigen::Vector3d Ray(double u, double v) const {
    return R_CW.transpose() * Eigen::Vector3d((u - cx) / f, (v - cy) / f, 1);
  }
};

std::vector<Eigen::Vector3d> BoxCorners(const lang::SceneObject& o) {
  std::vector<Eigen::Vector3d> corners;
  const Eigen::Matrix3d R = o.R_WO.toRotationMatrix();
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d s(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    corners.push_back(o.p_WO + R * s.cwiseProduct(o.dimensions));
  }
  return corners;
}

// The convex hull of 2D points (Andrew's monotone chain), counter-clockwise.
std::vector<Eigen::Vector2d> Hull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

// Signed distance (pixels) from q to the hull's boundary, negative inside.
double DistanceToHull(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& q) {
  double inside = -HUGE_VAL;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a = hull[i], b = hull[(i + 1) % hull.size()];
    const Eigen::Vector2d edge = (b - a).normalized();
    const Eigen::Vector2d outward(edge.y(), -edge.x());  // counter-clockwise hull
    inside = std::max(inside, (q - a).dot(outward));
  }
  return inside;
}

// The ray's entry distance into a box (slab method), or nullopt.
std::optional<double> HitBox(const lang::SceneObject& o, const Eigen::Vector3d& from,
                             const Eigen::Vector3d& ray) {
  const Eigen::Matrix3d R = o.R_WO.toRotationMatrix();
  const Eigen::Vector3d p = R.transpose() * (from - o.p_WO), d = R.transpose() * ray;
  double t0 = 0, t1 = HUGE_VAL;
  for (int k = 0; k < 3; ++k) {
    const double half = o.dimensions[k] / 2;
    if (std::abs(d[k]) < 1e-15) {
      if (std::abs(p[k]) > half) return std::nullopt;
      continue;
    }
    double a = (-half - p[k]) / d[k], b = (half - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (t0 > t1) return std::nullopt;
  return t0;
}

// PNG files read back with libpng's simplified API: 8-bit grey, 16-bit grey or RGB.
std::vector<uint16_t> ReadPng(const fs::path& path, png_uint_32 format, int* width = nullptr,
                              int* height = nullptr) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_file(&image, path.c_str())) << path;
  image.format = format;
  const size_t channels = PNG_IMAGE_SAMPLE_CHANNELS(format);
  const size_t bytes = PNG_IMAGE_SAMPLE_COMPONENT_SIZE(format);
  std::vector<uint8_t> buffer(size_t(image.width) * image.height * channels * bytes);
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, buffer.data(), 0, nullptr)) << path;
  if (width) *width = int(image.width);
  if (height) *height = int(image.height);
  std::vector<uint16_t> values(buffer.size() / bytes);
  for (size_t i = 0; i < values.size(); ++i) {
    values[i] = bytes == 2 ? reinterpret_cast<const uint16_t*>(buffer.data())[i] : buffer[i];
  }
  return values;
}

// COCO's compressed RLE decoded as pycocotools' rleFrString does, into a row-major mask.
std::vector<uint8_t> DecodeRle(const std::string& counts, int width, int height) {
  std::vector<long> runs;
  size_t p = 0;
  while (p < counts.size()) {
    long x = 0;
    int k = 0;
    bool more = true;
    while (more) {
      const long c = long(counts[p]) - 48;
      x |= (c & 0x1f) << (5 * k);
      more = c & 0x20;
      ++p;
      ++k;
      if (!more && (c & 0x10)) x |= -1L << (5 * k);
    }
    if (runs.size() > 2) x += runs[runs.size() - 2];
    runs.push_back(x);
  }
  std::vector<uint8_t> mask(size_t(width) * height, 0);
  size_t at = 0;
  for (size_t r = 0; r < runs.size(); ++r) {
    for (long i = 0; i < runs[r]; ++i, ++at) {
      const size_t column = at / size_t(height), row = at % size_t(height);
      if (r % 2 == 1) mask[row * width + column] = 1;
    }
  }
  EXPECT_EQ(at, mask.size());
  return mask;
}

json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  return json::parse(in);
}

// A binary little-endian PLY's vertices (x y z first), read by this file's own parser.
std::vector<Eigen::Vector3d> ReadPlyVertices(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  size_t vertices = 0, floats_per_vertex = 0;
  bool in_vertex = false;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string a, b, c;
    words >> a >> b >> c;
    if (a == "format") {
      EXPECT_EQ(b, "binary_little_endian");
    }
    if (a == "element") {
      in_vertex = b == "vertex";
      if (in_vertex) vertices = std::stoul(c);
    }
    if (a == "property" && in_vertex) {
      EXPECT_EQ(b, "float");
      ++floats_per_vertex;
    }
  }
  std::vector<Eigen::Vector3d> points;
  std::vector<float> v(floats_per_vertex);
  for (size_t i = 0; i < vertices; ++i) {
    in.read(reinterpret_cast<char*>(v.data()), std::streamsize(4 * floats_per_vertex));
    points.emplace_back(v[0], v[1], v[2]);
  }
  EXPECT_TRUE(in);
  return points;
}

class DatasetTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    program_ = Compile(kProgram).release();
    dir_ =
        new fs::path(fs::temp_directory_path() / ("prs_dataset_test_" + std::to_string(getpid())));
    fs::remove_all(*dir_);
    DatasetOptions options;
    options.dir = (*dir_ / "ds").string();
    options.cameras = {"cam"};
    options.width = 320;
    options.height = 240;
    DatasetWriter writer(options, {"Object", "Camera", "Crate", "Lid"});
    const auto labels = writer.RenderScene(SampleScene(*program_), 0);
    writer.Add(*labels);
    EXPECT_EQ(writer.Finish(), 1);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete program_;
  }
  static fs::path Chunk() { return *dir_ / "ds" / "train_pbr" / "000000"; }
  static const lang::Scene& Scene() {
    static const sampling::SampledScene sampled = SampleScene(*program_);
    return sampled.scene;
  }

  static lang::CompiledProgram* program_;
  static fs::path* dir_;
};
lang::CompiledProgram* DatasetTest::program_ = nullptr;
fs::path* DatasetTest::dir_ = nullptr;

TEST_F(DatasetTest, WritesTheBopLayoutAndNoPartialDirectory) {
  EXPECT_FALSE(fs::exists(dir_->string() + "/ds.partial"));
  for (const char* file : {"camera.json", "models/models_info.json", "models/obj_000003.ply",
                           "models/obj_000004.ply"}) {
    EXPECT_TRUE(fs::exists(*dir_ / "ds" / file)) << file;
  }
  for (const char* file : {"rgb/000000.png", "depth/000000.png", "mask/000000_000000.png",
                           "mask_visib/000000_000001.png", "scene_camera.json", "scene_gt.json",
                           "scene_gt_info.json", "annotations.json", "scenes.jsonl"}) {
    EXPECT_TRUE(fs::exists(Chunk() / file)) << file;
  }
}

TEST_F(DatasetTest, CameraAndPosesAgreeWithPinholeMathWrittenHere) {
  const TestCamera camera(FindObject(Scene(), "cam"), 50, 320, 240);
  const json cam = ReadJson(Chunk() / "scene_camera.json")["0"];
  const std::vector<double> K = cam["cam_K"];
  EXPECT_NEAR(K[0], camera.f, 1e-9);
  EXPECT_NEAR(K[4], camera.f, 1e-9);
  EXPECT_NEAR(K[2], camera.cx, 1e-9);
  EXPECT_NEAR(K[5], camera.cy, 1e-9);
  const json gt = ReadJson(Chunk() / "scene_gt.json")["0"];
  ASSERT_EQ(gt.size(), 2u);  // the crate and the lid; the camera does not see itself
  const char* names[2] = {"c", "l"};
  for (int k = 0; k < 2; ++k) {
    const lang::SceneObject& o = FindObject(Scene(), names[k]);
    EXPECT_EQ(gt[k]["obj_id"], k == 0 ? 3 : 4);
    const std::vector<double> R = gt[k]["cam_R_m2c"], t = gt[k]["cam_t_m2c"];
    const Eigen::Matrix3d R_expected = camera.R_CW * o.R_WO.toRotationMatrix();
    const Eigen::Vector3d t_expected = 1000 * camera.ToCamera(o.p_WO);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(R[i], R_expected(i / 3, i % 3), 1e-9);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(t[i], t_expected[i], 1e-6);
  }
}

TEST_F(DatasetTest, FullMasksAndBoxesMatchTheProjectedBoxes) {
  const TestCamera camera(FindObject(Scene(), "cam"), 50, 320, 240);
  const json info = ReadJson(Chunk() / "scene_gt_info.json")["0"];
  const char* names[2] = {"c", "l"};
  for (int k = 0; k < 2; ++k) {
    std::vector<Eigen::Vector2d> projected;
    for (const Eigen::Vector3d& p : BoxCorners(FindObject(Scene(), names[k])))
      projected.push_back(camera.Project(p));
    const std::vector<Eigen::Vector2d> hull = Hull(projected);
    const auto mask =
        ReadPng(Chunk() / "mask" / fmt::format("000000_{:06d}.png", k), PNG_FORMAT_GRAY);
    // Every pixel whose centre is more than a pixel inside the hull is in the mask, every one
    // more than a pixel outside is not; the count is the hull's within its border pixels.
    int64_t count = 0, inside = 0, border = 0;
    for (int v = 0; v < 240; ++v) {
      for (int u = 0; u < 320; ++u) {
        const double d = DistanceToHull(hull, {double(u), double(v)});
        const bool in = mask[size_t(v) * 320 + u] == 255;
        count += in;
        if (d < -1) {
          EXPECT_TRUE(in) << names[k] << " at " << u << "," << v;
        }
        if (d > 1) {
          EXPECT_FALSE(in) << names[k] << " at " << u << "," << v;
        }
        inside += d < 0;
        border += std::abs(d) <= 1;
      }
    }
    EXPECT_EQ(info[k]["px_count_all"], count);
    EXPECT_LE(std::abs(count - inside), border / 2) << names[k];
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
    for (const auto& p : hull) {
      x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y());
      x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
    }
    // The box's first and last pixels are those whose centres are inside the hull: within a
    // pixel of its extent, on the inner side (0.1 pixel of slack for the renderer's floats).
    const std::vector<int> box = info[k]["bbox_obj"];
    EXPECT_GE(box[0], x0 - 0.1) << names[k];
    EXPECT_LE(box[0], x0 + 1.1) << names[k];
    EXPECT_GE(box[1], y0 - 0.1) << names[k];
    EXPECT_LE(box[1], y0 + 1.1) << names[k];
    EXPECT_LE(box[0] + box[2] - 1, x1 + 0.1) << names[k];
    EXPECT_GE(box[0] + box[2] - 1, x1 - 1.1) << names[k];
    EXPECT_LE(box[1] + box[3] - 1, y1 + 0.1) << names[k];
    EXPECT_GE(box[1] + box[3] - 1, y1 - 1.1) << names[k];
  }
}

TEST_F(DatasetTest, TheLidHidesPartOfTheCrate) {
  const json info = ReadJson(Chunk() / "scene_gt_info.json")["0"];
  const auto crate = ReadPng(Chunk() / "mask_visib/000000_000000.png", PNG_FORMAT_GRAY);
  const auto lid = ReadPng(Chunk() / "mask_visib/000000_000001.png", PNG_FORMAT_GRAY);
  const auto crate_all = ReadPng(Chunk() / "mask/000000_000000.png", PNG_FORMAT_GRAY);
  const auto lid_all = ReadPng(Chunk() / "mask/000000_000001.png", PNG_FORMAT_GRAY);
  int64_t crate_visible = 0, hidden = 0;
  for (size_t p = 0; p < crate.size(); ++p) {
    EXPECT_FALSE(crate[p] && lid[p]);           // one object per pixel
    EXPECT_TRUE(!crate[p] || crate_all[p]);     // the visible part of the silhouette
    EXPECT_EQ(bool(lid[p]), bool(lid_all[p]));  // nothing is in front of the lid
    crate_visible += crate[p] != 0;
    hidden += crate_all[p] && lid_all[p];
  }
  EXPECT_GT(hidden, 100);
  EXPECT_EQ(info[0]["px_count_visib"], crate_visible);
  const double all = info[0]["px_count_all"], visib = info[0]["px_count_visib"];
  EXPECT_DOUBLE_EQ(info[0]["visib_fract"].get<double>(), visib / all);
  EXPECT_LT(info[0]["visib_fract"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(info[1]["visib_fract"].get<double>(), 1.0);
}

TEST_F(DatasetTest, DepthAtVisiblePixelsIsTheBoxesDepth) {
  const TestCamera camera(FindObject(Scene(), "cam"), 50, 320, 240);
  const double depth_scale = ReadJson(Chunk() / "scene_camera.json")["0"]["depth_scale"];
  const auto depth = ReadPng(Chunk() / "depth/000000.png", PNG_FORMAT_LINEAR_Y);
  const char* names[2] = {"c", "l"};
  int checked = 0;
  for (int k = 0; k < 2; ++k) {
    const lang::SceneObject& o = FindObject(Scene(), names[k]);
    const auto visible =
        ReadPng(Chunk() / "mask_visib" / fmt::format("000000_{:06d}.png", k), PNG_FORMAT_GRAY);
    for (int v = 1; v < 239; ++v) {
      for (int u = 1; u < 319; ++u) {
        // Inside the visible mask, away from its border (where a pixel's centre may miss).
        bool interior = true;
        for (int dv = -1; dv <= 1; ++dv)
          for (int du = -1; du <= 1; ++du) interior = interior && visible[(v + dv) * 320 + u + du];
        if (!interior) continue;
        const Eigen::Vector3d ray = camera.Ray(u, v);
        const std::optional<double> t = HitBox(o, camera.p_WC, ray);
        ASSERT_TRUE(t) << names[k] << " at " << u << "," << v;
        const double z_mm = 1000 * *t;  // the ray's camera z grows by 1 per unit of t
        EXPECT_NEAR(depth[v * 320 + u] * depth_scale, z_mm, depth_scale + 1.0)
            << names[k] << " at " << u << "," << v;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST_F(DatasetTest, ModelVerticesProjectIntoTheFullMask) {
  const json gt = ReadJson(Chunk() / "scene_gt.json")["0"];
  const json cam = ReadJson(Chunk() / "scene_camera.json")["0"];
  const std::vector<double> K = cam["cam_K"];
  for (int k = 0; k < 2; ++k) {
    const int obj_id = gt[k]["obj_id"];
    const auto mask =
        ReadPng(Chunk() / "mask" / fmt::format("000000_{:06d}.png", k), PNG_FORMAT_GRAY);
    const std::vector<double> R = gt[k]["cam_R_m2c"], t = gt[k]["cam_t_m2c"];
    const auto vertices =
        ReadPlyVertices(*dir_ / "ds" / "models" / fmt::format("obj_{:06d}.ply", obj_id));
    ASSERT_FALSE(vertices.empty());
    for (const Eigen::Vector3d& p_mm : vertices) {
      Eigen::Vector3d q;
      for (int i = 0; i < 3; ++i)
        q[i] = R[3 * i] * p_mm[0] + R[3 * i + 1] * p_mm[1] + R[3 * i + 2] * p_mm[2] + t[i];
      const double u = K[0] * q[0] / q[2] + K[2], v = K[4] * q[1] / q[2] + K[5];
      // A corner lies on the silhouette's edge: one of the pixels around it is in the mask.
      bool near = false;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du) {
          const int x = int(std::lround(u)) + du, y = int(std::lround(v)) + dv;
          near = near || (x >= 0 && y >= 0 && x < 320 && y < 240 && mask[y * 320 + x]);
        }
      EXPECT_TRUE(near) << "obj " << obj_id << " vertex at " << u << "," << v;
    }
  }
  const json models = ReadJson(*dir_ / "ds" / "models" / "models_info.json");
  // The crate, 300 x 200 x 150 mm: its diagonal, and only the half turns about each axis.
  EXPECT_NEAR(models["3"]["diameter"].get<double>(), std::sqrt(300. * 300 + 200 * 200 + 150 * 150),
              1e-3);
  EXPECT_NEAR(models["3"]["size_x"].get<double>(), 300, 1e-3);
  EXPECT_EQ(models["3"]["symmetries_discrete"].size(), 3u);
  // The lid, 120 x 120 x 20 mm: also the quarter turns about z (and their compositions).
  EXPECT_EQ(models["4"]["symmetries_discrete"].size(), 7u);
}

TEST_F(DatasetTest, CocoRleDecodedHereEqualsTheVisibleMasks) {
  const json coco = ReadJson(Chunk() / "annotations.json");
  ASSERT_EQ(coco["images"].size(), 1u);
  EXPECT_EQ(coco["images"][0]["file_name"], "rgb/000000.png");
  EXPECT_EQ(coco["images"][0]["width"], 320);
  ASSERT_EQ(coco["annotations"].size(), 2u);
  std::set<std::string> categories;
  for (const json& c : coco["categories"]) categories.insert(c["name"]);
  EXPECT_EQ(categories, (std::set<std::string>{"Object", "Camera", "Crate", "Lid"}));
  for (int k = 0; k < 2; ++k) {
    const json& a = coco["annotations"][k];
    EXPECT_EQ(a["iscrowd"], 0);
    EXPECT_EQ(a["category_id"], k + 3);
    EXPECT_EQ(a["segmentation"]["size"], json::array({240, 320}));
    const auto mask = DecodeRle(a["segmentation"]["counts"], 320, 240);
    const auto visible =
        ReadPng(Chunk() / "mask_visib" / fmt::format("000000_{:06d}.png", k), PNG_FORMAT_GRAY);
    int64_t area = 0;
    int x0 = 320, y0 = 240, x1 = -1, y1 = -1;
    for (int v = 0; v < 240; ++v) {
      for (int u = 0; u < 320; ++u) {
        ASSERT_EQ(mask[v * 320 + u] != 0, visible[v * 320 + u] != 0) << u << "," << v;
        if (!mask[v * 320 + u]) continue;
        ++area;
        x0 = std::min(x0, u), y0 = std::min(y0, v), x1 = std::max(x1, u), y1 = std::max(y1, v);
      }
    }
    EXPECT_EQ(a["area"], area);
    EXPECT_EQ(a["bbox"], json::array({x0, y0, x1 - x0 + 1, y1 - y0 + 1}));
  }
}

TEST(DatasetWriterTest, RefusesAnotherDatasetAndMissingIntrinsics) {
  const fs::path dir =
      fs::temp_directory_path() / ("prs_dataset_refuse_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "keep.txt") << "a user's file";
  DatasetOptions options;
  options.dir = dir.string();
  options.cameras = {"cam"};
  EXPECT_THROW(DatasetWriter(options, {"Object"}), std::runtime_error);
  EXPECT_TRUE(fs::exists(dir / "keep.txt"));
  options.dir = (dir / "new").string();
  options.cameras = {};
  EXPECT_THROW(DatasetWriter(options, {"Object"}), std::invalid_argument);
  // A camera without near and far: the message names what is missing.
  const auto program = Compile(
      "class Camera:\n    fovy_deg: 40\n    aspect: 1.5\n"
      "b = Object at V3D(0, 0, 0.1)\ncam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)\n");
  options.cameras = {"cam"};
  DatasetWriter writer(options, {"Object", "Camera"});
  try {
    writer.RenderScene(SampleScene(*program), 0);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("camera 'cam' has no near and far"), std::string::npos)
        << error.what();
  }
  EXPECT_TRUE(fs::exists(dir / "new.partial"));  // unfinished: marked so, never DIR
  EXPECT_FALSE(fs::exists(dir / "new"));
  fs::remove_all(dir);
}

// A scene's other cameras are viewpoints too, not things in its pictures: with a second camera
// 0.4 m below `cam`, in the middle of its view, the picture's centre still sees the crate or the
// lid (depth over 0.9 m, not 0.375), and only the crate and the lid are labelled.
TEST(DatasetWriterTest, OtherCamerasAreNeitherDrawnNorLabelled) {
  const fs::path dir =
      fs::temp_directory_path() / ("prs_dataset_views_" + std::to_string(getpid()));
  fs::remove_all(dir);
  const auto program =
      Compile(std::string(kProgram) + "other = Camera at V3D(0.05, 0.02, 1.2), with yaw 0.3, "
                                      "with pitch -1.5707963267948966\n");
  DatasetOptions options;
  options.dir = (dir / "ds").string();
  options.cameras = {"cam"};
  options.width = 64;
  options.height = 48;
  DatasetWriter writer(options, {"Object", "Camera", "Crate", "Lid"});
  writer.Add(*writer.RenderScene(SampleScene(*program), 0));
  EXPECT_EQ(writer.Finish(), 1);
  const fs::path chunk = dir / "ds" / "train_pbr" / "000000";
  const json gt = ReadJson(chunk / "scene_gt.json")["0"];
  ASSERT_EQ(gt.size(), 2u);
  EXPECT_EQ(gt[0]["obj_id"], 3);
  EXPECT_EQ(gt[1]["obj_id"], 4);
  const double depth_scale = ReadJson(chunk / "scene_camera.json")["0"]["depth_scale"];
  const auto depth = ReadPng(chunk / "depth/000000.png", PNG_FORMAT_LINEAR_Y);
  for (int v = 22; v <= 25; ++v) {
    for (int u = 30; u <= 33; ++u) EXPECT_GT(depth[v * 64 + u] * depth_scale, 900) << u << "," << v;
  }
  // Asking for cameras' labels says why there are none.
  options.dir = (dir / "cams").string();
  options.labels = {"Camera"};
  DatasetWriter cameras(options, {"Object", "Camera", "Crate", "Lid"});
  try {
    cameras.RenderScene(SampleScene(*program), 0);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("--label Camera: cameras are not labelled"),
              std::string::npos)
        << error.what();
  }
  fs::remove_all(dir);
}

// The width and height of a baseline JPEG from its SOF0 marker (FF C0), read here.
std::pair<int, int> ReadJpegSize(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), {});
  if (b.size() < 4 || uint8_t(b[0]) != 0xFF || uint8_t(b[1]) != 0xD8) return {0, 0};
  for (size_t at = 2; at + 9 < b.size();) {
    if (uint8_t(b[at]) != 0xFF) return {0, 0};
    const uint8_t marker = uint8_t(b[at + 1]);
    const size_t length = size_t(uint8_t(b[at + 2])) << 8 | uint8_t(b[at + 3]);
    if (marker == 0xC0) {
      const int height = uint8_t(b[at + 5]) << 8 | uint8_t(b[at + 6]);
      const int width = uint8_t(b[at + 7]) << 8 | uint8_t(b[at + 8]);
      return {width, height};
    }
    at += 2 + length;
  }
  return {0, 0};
}

TEST(DatasetWriterTest, JpegPicturesAndTheirCocoNames) {
  const fs::path dir = fs::temp_directory_path() / ("prs_dataset_jpeg_" + std::to_string(getpid()));
  fs::remove_all(dir);
  const auto program = Compile(kProgram);
  DatasetOptions options;
  options.dir = (dir / "ds").string();
  options.cameras = {"cam"};
  options.width = 96;
  options.height = 64;
  options.jpeg = true;
  DatasetWriter writer(options, {"Object", "Camera", "Crate", "Lid"});
  writer.Add(*writer.RenderScene(SampleScene(*program), 7));
  writer.Finish();
  const fs::path chunk = dir / "ds" / "train_pbr" / "000000";
  EXPECT_EQ(ReadJpegSize(chunk / "rgb" / "000007.jpg"), std::make_pair(96, 64));
  EXPECT_FALSE(fs::exists(chunk / "rgb" / "000007.png"));
  EXPECT_EQ(ReadJson(chunk / "annotations.json")["images"][0]["file_name"], "rgb/000007.jpg");
  fs::remove_all(dir);
}

TEST(CocoRleTest, EncodesRunsDownTheColumnsAsPycocotoolsDoes) {
  // 3 x 2 (width x height): column-major pixels 0 1 | 1 1 | 0 0 -> runs 1, 3, 2.
  const std::vector<uint8_t> mask = {0, 1, 0,  //
                                     1, 1, 0};
  EXPECT_EQ(EncodeCocoRle(mask, 3, 2), "132");
  // Long runs and differences to the run two before, negative ones too: decoded back here.
  std::vector<uint8_t> big(200 * 150, 0);
  for (int v = 0; v < 150; ++v)
    for (int u = 0; u < 200; ++u)
      big[v * 200 + u] = (u - 90) * (u - 90) + (v - 60) * (v - 60) < 900 || u > 190;
  EXPECT_EQ(DecodeRle(EncodeCocoRle(big, 200, 150), 200, 150), big);
}

}  // namespace
}  // namespace prs::dataset
