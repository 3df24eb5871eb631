// SDFormat 1.9 world for Gazebo: a sun, a static ground plane, and one model per object (static
// for fixed objects, a link with mass and inertia for free ones), posed in the world frame.
// Written as text: libsdformat can print a loaded DOM, but building one element by element is
// longer than the few elements used here.
#include <fmt/format.h>

#include "export/writers.h"

namespace prs::exporting::internal {
namespace {

// A capsule's <length> is its straight part's; a built-in shape without a native form (an
// elliptic cylinder or capsule, an ellipsoid) is written as its box: SDF refers to meshes by
// file only.
std::string FormatGeometry(const Body& body) {
  if (body.shape == Shape::kSphere) {
    return fmt::format("<sphere><radius>{}</radius></sphere>", FormatNumber(body.size.x() / 2));
  }
  if (body.shape == Shape::kCapsule) {
    return fmt::format("<capsule><radius>{}</radius><length>{}</length></capsule>",
                       FormatNumber(body.size.x() / 2), FormatNumber(body.size.z() - body.size.x()));
  }
  if (body.shape == Shape::kMesh && body.has_mesh_file()) {
    const double s = body.mesh_scale;
    return fmt::format("<mesh><uri>{}</uri><scale>{}</scale></mesh>", FormatMeshUri(body),
                       FormatVector(Eigen::Vector3d(s, s, s)));
  }
  if (body.shape == Shape::kCylinder) {
    return fmt::format("<cylinder><radius>{}</radius><length>{}</length></cylinder>",
                       FormatNumber(body.cylinder_radius()), FormatNumber(body.size.z()));
  }
  return fmt::format("<box><size>{}</size></box>", FormatVector(body.size));
}

void AppendShape(const Body& body, std::string& out) {
  if (body.shape == Shape::kNone) return;
  const std::string geometry = FormatGeometry(body);
  const std::string rgba = FormatRgba(body.color);
  // A mesh file keeps its own frame: moved so that its bounding box is centred on the link.
  const std::string pose =
      body.shape == Shape::kMesh && body.has_mesh_file()
          ? fmt::format("<pose>{} 0 0 0</pose>", FormatVector(CalcMeshFileOffset(body)))
          : "";
  if (body.collides) {
    fmt::format_to(std::back_inserter(out),
                   "        <collision name=\"collision\">{}<geometry>{}</geometry></collision>\n",
                   pose, geometry);
  }
  fmt::format_to(std::back_inserter(out),
                 "        <visual name=\"visual\">{}\n          <geometry>{}</geometry>\n"
                 "          <material><ambient>{}</ambient><diffuse>{}</diffuse></material>\n"
                 "        </visual>\n",
                 pose, geometry, rgba, rgba);
}

void AppendInertial(const Body& body, std::string& out) {
  const Eigen::Vector3d& I = body.inertia_diag;
  fmt::format_to(std::back_inserter(out),
                 "        <inertial>\n          <mass>{}</mass>\n"
                 "          <inertia><ixx>{}</ixx><ixy>0</ixy><ixz>0</ixz><iyy>{}</iyy>"
                 "<iyz>0</iyz><izz>{}</izz></inertia>\n        </inertial>\n",
                 FormatNumber(body.mass_kg), FormatNumber(I.x()), FormatNumber(I.y()),
                 FormatNumber(I.z()));
}

void AppendModel(const Body& body, std::string& out) {
  fmt::format_to(std::back_inserter(out),
                 "    <model name=\"{}\">\n      <static>{}</static>\n"
                 "      <pose>{} {}</pose>\n      <link name=\"link\">\n",
                 body.name, body.is_free() ? "false" : "true", FormatVector(body.p_WO),
                 FormatVector(CalcRollPitchYaw(body.R_WO)));
  if (body.is_free()) AppendInertial(body, out);
  AppendShape(body, out);
  out += "      </link>\n    </model>\n";
}

}  // namespace

std::string WriteSdf(const ExportScene& scene) {
  const std::string plane = fmt::format("<plane><normal>0 0 1</normal><size>{0} {0}</size></plane>",
                                        FormatNumber(2 * kGroundHalfWidth));
  std::string out = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<!-- ProbRobScene scene {0} -->\n"
      "<sdf version=\"1.9\">\n  <world name=\"prs_scene\">\n"
      "    <gravity>0 0 {1}</gravity>\n"
      "    <light type=\"directional\" name=\"sun\">\n      <pose>0 0 5 0 0 0</pose>\n"
      "      <direction>0 0 -1</direction>\n    </light>\n"
      "    <model name=\"ground\">\n      <static>true</static>\n      <link name=\"link\">\n"
      "        <collision name=\"collision\"><geometry>{2}</geometry></collision>\n"
      "        <visual name=\"visual\"><geometry>{2}</geometry></visual>\n"
      "      </link>\n    </model>\n",
      scene.title, FormatNumber(-kGravity), plane);
  for (const Body& body : scene.bodies) AppendModel(body, out);
  out += "  </world>\n</sdf>\n";
  return out;
}

}  // namespace prs::exporting::internal
