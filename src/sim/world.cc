// The simulated world from a scene (see world.h).
#include "sim/world.h"

#include <fmt/format.h>

#include <stdexcept>

#include "kinematics/mount.h"
#include "sim/control.h"
#include "sim/mjcf_text.h"

namespace prs::sim {

namespace {

// The world's extent (MuJoCo's stat.extent) in metres: see WriteWorldMjcf.
constexpr double kWorldExtentM = 3.0;

// The simulated camera's offscreen buffer, the size of the largest image a controller renders
// (the case study's 640 x 480; the original's 256 x 256 fits), and its shadow map, the size
// `prs render`'s pictures use (MuJoCo's default is 4096). Both are rendered on the CPU by
// Mesa's llvmpipe, one picture at a time per process (its rasterizer is shared by every
// context): a larger buffer is cleared for nothing, and the 4096² shadow map cost 12 % of an
// episode while moving only shadow-edge pixels (docs/benchmarks.md, the case study).
constexpr int kCameraBufferWidthPx = 640;
constexpr int kCameraBufferHeightPx = 480;
constexpr int kShadowMapSizePx = 2048;

using internal::FormatQuat;
using internal::FormatVector;

// Four static walls around the tray's top face, in the tray's frame.
std::string WriteTrayWalls(const exporting::Body& tray) {
  const double half_w = tray.size.x() / 2, half_l = tray.size.y() / 2, t = kTrayWallThickness_m;
  const double z = tray.size.z() / 2 + kTrayWallHeight_m / 2;
  const struct {
    Eigen::Vector3d p_TW, half;
  } walls[] = {
      {{-(half_w + t / 2), 0, z}, {t / 2, half_l + t, kTrayWallHeight_m / 2}},
      {{half_w + t / 2, 0, z}, {t / 2, half_l + t, kTrayWallHeight_m / 2}},
      {{0, -(half_l + t / 2), z}, {half_w, t / 2, kTrayWallHeight_m / 2}},
      {{0, half_l + t / 2, z}, {half_w, t / 2, kTrayWallHeight_m / 2}},
  };
  std::string xml = fmt::format(R"(<body name="{}_walls" pos="{}" quat="{}">)", tray.name,
                                FormatVector(tray.p_WO), FormatQuat(tray.R_WO));
  for (const auto& w : walls) {
    xml += fmt::format(R"(<geom type="box" pos="{}" size="{}" rgba="0.45 0.45 0.45 1"/>)",
                       FormatVector(w.p_TW), FormatVector(w.half));
  }
  return xml + "</body>";
}

void InsertBefore(std::string& xml, const std::string& marker, const std::string& text) {
  const size_t at = xml.rfind(marker);
  if (at == std::string::npos) throw std::logic_error("the exported MJCF has no " + marker);
  xml.insert(at, text);
}

// In the simulated world the arm is the robot, so each Robot object keeps its body (a frame,
// named as exported) but loses its box. A solid box would enclose the arm's links and push
// them apart; a visual-only one would still hide the arm, and a 1 m tall one (the Panda's
// real size) most of the table, from the ceiling camera. prs export keeps the boxes.
exporting::ExportScene WithoutRobotGeometry(exporting::ExportScene scene) {
  for (exporting::Body& b : scene.bodies) {
    if (b.class_name == "Robot") b.shape = exporting::Shape::kNone;
  }
  return scene;
}

PandaNames ArmNames(const exporting::Body& robot) { return PandaNames{robot.name + "_"}; }

}  // namespace

std::vector<ArmIndex> World::arm_indices() const {
  std::vector<ArmIndex> indices;
  for (const WorldArm& arm : arms) indices.push_back(arm.index);
  return indices;
}

int World::body(const std::string& name) const { return FindId(*model, mjOBJ_BODY, name); }

const exporting::Body* World::FindFirst(const std::string& class_name) const {
  for (const exporting::Body& b : scene.bodies) {
    if (b.class_name == class_name) return &b;
  }
  return nullptr;
}

Eigen::Isometry3d CalcArmMount(const exporting::Body& robot) {
  return kinematics::CalcArmMount(robot.p_WO, robot.R_WO.toRotationMatrix(), robot.size);
}

std::optional<std::string> MakePickTargetFree(exporting::Body& body) {
  if (body.is_free() || body.shape == exporting::Shape::kNone) return std::nullopt;
  exporting::SetMass(body, kDefaultPickTargetDensity_kg_m3 * exporting::CalcVolume(body));
  return fmt::format(
      "{} (a {}) has no mass, so a simulator would fix it in place (docs/export.md) and no arm "
      "could lift it; the case study simulates it as a free body of density {:g} kg/m^3 "
      "(MuJoCo's default; each record's extra.cube_mass_kg says how heavy). Give its class a "
      "mass in kilograms (`mass: 0.1`) to choose one",
      body.name, body.class_name, kDefaultPickTargetDensity_kg_m3);
}

std::string WriteWorldMjcf(const exporting::ExportScene& scene) {
  std::string bodies, equalities, actuators;
  for (const exporting::Body& b : scene.bodies) {
    if (b.class_name == "Tray") bodies += WriteTrayWalls(b);
    if (b.class_name != "Robot") continue;
    const PandaNames names = ArmNames(b);
    const Eigen::Isometry3d X = CalcArmMount(b);
    bodies += WritePandaBody(names, X.translation(), Eigen::Quaterniond(X.linear()));
    equalities += WritePandaEqualities(names);
    actuators += WritePandaActuators(names);
  }
  std::string xml = exporting::WriteScene(WithoutRobotGeometry(scene), exporting::Format::kMjcf);
  InsertBefore(xml, "</worldbody>", bodies);
  InsertBefore(xml, "</mujoco>",
               fmt::format("<visual><global offwidth=\"{}\" offheight=\"{}\"/>"
                           "<quality shadowsize=\"{}\"/></visual>",
                           kCameraBufferWidthPx, kCameraBufferHeightPx, kShadowMapSizePx));
  // One extent for every scene (MuJoCo would compute 2.97-3.13 m for Table-Cube's, from where
  // the objects lie): the cameras' clipping planes, the shadows and the ground's grid are then
  // the same in every episode, and one render context serves them all (render/context_key.h).
  InsertBefore(xml, "</mujoco>", fmt::format("<statistic extent=\"{}\"/>", kWorldExtentM));
  if (!equalities.empty())
    InsertBefore(xml, "</mujoco>", "<equality>" + equalities + "</equality>");
  if (!actuators.empty()) InsertBefore(xml, "</mujoco>", "<actuator>" + actuators + "</actuator>");
  return xml;
}

World BuildWorld(exporting::ExportScene scene) {
  // A controller is tested in one contact model, MuJoCo's default, whether or not its scenes
  // were settled: a settled scene's export carries the elliptic cones it was settled with, and
  // under them 7 of 100 Table-Cube hand-overs that succeed in the scene as drawn let the cube
  // slip (seed 1), though settling moved it by 0.2 mm. A failure must come from the scene,
  // not from a physics model that changed with it.
  scene.settled = false;
  World world;
  world.xml = WriteWorldMjcf(scene);
  world.model = LoadModelFromXml(world.xml);
  world.data = MakeData(*world.model);
  for (const exporting::Body& b : scene.bodies) {
    if (b.class_name != "Robot") continue;
    WorldArm arm{b.name, ArmNames(b), CalcArmMount(b), {}};
    arm.index = FindArm(*world.model, arm.names);
    SetArmJoints(*world.model, *world.data, arm.index, kPandaReadyPose_rad);
    SetGripper(*world.data, arm.index, kPandaFingerTravel_m, /*now=*/true);
    world.arms.push_back(std::move(arm));
  }
  world.scene = std::move(scene);
  mj_forward(world.model.get(), world.data.get());
  return world;
}

}  // namespace prs::sim
