// The facets of a mesh's convex hull as planes, for the footprint common to every turn of an
// object whose orientation is not known when its position is drawn (the round core: the
// largest disk or ball about the object's centre inside its hull). Kept apart from mesh.h,
// which the language includes everywhere.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace prs::shapes {

/// A facet's plane: the hull lies where normal_O · p <= offset_m (normal_O a unit vector,
/// pointing out of the hull).
struct HullPlane {
  Eigen::Vector3d normal_O;
  double offset_m = 0;
};

/// The facet planes of the convex hull of `points` (qhull). Empty when the points span fewer
/// than three dimensions (a flat set has no interior).
std::vector<HullPlane> CalcHullPlanes(const std::vector<Eigen::Vector3d>& points);

}  // namespace prs::shapes
