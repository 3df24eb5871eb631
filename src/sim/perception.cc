// MuJoCo cameras as pinhole cameras, and blob detection (see perception.h).
#include "sim/perception.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace prs::sim {

PinholeCamera GetMujocoCamera(const mjModel& model, const mjData& data, int camera_id, int width,
                              int height) {
  PinholeCamera camera;
  camera.X_WC.translation() = Eigen::Map<const Eigen::Vector3d>(data.cam_xpos + 3 * camera_id);
  camera.X_WC.linear() =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data.cam_xmat + 9 * camera_id);
  camera.fovy_rad = model.cam_fovy[camera_id] * M_PI / 180;  // MuJoCo stores degrees
  camera.width = width;
  camera.height = height;
  return camera;
}

bool IsBluePixel(uint8_t r, uint8_t g, uint8_t b) {
  return b >= 60 && b > 1.5 * r + 20 && b > 1.3 * g + 15;
}

std::optional<ColorBlob> FindLargestBlob(const render::Image& image, const PixelTest& matches, int min_pixels) {
  const int w = image.width, h = image.height;
  std::vector<char> candidate(static_cast<size_t>(w) * h), seen(candidate.size(), 0);
  for (int i = 0; i < w * h; ++i) {
    const uint8_t* p = &image.rgb[3 * static_cast<size_t>(i)];
    candidate[i] = matches(p[0], p[1], p[2]);
  }
  std::optional<ColorBlob> best;
  std::vector<int> stack;
  for (int start = 0; start < w * h; ++start) {
    if (!candidate[start] || seen[start]) continue;
    ColorBlob blob;
    stack.assign(1, start);
    seen[start] = 1;
    while (!stack.empty()) {  // flood fill
      const int i = stack.back();
      stack.pop_back();
      blob.pixels.push_back(i);
      const int x = i % w, y = i / w;
      blob.touches_border |= x == 0 || y == 0 || x == w - 1 || y == h - 1;
      const int neighbours[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
      for (const auto& n : neighbours) {
        if (n[0] < 0 || n[1] < 0 || n[0] >= w || n[1] >= h) continue;
        const int j = n[1] * w + n[0];
        if (candidate[j] && !seen[j]) {
          seen[j] = 1;
          stack.push_back(j);
        }
      }
    }
    if (!best || blob.pixels.size() > best->pixels.size()) best = std::move(blob);
  }
  if (!best || static_cast<int>(best->pixels.size()) < min_pixels) return std::nullopt;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int i : best->pixels) sum += Eigen::Vector2d(i % w + 0.5, i / w + 0.5);
  best->pixel_count = static_cast<int>(best->pixels.size());
  best->centroid_px = sum / best->pixel_count;
  return best;
}

double MedianDepth(const render::DepthImage& depth, const ColorBlob& blob) {
  std::vector<float> values;
  values.reserve(blob.pixels.size());
  for (int i : blob.pixels) {
    if (std::isfinite(depth.depth_m[i])) values.push_back(depth.depth_m[i]);
  }
  if (values.empty()) return std::numeric_limits<double>::infinity();
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace prs::sim
