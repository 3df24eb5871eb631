// Object shapes from mesh files (spec §10): a triangle mesh read with assimp, put in the
// object's frame (its axis-aligned bounding box centred on the origin), checked, and reduced to
// its convex hull's vertices (qhull) for exact containment. Below the language; no MuJoCo.
//
// Frames and units: `_O` is the object's frame before scaling: the file's axes and units,
// translated so that the bounding box's centre is the origin. A program scales a mesh by a
// number (`Mesh("mug.obj", scale=0.001)`); everything here is at scale 1 and callers multiply.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "shapes/support.h"

namespace prs::shapes {

/// A bad mesh file; `what()` is a message for the user in our words (never assimp's or qhull's).
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices_O;
  std::vector<Eigen::Vector3i> triangles;  // indices into vertices_O, as the file orders them
};

/// A mesh ready for placement. Immutable once loaded; shared by every scene and thread.
struct MeshShape {
  std::string name;  // as the program names it, e.g. "assets/mug.obj"
  std::string path;  // where it was read
  TriangleMesh mesh;  // bounding-box centre at the origin, file units
  /// Where the bounding box's centre is in the file's own coordinates (exports that name the
  /// file itself shift it by this much).
  Eigen::Vector3d p_FileCenter = Eigen::Vector3d::Zero();
  Eigen::Vector3d extents = Eigen::Vector3d::Zero();  // bounding box size along x, y, z
  /// The vertices of the convex hull (a subset of mesh.vertices_O). The mesh lies in a convex
  /// region iff all of these do, so containment erodes by them (geometry::ErodeByPoints).
  std::vector<Eigen::Vector3d> hull_O;
  /// Its upward-facing surfaces as convex pieces, for `on` this mesh (support.h).
  std::vector<SupportPolygon> supports_O;
  /// Edges used by exactly one triangle (0 for a closed surface) and triangles of zero area
  /// (dropped when loading): reported as warnings, the mesh is still usable.
  int open_edges = 0;
  int degenerate_triangles = 0;
};

/// The file formats read, by lower-case extension: "obj", "stl", "ply", "gltf", "glb".
bool IsSupportedMeshExtension(std::string_view extension);
/// "OBJ, STL, PLY, glTF (.gltf with embedded buffers, .glb)", for messages.
const char* SupportedMeshFormats();

/// Reads a mesh from a file's bytes; the format comes from `name`'s extension. Every triangle
/// of every mesh in the file, with the file's node transforms applied. Throws MeshError for an
/// unsupported extension, a file assimp cannot read, a file with no triangles, or a vertex
/// whose coordinates are not finite numbers (named by its number, counted from 1: an OBJ's
/// `v` lines with the line, an STL's facet corners). A mesh flat along an axis is kept (its
/// hull is then the vertex set itself).
std::shared_ptr<const MeshShape> LoadMeshShape(std::string_view bytes, const std::string& name,
                                               const std::string& path);

/// The points among `points` that are vertices of their convex hull (qhull); all of them when
/// they span less than three dimensions (a flat or degenerate set), which is still exact for
/// support functions. Empty input gives an empty result.
std::vector<Eigen::Vector3d> CalcConvexHullVertices(const std::vector<Eigen::Vector3d>& points);

/// Warnings a user should see about a loaded mesh at `scale` (each one sentence, without the
/// file name): open edges, degenerate triangles, and sizes that suggest wrong units (larger
/// than 20 m or smaller than 2 mm across at that scale).
std::vector<std::string> DescribeMeshWarnings(const MeshShape& shape, double scale);

}  // namespace prs::shapes
