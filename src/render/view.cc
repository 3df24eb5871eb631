// Where pictures are taken from: the framed views (overview, top, front) fitted to the
// objects' boxes, and a camera object's own pose (it looks along its local +y, up is +z).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "render/render.h"
#include "render/scene_geoms.h"

namespace prs::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Corners of every object's box (points count as themselves); a unit box at the origin for
// an empty scene.
std::vector<Eigen::Vector3d> CollectCorners(const RenderScene& scene) {
  std::vector<Eigen::Vector3d> corners;
  for (const RenderObject& o : scene.objects) {
    const Eigen::Matrix3d R_WO = o.R_WO.toRotationMatrix();
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d sign(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
      corners.push_back(o.p_WO + R_WO * sign.cwiseProduct(o.dimensions / 2));
    }
  }
  if (corners.empty()) {
    corners = {Eigen::Vector3d(-0.5, -0.5, 0), Eigen::Vector3d(0.5, 0.5, 1)};
  }
  return corners;
}

Eigen::Vector3d UpFor(const Eigen::Vector3d& forward_W, const Eigen::Vector3d& hint_W) {
  return (hint_W - hint_W.dot(forward_W) * forward_W).normalized();
}

// Backs the camera off along -forward until every corner is inside the frustum (with a 10 %
// margin): a corner at (a, b) across and f along the view needs distance d with
// |a| <= (d + f) tan(half_x), |b| <= (d + f) tan(half_y).
CameraPose FitCorners(const std::vector<Eigen::Vector3d>& corners, const Eigen::Vector3d& forward_W,
                      const Eigen::Vector3d& up_W, const RenderOptions& options) {
  const double tan_y = std::tan(options.camera_fovy_deg * kPi / 360.0);
  const double tan_x = tan_y * options.width / options.height;
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();
  for (const auto& c : corners) centre_W += c / corners.size();
  const Eigen::Vector3d right_W = forward_W.cross(up_W);
  double distance = 0, reach = 0;
  for (const auto& c : corners) {
    const Eigen::Vector3d q = c - centre_W;
    const double f = q.dot(forward_W);
    distance = std::max(
        distance,
        std::max(std::abs(q.dot(right_W)) * 1.1 / tan_x, std::abs(q.dot(up_W)) * 1.1 / tan_y) - f);
    reach = std::max(reach, q.norm());
  }
  distance = std::max(distance, 0.2);
  CameraPose pose;
  pose.p_WC = centre_W - distance * forward_W;
  pose.forward_W = forward_W;
  pose.up_W = up_W;
  pose.near_m = std::max(0.01, (distance - reach) * 0.5);
  pose.far_m = distance + 40 * std::max(reach, 1.0);  // the floor reaches far beyond the scene
  return pose;
}

// Direction from the scene towards the viewer: behind it (-y), turned towards +x by
// `azimuth_deg`, raised by `elevation_deg`. Looking along +y (the scene's "ahead") keeps the
// language's left and right (-x, +x) on the left and right of the picture.
Eigen::Vector3d ViewerDirection(double azimuth_deg, double elevation_deg) {
  const double az = azimuth_deg * kPi / 180, el = elevation_deg * kPi / 180;
  return {std::cos(el) * std::sin(az), -std::cos(el) * std::cos(az), std::sin(el)};
}

std::string ListCameras(const RenderScene& scene) {
  std::string list;
  for (const RenderObject& o : scene.objects) {
    if (o.shape == ObjectShape::kCamera) list += (list.empty() ? "" : ", ") + o.name;
  }
  return list.empty() ? "the scene has no camera objects" : "camera objects: " + list;
}

CameraPose CalcCameraObjectPose(const RenderObject& camera) {
  const Eigen::Matrix3d R_WO = camera.R_WO.toRotationMatrix();
  CameraPose pose;
  pose.p_WC = camera.p_WO;
  pose.forward_W = R_WO.col(1);
  pose.up_W = R_WO.col(2);
  pose.near_m = camera.near_m;  // its own range (an RGB-D camera's by default)
  pose.far_m = camera.far_m;
  return pose;
}

}  // namespace

// By variable name (or "Class#index"), else by class name when exactly one object has it.
const RenderObject& FindViewpointObject(const RenderScene& scene, const std::string& name) {
  const RenderObject* by_class = nullptr;
  int class_matches = 0;
  for (const RenderObject& o : scene.objects) {
    if (o.name == name) return o;
    if (o.class_name == name) {
      by_class = &o;
      ++class_matches;
    }
  }
  if (class_matches == 1) return *by_class;
  throw std::invalid_argument("no object named '" + name + "' to look from (" + ListCameras(scene) +
                              ")");
}

View ParseView(const std::string& text) {
  if (text == "overview") return {ViewKind::kOverview, ""};
  if (text == "top") return {ViewKind::kTop, ""};
  if (text == "front") return {ViewKind::kFront, ""};
  const std::string prefix = "camera:";
  if (text.rfind(prefix, 0) == 0 && text.size() > prefix.size())
    return {ViewKind::kCamera, text.substr(prefix.size())};
  throw std::invalid_argument("unknown view '" + text +
                              "' (expected overview, top, front or camera:NAME)");
}

std::pair<int, int> ParseSize(const std::string& text) {
  const size_t x = text.find('x');
  int width = 0, height = 0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  bool ok = x != std::string::npos;
  if (ok) {
    const auto w = std::from_chars(begin, begin + x, width);
    const auto h = std::from_chars(begin + x + 1, end, height);
    ok = w.ec == std::errc() && w.ptr == begin + x && h.ec == std::errc() && h.ptr == end;
  }
  if (!ok) throw std::invalid_argument("expects WIDTHxHEIGHT such as 640x480, got '" + text + "'");
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw std::invalid_argument("width and height must be from 16 to 8192 pixels, got '" + text +
                                "'");
  return {width, height};
}

CameraPose CalcViewPose(const RenderScene& scene, const RenderOptions& options) {
  const std::vector<Eigen::Vector3d> corners = CollectCorners(scene);
  const Eigen::Vector3d z_W = Eigen::Vector3d::UnitZ();
  switch (options.view.kind) {
    case ViewKind::kTop:
      return FitCorners(corners, -z_W, Eigen::Vector3d::UnitY(), options);
    case ViewKind::kFront:
      return FitCorners(corners, -Eigen::Vector3d::UnitY(), z_W, options);
    case ViewKind::kOverview: {
      const Eigen::Vector3d forward_W = -ViewerDirection(30, 35);
      return FitCorners(corners, forward_W, UpFor(forward_W, z_W), options);
    }
    case ViewKind::kCamera:
      return CalcCameraObjectPose(FindViewpointObject(scene, options.view.camera_name));
  }
  throw std::logic_error("unhandled view kind");
}

}  // namespace prs::render
