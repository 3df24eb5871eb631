// Facet planes of a convex hull (hull_planes.h), from qhull's facets.
#include "shapes/hull_planes.h"

#include "shapes/qhull_session.h"

namespace prs::shapes {

std::vector<HullPlane> CalcHullPlanes(const std::vector<Eigen::Vector3d>& points) {
  std::vector<HullPlane> planes;
  if (points.size() < 4) return planes;
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Eigen::Vector3d& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  // qhull's facet hyperplanes: normal · p + offset = 0 on the facet, normal outward and unit.
  const int status = internal::RunQhull(3, coordinates, "qhull", [&](qhT* qh) {
    facetT* facet;
    FORALLfacets {
      planes.push_back({Eigen::Vector3d(facet->normal[0], facet->normal[1], facet->normal[2]),
                        -facet->offset});
    }
  });
  if (status != 0) planes.clear();  // flat or degenerate: no interior
  return planes;
}

}  // namespace prs::shapes
