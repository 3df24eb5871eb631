// MJCF for MuJoCo: one body per object under the worldbody, static bodies welded to the world,
// free bodies with a free joint and an explicit inertial; a ground plane at z = 0.
// Written as text: MuJoCo has no writer for models it did not compile itself (mj_saveLastXML
// needs a loaded model), and the elements used here are few.
#include <fmt/format.h>

#include <cmath>

#include "export/writers.h"

namespace prs::exporting::internal {
namespace {

std::string FormatQuaternion(const Eigen::Quaterniond& R) {  // MuJoCo's order: w x y z
  return FormatNumber(R.w()) + " " + FormatNumber(R.x()) + " " + FormatNumber(R.y()) + " " +
         FormatNumber(R.z());
}

// MuJoCo sizes are half-extents; a cylinder's are radius and half-height.
std::string FormatGeomType(const Body& body) {
  if (body.shape == Shape::kCylinder) {
    const double radius = body.cylinder_radius();
    return fmt::format("type=\"cylinder\" size=\"{} {}\"", FormatNumber(radius),
                       FormatNumber(body.size.z() / 2));
  }
  return fmt::format("type=\"box\" size=\"{}\"", FormatVector(body.size / 2));
}

// A MuJoCo camera looks along its -z with +y up; a scene's camera looks along its forward +y
// with +z up. The quarter turn about x maps one onto the other.
bool IsCamera(const Body& body) { return body.class_name == "Camera"; }

void AppendBody(const Body& body, std::string& out) {
  fmt::format_to(std::back_inserter(out), "    <body name=\"{}\" pos=\"{}\" quat=\"{}\">\n",
                 body.name, FormatVector(body.p_WO), FormatQuaternion(body.R_WO));
  if (body.is_free()) {
    fmt::format_to(std::back_inserter(out),
                   "      <freejoint name=\"{}_free\"/>\n"
                   "      <inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{}\"/>\n",
                   body.name, FormatNumber(body.mass_kg), FormatVector(body.inertia_diag));
  }
  if (body.shape != Shape::kNone) {
    fmt::format_to(std::back_inserter(out), "      <geom name=\"{}\" {} rgba=\"{}\"{}/>\n",
                   body.name, FormatGeomType(body), FormatRgba(body.color),
                   body.collides ? "" : " contype=\"0\" conaffinity=\"0\"");
  }
  if (IsCamera(body)) {
    fmt::format_to(std::back_inserter(out),
                   "      <camera name=\"{}\" quat=\"{} {} 0 0\" fovy=\"{}\"/>\n", body.name,
                   FormatNumber(std::sqrt(0.5)), FormatNumber(std::sqrt(0.5)),
                   FormatNumber(body.fovy_deg));
  }
  out += "    </body>\n";
}

}  // namespace

std::string WriteMjcf(const ExportScene& scene) {
  std::string out = fmt::format(
      "<!-- ProbRobScene scene {}: load with mujoco.MjModel.from_xml_path or `simulate` -->\n"
      "<mujoco model=\"prs_scene\">\n"
      "  <compiler angle=\"radian\" autolimits=\"true\"/>\n"
      "  <option gravity=\"0 0 {}\"/>\n"
      "  <worldbody>\n"
      "    <light name=\"sun\" pos=\"0 0 5\" dir=\"0 0 -1\" directional=\"true\"/>\n"
      "    <geom name=\"ground\" type=\"plane\" size=\"0 0 0.05\" rgba=\"0.9 0.9 0.9 1\"/>\n",
      scene.title, FormatNumber(-kGravity));
  for (const Body& body : scene.bodies) AppendBody(body, out);
  out += "  </worldbody>\n</mujoco>\n";
  return out;
}

}  // namespace prs::exporting::internal
