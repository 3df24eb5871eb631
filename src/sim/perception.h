// The controller's eyes: a MuJoCo camera as a pinhole camera (camera/camera.h, which also
// projects and back-projects), and colour-blob detection in its RGB image. Pure functions over
// images, so they are tested on synthetic pictures as well as rendered ones.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <optional>

#include "camera/camera.h"
#include "render/render.h"
#include "sim/mujoco_model.h"

namespace prs::sim {

// A MuJoCo camera looks along its frame's −z with +y up, as camera::PinholeCamera does.
using camera::BackProject;
using camera::PinholeCamera;
using camera::Project;

/// The pose and field of view of camera `camera_id` in `data` (after kinematics).
PinholeCamera GetMujocoCamera(const mjModel& model, const mjData& data, int camera_id, int width,
                              int height);

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
