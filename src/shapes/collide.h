// Collision tests between placed shapes (meshes and boxes) with FCL's bounding-volume
// hierarchies. Boxes against boxes keep geometry::DoBoxesOverlap (exact and faster); these are
// for pairs in which at least one object has a mesh.
//
// Touching is not overlapping, as for boxes (geometry::DoBoxesOverlap's tolerance): each shape
// is tested shrunk toward its centre so that no surface point moves by more than
// `touching_m`, so a mug standing on a shelf board (faces in one plane) does not collide with
// it, while any real interpenetration deeper than that does.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>

#include "shapes/mesh.h"

namespace prs::shapes {

/// A shape ready for FCL queries: a mesh at one scale, or a box. Immutable and shareable.
class Collider {
 public:
  /// `mesh` at `scale` (> 0), shrunk by `touching_m` (>= 0).
  static std::shared_ptr<const Collider> MakeMesh(const MeshShape& mesh, double scale,
                                                  double touching_m);
  /// A box of `half_extents` (>= 0), shrunk by `touching_m`.
  static std::shared_ptr<const Collider> MakeBox(const Eigen::Vector3d& half_extents,
                                                 double touching_m);
  ~Collider();
  Collider(const Collider&) = delete;
  Collider& operator=(const Collider&) = delete;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  explicit Collider(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Whether `a` placed at X_WA and `b` placed at X_WB intersect.
bool DoCollidersOverlap(const Collider& a, const Eigen::Isometry3d& X_WA, const Collider& b,
                        const Eigen::Isometry3d& X_WB);

}  // namespace prs::shapes
