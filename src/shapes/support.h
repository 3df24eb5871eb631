// Where things can stand on a mesh (spec §10, `on MESH_OBJECT`): its upward-facing surfaces.
// Triangles whose normal is within kSupportTiltRad of the mesh's +z are grouped into planar
// pieces: triangles that share an edge and lie in one plane form one piece, kept as one convex
// polygon when their union is convex (a board's top, a bowl's floor) and as its triangles
// otherwise (each convex). Frames and units as in mesh.h (`_O`, scale 1).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace prs::shapes {

struct TriangleMesh;

/// Faces tilted at most this much from the mesh's +z are surfaces to stand on (5 degrees).
inline constexpr double kSupportTiltRad = 5.0 * 3.14159265358979323846 / 180;

/// One convex planar piece of surface, facing `normal_O` (unit, within the tilt of +z).
struct SupportPolygon {
  std::vector<Eigen::Vector3d> vertices_O;  // coplanar; their convex hull is the piece
  Eigen::Vector3d normal_O = Eigen::Vector3d::UnitZ();
  double area = 0;  // m² at scale 1
};

/// The mesh's upward-facing surfaces as convex pieces (see above), largest first.
std::vector<SupportPolygon> CalcSupportPolygons(const TriangleMesh& mesh,
                                                double max_tilt_rad = kSupportTiltRad);

/// The area of the convex hull of coplanar points (qhull in the plane's own 2-D coordinates);
/// 0 for fewer than three points or collinear ones.
double CalcPlanarHullArea(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal);

}  // namespace prs::shapes
