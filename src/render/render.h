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
/// kLight: a light of the scene (a class named like "Light"), drawn as nothing.
enum class ObjectShape { kBox, kCylinder, kSphere, kCapsule, kPoint, kCamera, kMesh, kLight };

/// A light object's properties (docs/render.md, "Lights"): it shines along its local +y from
/// its position, in its `color` (white by default) times `intensity`.
struct LightProperties {
  double intensity = 0.8;    // diffuse brightness, 0 (off) to about 1 (full)
  bool directional = false;  // a sun: parallel rays along its direction, from far away
  double cutoff_deg = 45;    // a spotlight's half-angle (not directional)
  bool castshadow = true;
};

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
  /// The depths it sees (its `near` and `far`, metres): the clipping planes of a view through
  /// it. The defaults, when it has none, are an RGB-D camera's range.
  double near_m = 0.02, far_m = 50.0;
  /// Of fovy_deg, aspect, near and far: those the object does not give as valid numbers (a
  /// dataset needs them all of a camera it looks through).
  std::vector<std::string> missing_view_properties;
  LightProperties light;  // kLight only
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
  /// Box edges, camera bodies and their frusta, point markers, outlines and the caption: off
  /// for a dataset's pictures, which show the solids alone (no camera is seen).
  bool decorations = true;
};

/// A pinhole camera pose: the point it looks from, its look axis and its up axis (world).
struct CameraPose {
  Eigen::Vector3d p_WC = Eigen::Vector3d::Zero();
  Eigen::Vector3d forward_W = -Eigen::Vector3d::UnitZ();
  Eigen::Vector3d up_W = Eigen::Vector3d::UnitY();
  double near_m = 0.01;
  double far_m = 100.0;
};

/// Per pixel (rows from the top), the index in RenderScene::objects of the object drawn there,
/// or kNoObject (the floor, the sky).
struct ObjectIdImage {
  int width = 0;
  int height = 0;
  std::vector<int32_t> object;
};
inline constexpr int32_t kNoObject = -1;

/// One picture with what a dataset labels: its colours, its depth, which object each pixel
/// shows, and the silhouettes of the objects asked for, each drawn alone (1 where it covers the
/// pixel, whatever is in front of it).
struct LabelledPicture {
  CameraPose pose;  // where it was taken from (CalcViewPose)
  Image rgb;
  DepthImage depth;
  ObjectIdImage visible;
  std::vector<std::vector<uint8_t>> silhouettes;  // in the order asked for; width * height
};

/// The object a camera view looks from: by name (variable or "Class#index"), else by class
/// when exactly one object has that class. Throws std::invalid_argument listing the cameras.
const RenderObject& FindViewpointObject(const RenderScene& scene, const std::string& name);

/// The pose a view is taken from. Throws std::invalid_argument when a camera view names no
/// object of the scene (the message lists the scene's camera objects).
CameraPose CalcViewPose(const RenderScene& scene, const RenderOptions& options);

class Renderer {
 public:
  /// Creates the OpenGL context (EGL, Mesa's software rasteriser) and MuJoCo's render state.
  /// Throws std::runtime_error with the reason when no context can be made. The context is
  /// current only during each call, so a renderer may be used by one thread after another.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders one scene. Fills `depth` (same size) when it is not null. Throws
  /// std::invalid_argument for an unknown camera name (see CalcViewPose).
  Image Render(const RenderScene& scene, const RenderOptions& options, DepthImage* depth = nullptr);

  /// Renders one scene with its labels: the colour and depth picture of Render, then MuJoCo's
  /// segmentation rendering (each object in one flat colour: no lighting, blending or
  /// multisampling), once with every object and once per object of `silhouettes_of` (indices
  /// into scene.objects) drawn alone. Throws as Render does, and std::out_of_range for an
  /// index that is not an object's.
  LabelledPicture RenderLabelled(const RenderScene& scene, const RenderOptions& options,
                                 const std::vector<int>& silhouettes_of);

 private:
  // With the context current: fills MuJoCo's scene for `options`: geoms, camera, lights.
  // Returns the pose, and sets *fovy_deg (when not null) to the view's field of view.
  CameraPose Prepare(const RenderScene& scene, const RenderOptions& options,
                     double* fovy_deg = nullptr);

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
/// Writes a 16-bit grey PNG of depth in units of `mm_per_unit` millimetres (by default
/// millimetres, the usual RGB-D convention; BOP's depth_scale), 0 where nothing was seen or
/// beyond 65,535 units. Throws std::runtime_error naming the path.
void WriteDepthPng(const DepthImage& depth, const std::string& path, double mm_per_unit = 1.0);
/// Writes an 8-bit RGB JPEG of `quality` (1 to 100; libjpeg-turbo, exact integer DCT, so the
/// same bytes on every machine). Throws std::runtime_error naming the path.
void WriteJpeg(const Image& image, const std::string& path, int quality = 95);
/// Writes an 8-bit grey PNG of a mask (width * height values, row-major from the top): 255
/// where it is not 0, else 0 (BOP's masks). Throws std::runtime_error naming the path.
void WriteMaskPng(const std::vector<uint8_t>& mask, int width, int height, const std::string& path);

}  // namespace prs::render
