// URDF for PyBullet and ROS tools: one robot whose root link "world" holds a ground slab and one
// link per object, joined by a fixed joint (static objects) or a floating joint (free bodies).
// Written as text for the same reason as MJCF: urdfdom reads URDF but has no writer.
#include <fmt/format.h>

#include "export/writers.h"

namespace prs::exporting::internal {
namespace {

// URDF has no capsule: a round capsule is written as the cylinder around it (its radius and
// whole height), which holds it; a built-in shape without a native form as its box.
std::string FormatGeometry(const Body& body) {
  if (body.shape == Shape::kSphere) {
    return fmt::format("<sphere radius=\"{}\"/>", FormatNumber(body.size.x() / 2));
  }
  if (body.shape == Shape::kMesh && body.has_mesh_file()) {
    const double s = body.mesh_scale;
    return fmt::format("<mesh filename=\"{}\" scale=\"{}\"/>", FormatMeshUri(body),
                       FormatVector(Eigen::Vector3d(s, s, s)));
  }
  if (body.shape == Shape::kCylinder || body.shape == Shape::kCapsule) {
    return fmt::format("<cylinder radius=\"{}\" length=\"{}\"/>",
                       FormatNumber(body.cylinder_radius()), FormatNumber(body.size.z()));
  }
  return fmt::format("<box size=\"{}\"/>", FormatVector(body.size));
}

void AppendLink(const Body& body, std::string& out) {
  fmt::format_to(std::back_inserter(out), "  <link name=\"{}\">\n", body.name);
  if (body.shape != Shape::kNone) {
    const std::string geometry = FormatGeometry(body);
    // A mesh file keeps its own frame: moved so that its bounding box is centred on the link.
    const std::string origin =
        body.shape == Shape::kMesh && body.has_mesh_file()
            ? fmt::format("<origin xyz=\"{}\"/>", FormatVector(CalcMeshFileOffset(body)))
            : "";
    fmt::format_to(std::back_inserter(out),
                   "    <visual>\n      {}<geometry>{}</geometry>\n"
                   "      <material name=\"{}_color\"><color rgba=\"{}\"/></material>\n"
                   "    </visual>\n",
                   origin, geometry, body.name, FormatRgba(body.color));
    if (body.collides) {
      fmt::format_to(std::back_inserter(out),
                     "    <collision>\n      {}<geometry>{}</geometry>\n    </collision>\n",
                     origin, geometry);
    }
  }
  if (body.is_free()) {
    const Eigen::Vector3d& I = body.inertia_diag;
    fmt::format_to(
        std::back_inserter(out),
        "    <inertial>\n      <mass value=\"{}\"/>\n"
        "      <inertia ixx=\"{}\" ixy=\"0\" ixz=\"0\" iyy=\"{}\" iyz=\"0\" izz=\"{}\"/>\n"
        "    </inertial>\n",
        FormatNumber(body.mass_kg), FormatNumber(I.x()), FormatNumber(I.y()), FormatNumber(I.z()));
  }
  out += "  </link>\n";
}

void AppendJoint(const std::string& child, const char* type, const Eigen::Vector3d& p_WO,
                 const Eigen::Vector3d& rpy, std::string& out) {
  fmt::format_to(std::back_inserter(out),
                 "  <joint name=\"{0}_joint\" type=\"{1}\">\n"
                 "    <parent link=\"world\"/>\n    <child link=\"{0}\"/>\n"
                 "    <origin xyz=\"{2}\" rpy=\"{3}\"/>\n  </joint>\n",
                 child, type, FormatVector(p_WO), FormatVector(rpy));
}

void AppendGround(std::string& out) {
  const Eigen::Vector3d size(2 * kGroundHalfWidth, 2 * kGroundHalfWidth, kGroundThickness);
  fmt::format_to(
      std::back_inserter(out),
      "  <link name=\"ground\">\n"
      "    <visual>\n      <geometry><box size=\"{0}\"/></geometry>\n"
      "      <material name=\"ground_color\"><color rgba=\"0.9 0.9 0.9 1\"/></material>\n"
      "    </visual>\n"
      "    <collision>\n      <geometry><box size=\"{0}\"/></geometry>\n"
      "    </collision>\n  </link>\n",
      FormatVector(size));
  AppendJoint("ground", "fixed", Eigen::Vector3d(0, 0, -kGroundThickness / 2),
              Eigen::Vector3d::Zero(), out);
}

}  // namespace

std::string WriteUrdf(const ExportScene& scene) {
  std::string out = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<!-- ProbRobScene scene {}: static objects hang from \"world\" by fixed joints, free ones "
      "by floating joints -->\n"
      "<robot name=\"prs_scene\">\n  <link name=\"world\"/>\n",
      scene.title);
  AppendGround(out);
  for (const Body& body : scene.bodies) {
    AppendLink(body, out);
    AppendJoint(body.name, body.is_free() ? "floating" : "fixed", body.p_WO,
                CalcRollPitchYaw(body.R_WO), out);
  }
  out += "</robot>\n";
  return out;
}

}  // namespace prs::exporting::internal
