// The original tool's mask-based cube estimate (see paper_perception.h).
#include "sim/paper_perception.h"

#include <algorithm>
#include <cmath>

namespace prs::sim {

std::optional<MaskEstimate> EstimateFromMask(const render::DepthImage& depth_of_target,
                                             const MaskCamera& camera) {
  const int w = depth_of_target.width, h = depth_of_target.height;
  const std::vector<float>& d = depth_of_target.depth_m;
  int first = -1, last = -1;
  for (int i = 0; i < w * h; ++i) {
    if (!std::isfinite(d[i])) continue;
    if (first < 0) first = i;
    last = i;
  }
  if (first < 0) return std::nullopt;
  MaskEstimate e;
  e.first_px = Eigen::Vector2d(first % w, first / w);
  e.last_px = Eigen::Vector2d(last % w, last / w);
  e.middle_px = (e.first_px + e.last_px) / 2;
  // CoppeliaSim's depth buffer: linear between the clipping planes, 1 where nothing was drawn.
  const float here = d[int(e.middle_px.y()) * w + int(e.middle_px.x())];
  const double range_m = camera.far_m - camera.near_m;
  e.depth_raw = std::isfinite(here) ? std::clamp((here - camera.near_m) / range_m, 0.0, 1.0) : 1.0;
  e.depth_m = camera.near_m + range_m * e.depth_raw;
  const double bx = e.middle_px.x() / w, by = e.middle_px.y() / h;
  const double t = std::tan(camera.perspective_angle_rad / 2);
  e.p_S =
      Eigen::Vector3d(e.depth_m * t * (0.5 - bx) * 2, e.depth_m * t * (0.5 - by) * 2, e.depth_m);
  const Eigen::Vector3d p_C(-e.p_S.x(), e.p_S.y(), -e.p_S.z());
  e.p_W = camera.X_WC * p_C;
  return e;
}

}  // namespace prs::sim
