// Convex pieces of a mesh, for simulators that collide convex shapes only: MuJoCo collides a
// mesh geom as its convex hull, so a bowl exported whole would be a solid dome and a shelf a
// solid block. Exports give such simulators one hull per piece instead (docs/export.md).
//
// Pieces: each connected part of the mesh that is convex (a shelf's board, a box) is one piece,
// exactly; a part that is not (a bowl, a mug's cup) is split by HACD, the hierarchical
// approximate convex decomposition in Debian's Bullet extras (libbullet-extras-dev), whose
// pieces' hulls follow the surface to within about 2 % of the part's size. Frames and units as
// in mesh.h (`_O`, the file's units at scale 1).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "shapes/mesh.h"

namespace prs::shapes {

/// One convex piece: the points whose convex hull it is (at least four, not all in a plane).
struct ConvexPiece {
  std::vector<Eigen::Vector3d> points_O;
};

/// The mesh's convex pieces (see above). A part too thin to have a volume (a single triangle,
/// a flat sheet) gives no piece: it has nothing for a simulator's hull to hold. Deterministic;
/// computed once per distinct mesh content and then shared (HACD takes about a second for a
/// 2,000-triangle bowl), safe to call from several threads.
std::shared_ptr<const std::vector<ConvexPiece>> CalcConvexPieces(const MeshShape& shape);

/// Whether a closed connected surface is convex: every vertex lies on one side of every
/// triangle's plane, within `tolerance` (metres in the mesh's units).
bool IsConvexSurface(const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<Eigen::Vector3i>& triangles, double tolerance);

/// The mesh's connected parts: triangles that share a vertex (by index) are in one part.
/// Each part is returned as its own TriangleMesh with its vertices renumbered.
std::vector<TriangleMesh> SplitConnectedParts(const TriangleMesh& mesh);

}  // namespace prs::shapes
