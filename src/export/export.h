// Scene export for simulators and viewers: MJCF (MuJoCo), URDF (PyBullet, ROS), SDF (Gazebo),
// USD text (Isaac Sim) and glTF 2.0. A scene is first reduced to format-neutral bodies, with the
// rules of docs/export.md applied once (shape, colour, static or free, mass and inertia).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "export/color.h"
#include "lang/scene.h"

namespace prs::exporting {

enum class Format { kMjcf, kUrdf, kSdf, kUsda, kGltf, kGlb };

/// "mjcf", "urdf", "sdf", "usda", "gltf", "glb" (lowercase); nullopt for anything else.
std::optional<Format> ParseFormat(std::string_view name);
/// The format's name as ParseFormat reads it.
const char* FormatName(Format format);
/// The file extension with its dot: ".xml" for MJCF, ".urdf", ".sdf", ".usda", ".gltf", ".glb".
const char* FileExtension(Format format);
/// The format whose FileExtension is `extension` (with its dot); nullopt if none.
std::optional<Format> FormatFromExtension(std::string_view extension);
/// Every format name, comma-separated, for messages.
std::string ListFormatNames();

enum class Shape {
  kBox,       // width x length x height, centred on the body's origin
  kCylinder,  // axis along local z; radius min(width, length) / 2; length height
  kSphere,    // radius width / 2 (width = length = height)
  kCapsule,   // axis along local z; radius width / 2 (width = length <= height); total height
  kMesh,      // Body::mesh at Body::mesh_scale, its bounding box centred on the body's origin
  kNone,      // a point (some dimension is zero): a frame without geometry
};

/// One object as every exporter sees it.
struct Body {
  std::string name;        // unique in the scene, an identifier: [A-Za-z_][A-Za-z0-9_]*
  std::string class_name;  // "Cube"
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();            // metres
  Eigen::Quaterniond R_WO = Eigen::Quaterniond::Identity();  // local to world, unit
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // width (x), length (y), height (z), metres
  Shape shape = Shape::kBox;
  /// For Shape::kMesh: the mesh (shapes/mesh.h) and the factor on its file's coordinates.
  /// A built-in shape (`Cylinder()`, ...) has `primitive` set and `mesh` its polytope
  /// (shapes/primitive.h, scale 1, no file); its `shape` is the native one when it is round
  /// (kCylinder, kSphere, kCapsule), else kMesh (an elliptic cylinder, an ellipsoid).
  std::shared_ptr<const shapes::MeshShape> mesh;
  std::optional<shapes::Primitive> primitive;
  double mesh_scale = 1;
  Rgba color;
  double mass_kg = 0;  // > 0: a free body; 0: static (fixed in the world)
  Eigen::Vector3d inertia_diag = Eigen::Vector3d::Zero();  // kg m^2 about the centre, local axes
  bool collides = true;  // false for allowCollisions objects: visual geometry only
  /// A camera's vertical field of view (degrees), from its `fovy_deg` property as the
  /// language's `in view of` reads it; 45 when it has none.
  double fovy_deg = 45;

  bool is_free() const { return mass_kg > 0; }
  /// A cylinder's radius: it fits the box the sampler placed.
  double cylinder_radius() const { return std::min(size.x(), size.y()) / 2; }
  /// Whether `mesh` names a file (false for a built-in shape's polytope): URDF and SDF can
  /// only refer to meshes by file, so they write a file-less mesh as its box.
  bool has_mesh_file() const { return mesh && !mesh->path.empty(); }
};

/// A scene ready to be written; `title` names it inside the file ("seed 1 index 0").
struct ExportScene {
  std::string title;
  uint64_t seed = 0, index = 0;  // the scene's identity (spec §7): set by ReadSceneJson; by
                                 // the caller after MakeExportScene
  std::vector<Body> bodies;
  /// Properties the rules could not read (an unknown colour name, a mass that is not a
  /// positive number), one sentence each naming the object; the body falls back to a default.
  std::vector<std::string> warnings;
  /// A scene --settle let come to rest (lang::Scene::settled_s), or one being settled: the MJCF
  /// carries the contact model it was settled with, elliptic friction cones with impratio 10,
  /// which keeps a pile from creeping (docs/physics.md).
  bool settled = false;
  /// The room MuJoCo keeps for contacts (`<size nconmax njmax>`): this many a free body, each
  /// of 4 constraint rows; contacts past the room are dropped and bodies sink into each other.
  /// Exports keep 20, and MuJoCo 2.2's default (100 contacts) where that is more. The
  /// simulations of sim/stability.h first try less (StabilityOptions::
  /// first_contacts_per_free_body).
  int contacts_per_free_body = kExportContactsPerFreeBody;
  static constexpr int kExportContactsPerFreeBody = 20;
};

/// Applies the export rules (docs/export.md) to a sampled scene. Never throws for odd
/// properties: it falls back to a default and adds a warning.
ExportScene MakeExportScene(const lang::Scene& scene, std::string title);

/// A triangle mesh in a body's frame (metres), counter-clockwise seen from outside; each face
/// has its own vertices, so that each vertex's normal is its face's.
struct TriangleMesh {
  std::vector<float> positions;  // x y z per vertex
  std::vector<float> normals;    // unit, x y z per vertex
  std::vector<uint32_t> indices;  // three per triangle

  void AddVertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    for (int i = 0; i < 3; ++i) positions.push_back(float(p[i]));
    for (int i = 0; i < 3; ++i) normals.push_back(float(n[i]));
  }
  uint32_t vertex_count() const { return uint32_t(positions.size() / 3); }
};

/// The body's shape as triangles: a box's 12, a cylinder's 32-sided prism, a mesh's own (at its
/// scale), a sphere's or capsule's polytope; none for Shape::kNone.
TriangleMesh MakeBodyTriangles(const Body& body);

/// The volume of the body's solid shape in cubic metres: box, cylinder, sphere and capsule
/// exactly; a mesh or a built-in shape drawn as a polytope, its bounding box's; a point, 0.
double CalcVolume(const Body& body);

/// Makes `body` a free body of `mass_kg`, with the inertia the rules give an object of that
/// `mass` (a solid of its shape). Throws std::invalid_argument when `mass_kg` is not a positive
/// finite number or the body has no volume (Shape::kNone).
void SetMass(Body& body, double mass_kg);

/// Reads one line of a scenes file (spec §8, "prs-scene/1") and applies the export rules.
/// Throws std::invalid_argument with a message naming the missing or malformed field.
ExportScene ReadSceneJson(std::string_view line);

/// The scene in `format`: text for every format but kGlb, which is binary. Throws
/// std::runtime_error only if tinygltf cannot serialise a glTF model (not expected).
std::string WriteScene(const ExportScene& scene, Format format);

/// One MJCF `<mesh>` element with its data inline: `points_O` times `scale` as its vertices,
/// and `triangles` (indices into points_O) as its faces, or no faces when null (MuJoCo then
/// makes the points' convex hull). Shared by MJCF export and the renderer's model.
std::string FormatMjcfMesh(const std::string& name, const std::vector<Eigen::Vector3d>& points_O,
                           const std::vector<Eigen::Vector3i>* triangles, double scale);

}  // namespace prs::exporting
