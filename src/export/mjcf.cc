// MJCF for MuJoCo: one body per object under the worldbody, static bodies welded to the world,
// free bodies with a free joint and an explicit inertial; a ground plane at z = 0. A mesh body
// has its triangles as a visual geom and its convex pieces (shapes/decompose.h) as collision
// geoms, since MuJoCo collides each mesh geom as its convex hull.
// Written as text: MuJoCo has no writer for models it did not compile itself (mj_saveLastXML
// needs a loaded model), and the elements used here are few.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <algorithm>
#include <optional>
#include <utility>

#include "export/writers.h"
#include "shapes/decompose.h"

namespace prs::exporting::internal {
namespace {

// Rolling friction of a free can's side (AppendCylinderSpine), in metres: a lying can stays put
// on a slope under atan(1 mm / r), about 1.7° for a 66 mm can. More than a metal can meets on a
// hard floor (tenths of a millimetre); the least of those tried that stopped the cans of
// examples/bin_pile.prs rolling in place (0.1 mm did not).
constexpr double kCanRollingFriction_m = 0.001;

std::string FormatQuaternion(const Eigen::Quaterniond& R) {  // MuJoCo's order: w x y z
  return FormatNumber(R.w()) + " " + FormatNumber(R.x()) + " " + FormatNumber(R.y()) + " " +
         FormatNumber(R.z());
}

// The mesh assets of a scene: one set per distinct mesh and scale, shared by its bodies. The
// convex pieces (HACD, about a second per mesh) are made only for meshes a colliding body uses.
class MeshAssets {
 public:
  struct Entry {
    std::string name;  // "mesh3"; its convex pieces are "mesh3_piece0", "mesh3_piece1", ...
    std::optional<size_t> piece_count;  // set once the pieces are written
  };

  // The body's mesh asset, and its pieces when `with_pieces`.
  const Entry& Of(const Body& body, bool with_pieces) {
    const auto key = std::make_pair(body.mesh.get(), body.mesh_scale);
    auto it = entries_.find(key);
    if (it == entries_.end()) {
      it = entries_.emplace(key, Entry{"mesh" + std::to_string(entries_.size()), std::nullopt})
               .first;
      Append(FormatMjcfMesh(it->second.name, body.mesh->mesh.vertices_O,
                            &body.mesh->mesh.triangles, body.mesh_scale));
    }
    Entry& entry = it->second;
    if (with_pieces && !entry.piece_count) {
      const auto pieces = shapes::CalcConvexPieces(*body.mesh);
      for (size_t k = 0; k < pieces->size(); ++k) {
        Append(FormatMjcfMesh(entry.name + "_piece" + std::to_string(k), (*pieces)[k].points_O,
                              nullptr, body.mesh_scale));
      }
      entry.piece_count = pieces->size();
    }
    return entry;
  }
  // The <mesh> elements, one per line.
  const std::string& text() const { return text_; }

 private:
  void Append(const std::string& element) { text_ += "    " + element + "\n"; }

