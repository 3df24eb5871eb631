// The controller's eyes: a pinhole model of a MuJoCo camera, colour-blob detection in its RGB
// image, and back-projection of a pixel with its depth into world coordinates. Pure functions
// over images, so they are tested on synthetic pictures as well as rendered ones.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <optional>

#include "render/render.h"
#include "sim/mujoco_model.h"

namespace prs::sim {

/// A camera as MuJoCo defines one: it looks along its frame's -z with +y up; fovy is the
/// vertical field of view. Pixels are counted from the top-left corner, rows downwards.
struct PinholeCamera {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  double fovy_rad = 0.785398;
  int width = 640;
  int height = 480;

  /// Focal length in pixels.
  double focal_px() const;
};

/// The pose and field of view of camera `camera_id` in `data` (after kinematics).
PinholeCamera GetMujocoCamera(const mjModel& model, const mjData& data, int camera_id, int width,
                              int height);

/// The point at `depth_m` along the look axis that projects to `pixel` (column, row; pixel
/// centres at +0.5), in world coordinates.
Eigen::Vector3d BackProject(const PinholeCamera& camera, const Eigen::Vector2d& pixel, double depth_m);
/// Where a world point lands in the image (column, row), and its depth along the look axis.
Eigen::Vector3d Project(const PinholeCamera& camera, const Eigen::Vector3d& p_W);

/// A connected set of matching pixels (4-neighbourhood).
struct ColorBlob {
  Eigen::Vector2d centroid_px = Eigen::Vector2d::Zero();
  int pixel_count = 0;
  bool touches_border = false;  // part of it may be outside the view
  std::vector<int> pixels;      // row * width + column
};

using PixelTest = std::function<bool(uint8_t r, uint8_t g, uint8_t b)>;

/// The largest connected blob of pixels passing `matches`, if it has at least `min_pixels`.
std::optional<ColorBlob> FindLargestBlob(const render::Image& image, const PixelTest& matches,
                                         int min_pixels = 12);

/// Saturated blue under any shading (the Table-Cube cube's colour), not grey or white.
bool IsBluePixel(uint8_t r, uint8_t g, uint8_t b);

/// The median depth over a blob's pixels (robust to a few edge pixels that see behind it).
double MedianDepth(const render::DepthImage& depth, const ColorBlob& blob);

}  // namespace prs::sim
