// Offscreen pictures of scenes: MuJoCo's OpenGL renderer on a software (Mesa llvmpipe) EGL
// context, so no GPU and no display are needed. Plain structs in, pixels out (docs/render.md).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace prs::shapes {
struct MeshShape;  // shapes/mesh.h
}

namespace prs::render {

/// An 8-bit RGB picture, rows from the top, 3 bytes per pixel.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;
};

/// Distance along the camera's look axis (metres) per pixel, rows from the top; pixels that
/// see nothing (the sky) hold +infinity.
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth_m;
};

/// Linear RGBA in [0, 1].
using Rgba = std::array<float, 4>;

/// kSphere is an ellipsoid filling the box; kCylinder and kCapsule are round (the mean of the
/// half width and length): MuJoCo draws no elliptic ones.
enum class ObjectShape { kBox, kCylinder, kSphere, kCapsule, kPoint, kCamera, kMesh };

/// One object as the renderer needs it (converted from a lang::SceneObject or a JSON object).
struct RenderObject {
  std::string name;  // variable name, or "Class#index" for anonymous objects
  std::string class_name;
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();
  Eigen::Quaterniond R_WO = Eigen::Quaterniond::Identity();
  Eigen::Vector3d dimensions = Eigen::Vector3d::Zero();  // width (x), length (y), height (z)
  ObjectShape shape = ObjectShape::kBox;
  /// kMesh: the object's mesh (its bounding box centred on p_WO) and the factor on its file's
  /// coordinates. Set before the shape is classified; an object without one is drawn as a box.
  std::shared_ptr<const shapes::MeshShape> mesh;
  double mesh_scale = 1;
  Rgba color = {0.75f, 0.72f, 0.66f, 1.0f};
  // Cameras: the vertical field of view (degrees) and width / height of what they see (the
  // object's fovy_deg and aspect, as `in view of` and MJCF export read them), for the frustum
  // drawn at the camera and for a view through it.
  double fovy_deg = 45.0;
  double aspect = 4.0 / 3.0;
};

/// A straight edge of the workspace outline (world frame, metres).
using Segment = std::pair<Eigen::Vector3d, Eigen::Vector3d>;

/// The outline of a region drawn into the picture (prs render --show-regions): where an
/// object's position was drawn from, or what a camera sees.
struct RegionOutline {
  std::string what;  // "position of c", "view of camera"
  bool is_view = false;
  std::vector<Segment> edges;
};

struct RenderScene {
  std::vector<RenderObject> objects;
  std::vector<Segment> workspace_edges;  // empty when the program binds no workspace
  std::vector<RegionOutline> regions;    // empty unless regions were recorded
  std::string caption;                   // drawn in the top-left corner when non-empty
};

enum class ViewKind { kOverview, kTop, kFront, kCamera };

/// Where the picture is taken from: a framing of the scene's objects, or a camera object.
struct View {
  ViewKind kind = ViewKind::kOverview;
  std::string camera_name;  // kCamera only
};

/// Parses "overview", "top", "front" or "camera:NAME". Throws std::invalid_argument with a
/// message naming the accepted forms.
View ParseView(const std::string& text);

/// Parses "WxH" (e.g. "640x480"), each from 16 to 8192. Throws std::invalid_argument.
std::pair<int, int> ParseSize(const std::string& text);

struct RenderOptions {
  int width = 640;
  int height = 480;
  View view;
  double camera_fovy_deg = 45.0;  // vertical field of view of the framings (overview, top, front)
};

/// A pinhole camera pose: the point it looks from, its look axis and its up axis (world).
struct CameraPose {
  Eigen::Vector3d p_WC = Eigen::Vector3d::Zero();
  Eigen::Vector3d forward_W = -Eigen::Vector3d::UnitZ();
  Eigen::Vector3d up_W = Eigen::Vector3d::UnitY();
  double near_m = 0.01;
  double far_m = 100.0;
};

/// The pose a view is taken from. Throws std::invalid_argument when a camera view names no
/// object of the scene (the message lists the scene's camera objects).
CameraPose CalcViewPose(const RenderScene& scene, const RenderOptions& options);

class Renderer {
 public:
  /// Creates the OpenGL context (EGL, Mesa's software rasteriser) and MuJoCo's render state.
  /// Throws std::runtime_error with the reason when no context can be made.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders one scene. Fills `depth` (same size) when it is not null. Throws
  /// std::invalid_argument for an unknown camera name (see CalcViewPose).
  Image Render(const RenderScene& scene, const RenderOptions& options, DepthImage* depth = nullptr);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Columns and rows of a grid of `count` pictures: ceil(sqrt(count)) columns.
std::pair<int, int> CalcGridShape(int count);

/// White pixels between the tiles of a grid.
constexpr int kGridGutter = 4;

/// Tiles of one size in row-major order on a grid of CalcGridShape(tiles.size()), kGridGutter
/// white pixels apart, empty cells white: columns * (w + gutter) - gutter wide. Throws
/// std::invalid_argument when the tiles differ in size or there are none.
Image ComposeGrid(const std::vector<Image>& tiles);

/// Writes an 8-bit RGB PNG. Throws std::runtime_error naming the path when it cannot.
void WritePng(const Image& image, const std::string& path);
/// Writes a 16-bit grey PNG of depth in millimetres (0 where nothing was seen or beyond
/// 65.535 m), the usual RGB-D convention. Throws std::runtime_error naming the path.
void WriteDepthPng(const DepthImage& depth, const std::string& path);

}  // namespace prs::render
