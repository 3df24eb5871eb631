// The original tool's perception for the Table-Cube case study, as its CoppeliaSim controller
// did it: the depth camera renders the cube alone (its mask: no arm can hide it), the estimate
// is at the midpoint of the mask's first and last pixels in raster order, at the depth read
// there, back-projected with one perspective angle for both image axes. A pure function of
// the depth image, so it is tested against a computation by hand.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

#include "render/render.h"

namespace prs::sim {

/// The camera as the original's estimate uses it: its pose (MuJoCo's convention, looking along
/// its frame's −z with +y up), clipping planes, and one perspective angle, which CoppeliaSim
/// gives for the image's larger side and the estimate applies to both (exact for a square
/// image, as the original's 256 × 256 one was).
struct MaskCamera {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  double near_m = 0.01, far_m = 10;
  double perspective_angle_rad = 0;
};

/// The estimate and the numbers it was made from.
struct MaskEstimate {
  Eigen::Vector2d first_px, last_px;  // the mask's first and last pixels in raster order (x, y)
  Eigen::Vector2d middle_px;          // their midpoint (pixel indices, not pixel centres)
  double depth_raw = 1;               // the depth buffer there: 0 at the near plane, 1 at far
  double depth_m = 0;                 // mapped linearly between the clipping planes
  Eigen::Vector3d p_S = Eigen::Vector3d::Zero();  // in CoppeliaSim's sensor frame (below)
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // in the world: the point on the object seen
};

/// The original's estimate from a depth image in which only the target was rendered
/// (render::ModelRenderer::Render with only_body): its mask is every pixel with a finite depth.
/// The depth is normalised between the camera's clipping planes, as CoppeliaSim's depth
/// buffer is (1 where nothing was drawn), read at the midpoint pixel (its indices truncated)
/// and mapped back linearly. With bx = x / width and by = y / height, the point in
/// CoppeliaSim's sensor frame S (x to the image's left, y up, z along the view) is
/// (d tan(a/2)(0.5 − bx)·2, d tan(a/2)(0.5 − by)·2, d), turned into MuJoCo's camera frame
/// (x right, y up, looking along −z) by diag(−1, 1, −1). nullopt when the mask is empty.
std::optional<MaskEstimate> EstimateFromMask(const render::DepthImage& depth_of_target,
                                             const MaskCamera& camera);

}  // namespace prs::sim