  std::map<std::pair<const shapes::MeshShape*, double>, Entry> entries_;
  std::string text_;
};

// MuJoCo sizes are half-extents; a cylinder's are radius and half-height, a capsule's radius
// and the half-length of its straight part.
std::string FormatGeomType(const Body& body) {
  if (body.shape == Shape::kSphere) return fmt::format("type=\"sphere\" size=\"{}\"", FormatNumber(body.size.x() / 2));
  if (body.shape == Shape::kCapsule) {
    return fmt::format("type=\"capsule\" size=\"{} {}\"", FormatNumber(body.size.x() / 2),
                       FormatNumber((body.size.z() - body.size.x()) / 2));
  }
  if (body.shape == Shape::kCylinder) {
    const double radius = body.cylinder_radius();
    return fmt::format("type=\"cylinder\" size=\"{} {}\"", FormatNumber(radius),
                       FormatNumber(body.size.z() / 2));
  }
  return fmt::format("type=\"box\" size=\"{}\"", FormatVector(body.size / 2));
}

// MuJoCo 2.2 touches a cylinder and a box at one point, so an upright can on a table rocks
// and tilts by several degrees. A box inscribed in the cylinder (a square of side r·√2, the
// cylinder's height; hidden, group 3) gives its flat ends the box-box collider's several
// contacts. It lies inside the cylinder, so it never touches anything first elsewhere. Free
// bodies carry an explicit inertial, so it adds no mass.
void AppendCylinderFoot(const Body& body, std::string& out) {
  const double half_side = body.cylinder_radius() / std::sqrt(2.0);
  fmt::format_to(std::back_inserter(out),
                 "      <geom name=\"{}_foot\" type=\"box\" size=\"{} {} {}\" group=\"3\" "
                 "rgba=\"{}\"/>\n",
                 body.name, FormatNumber(half_side), FormatNumber(half_side),
                 FormatNumber(body.size.z() / 2), FormatRgba(body.color));
}

// A free can on its side touches a box at one point too, and nothing stops it rolling: in a pile
// it jitters and rolls in place for as long as it is simulated. A capsule inscribed along the
// cylinder's axis (its radius, ending at the flat ends; hidden) lies along its side, so a lying
// can gets the capsule-box collider's two contacts, and rolling friction (condim 6) stops it as
// a real can stops. A squat cylinder (no longer than its diameter) has no such capsule; it lies
// on a flat end.
void AppendCylinderSpine(const Body& body, std::string& out) {
  const double radius = body.cylinder_radius(), half_length = body.size.z() / 2 - radius;
  if (half_length <= 0) return;
  fmt::format_to(std::back_inserter(out),
                 "      <geom name=\"{}_spine\" type=\"capsule\" size=\"{} {}\" condim=\"6\" "
                 "friction=\"1 0.005 {}\" group=\"3\" rgba=\"{}\"/>\n",
                 body.name, FormatNumber(radius), FormatNumber(half_length),
                 FormatNumber(kCanRollingFriction_m), FormatRgba(body.color));
}

// A MuJoCo camera looks along its -z with +y up; a scene's camera looks along its forward +y
// with +z up. The quarter turn about x maps one onto the other.
bool IsCamera(const Body& body) { return body.class_name == "Camera"; }

// A mesh body: its triangles drawn (group 1, no contacts), its convex pieces colliding (group 3,
// hidden in MuJoCo's default view).
void AppendMeshGeoms(const Body& body, MeshAssets& assets, std::string& out) {
  const MeshAssets::Entry& mesh = assets.Of(body, body.collides);
  const std::string rgba = FormatRgba(body.color);
  fmt::format_to(std::back_inserter(out),
                 "      <geom name=\"{}\" type=\"mesh\" mesh=\"{}\" rgba=\"{}\" group=\"1\" "
                 "contype=\"0\" conaffinity=\"0\"/>\n",
                 body.name, mesh.name, rgba);
  if (!body.collides) return;
  for (size_t k = 0; k < *mesh.piece_count; ++k) {
    fmt::format_to(std::back_inserter(out),
                   "      <geom name=\"{}_piece{}\" type=\"mesh\" mesh=\"{}_piece{}\" rgba=\"{}\" "
                   "group=\"3\"/>\n",
                   body.name, k, mesh.name, k, rgba);
  }
}

void AppendBody(const Body& body, MeshAssets& assets, std::string& out) {
  fmt::format_to(std::back_inserter(out), "    <body name=\"{}\" pos=\"{}\" quat=\"{}\">\n",
                 body.name, FormatVector(body.p_WO), FormatQuaternion(body.R_WO));
  if (body.is_free()) {
    fmt::format_to(std::back_inserter(out),
                   "      <freejoint name=\"{}_free\"/>\n"
                   "      <inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{}\"/>\n",
                   body.name, FormatNumber(body.mass_kg), FormatVector(body.inertia_diag));
  }
  if (body.shape == Shape::kMesh) {
    AppendMeshGeoms(body, assets, out);
  } else if (body.shape != Shape::kNone) {
    fmt::format_to(std::back_inserter(out), "      <geom name=\"{}\" {} rgba=\"{}\"{}/>\n",
                   body.name, FormatGeomType(body), FormatRgba(body.color),
                   body.collides ? "" : " contype=\"0\" conaffinity=\"0\"");
    if (body.shape == Shape::kCylinder && body.collides) {
      AppendCylinderFoot(body, out);
      if (body.is_free()) AppendCylinderSpine(body, out);
    }
  }
  if (IsCamera(body)) {
    fmt::format_to(std::back_inserter(out),
                   "      <camera name=\"{}\" quat=\"{} {} 0 0\" fovy=\"{}\"/>\n", body.name,
                   FormatNumber(std::sqrt(0.5)), FormatNumber(std::sqrt(0.5)),
                   FormatNumber(body.fovy_deg));
  }
  out += "    </body>\n";
}

// MuJoCo 2.2 keeps room for 100 contacts and 500 constraint rows unless told otherwise; a pile
// of free bodies touches in more places than that, and contacts past the room are dropped
// (bodies then sink into each other). Room for ExportScene::contacts_per_free_body contacts a
// free body, each of 4 rows; exports leave MuJoCo's default where it is room enough.
std::string SizeElement(const ExportScene& scene) {
  int free_bodies = 0;
  for (const Body& body : scene.bodies) free_bodies += body.is_free() && body.collides;
  constexpr int kRowsPerContact = 4;
  const int contacts = free_bodies * scene.contacts_per_free_body;
  const bool exported = scene.contacts_per_free_body == ExportScene::kExportContactsPerFreeBody;
  if (free_bodies == 0 || (exported && contacts <= 100)) return "";
  return fmt::format("  <size nconmax=\"{}\" njmax=\"{}\"/>\n", contacts,
                     std::max(500, contacts * kRowsPerContact));
}

}  // namespace

std::string WriteMjcf(const ExportScene& scene) {
  MeshAssets assets;
  std::string bodies;
  for (const Body& body : scene.bodies) AppendBody(body, assets, bodies);
  std::string out = fmt::format(
      "<!-- ProbRobScene scene {}: load with mujoco.MjModel.from_xml_path or `simulate` -->\n"
      "<mujoco model=\"prs_scene\">\n"
      "  <compiler angle=\"radian\" autolimits=\"true\"/>\n"
      "  <option gravity=\"0 0 {}\"{}/>\n{}{}"
      "  <worldbody>\n"
      "    <light name=\"sun\" pos=\"0 0 5\" dir=\"0 0 -1\" directional=\"true\"/>\n"
      "    <geom name=\"ground\" type=\"plane\" size=\"0 0 0.05\" rgba=\"0.9 0.9 0.9 1\"/>\n",
      scene.title, FormatNumber(-kGravity),
      scene.settled ? " cone=\"elliptic\" impratio=\"10\"" : "", SizeElement(scene),
      assets.text().empty() ? "" : "  <asset>\n" + assets.text() + "  </asset>\n");
  out += bodies;
  out += "  </worldbody>\n</mujoco>\n";
  return out;
}

}  // namespace prs::exporting::internal

namespace prs::exporting {

std::string FormatMjcfMesh(const std::string& name, const std::vector<Eigen::Vector3d>& points_O,
                           const std::vector<Eigen::Vector3i>* triangles, double scale) {
  std::string out = "<mesh name=\"" + name + "\" vertex=\"";
  for (size_t i = 0; i < points_O.size(); ++i) {
    if (i > 0) out += ' ';
    out += internal::FormatVector(points_O[i] * scale);
  }
  out += '"';
  if (triangles) {
    out += " face=\"";
    for (size_t i = 0; i < triangles->size(); ++i) {
      const Eigen::Vector3i& t = (*triangles)[i];
      fmt::format_to(std::back_inserter(out), "{}{} {} {}", i > 0 ? " " : "", t[0], t[1], t[2]);
    }
    out += '"';
  }
  return out + "/>";
}

}  // namespace prs::exporting
