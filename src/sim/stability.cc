// Scenes simulated under gravity until they come to rest (see stability.h).
#include "sim/stability.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "sim/mujoco_model.h"

namespace prs::sim {

namespace {

constexpr double kRestSpeed_m_s = 0.005;   // a free body slower than this ...
constexpr double kRestSpin_rad_s = 0.05;   // ... and turning slower than this ...
constexpr double kRestWindow_s = 0.1;      // ... for this long is at rest
constexpr double kFirstRestCheck_s = 0.1;  // (not before: every body starts at rest)

// One free body's free joint in the model.
struct FreeJoint {
  int object = -1;
  int qpos = -1, qvel = -1;
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q0 = Eigen::Quaterniond::Identity();
};

std::vector<FreeJoint> FindFreeJoints(const exporting::ExportScene& scene, const mjModel& model) {
  std::vector<FreeJoint> joints;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const exporting::Body& body = scene.bodies[i];
    if (!body.is_free()) continue;
    const int joint = FindId(model, mjOBJ_JOINT, body.name + "_free");
    FreeJoint j;
    j.object = static_cast<int>(i);
    j.qpos = model.jnt_qposadr[joint];
    j.qvel = model.jnt_dofadr[joint];
    const mjtNum* q = model.qpos0 + j.qpos;
    j.p0 = Eigen::Vector3d(q[0], q[1], q[2]);
    j.q0 = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized();
    joints.push_back(j);
  }
  return joints;
}

BodyMotion MeasureMotion(const FreeJoint& j, const mjData& data) {
  const mjtNum* q = data.qpos + j.qpos;
  const mjtNum* v = data.qvel + j.qvel;
  BodyMotion m;
  m.object = j.object;
  m.p_moved_W = Eigen::Vector3d(q[0], q[1], q[2]) - j.p0;
  m.turned_rad = j.q0.angularDistance(Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized());
  m.speed_m_s = Eigen::Vector3d(v[0], v[1], v[2]).norm();
  return m;
}

bool IsMoving(const FreeJoint& j, const mjData& data) {
  const mjtNum* v = data.qvel + j.qvel;
  return Eigen::Vector3d(v[0], v[1], v[2]).norm() > kRestSpeed_m_s ||
         Eigen::Vector3d(v[3], v[4], v[5]).norm() > kRestSpin_rad_s;
}

bool IsPastTolerance(const BodyMotion& m, const StabilityOptions& options) {
  return m.p_moved_W.norm() > options.max_move_m || m.turned_rad > options.max_turn_rad;
}

// "fell 2.04 m", "slid 3.1 cm", "turned 7.2°", "is still moving at 0.2 m/s after 1 s".
std::string DescribeMotion(const BodyMotion& m, const StabilityOptions& options, bool at_rest,
                           double simulated_s) {
  const double drop = -m.p_moved_W.z(), across = m.p_moved_W.head<2>().norm();
  const double moved = m.p_moved_W.norm();
  if (moved > options.max_move_m) {
    const std::string distance =
        moved >= 0.1 ? fmt::format("{:.2f} m", moved) : fmt::format("{:.1f} cm", 100 * moved);
    const char* how = drop >= across ? "fell" : (m.p_moved_W.z() > across ? "rose" : "slid");
    return fmt::format("{} {} in {:.2f} s", how, distance, simulated_s);
  }
  if (m.turned_rad > options.max_turn_rad) {
    return fmt::format("turned {:.1f}° in {:.2f} s", m.turned_rad * 180 / M_PI, simulated_s);
  }
  if (!at_rest) {
    return fmt::format("was still moving at {:.3f} m/s after {:.2f} s", m.speed_m_s, simulated_s);
  }
  return "stayed put";
}

}  // namespace

void CheckStabilityOptions(const StabilityOptions& options) {
  const auto check = [](double value, const char* what) {
    if (!(std::isfinite(value) && value > 0)) {
      throw std::invalid_argument(fmt::format("{} must be a positive number, not {}", what, value));
    }
  };
  check(options.duration_s, "the simulated time of --stable");
  check(options.max_move_m, "--stable-move");
  check(options.max_turn_rad, "--stable-turn");
}

StabilityReport SimulateUnderGravity(const exporting::ExportScene& scene,
                                     const StabilityOptions& options) {
  CheckStabilityOptions(options);
  StabilityReport report;
  bool any_free = false;
  for (const exporting::Body& body : scene.bodies) any_free |= body.is_free();
  if (!any_free) {
    report.at_rest = true;
    return report;
  }
  ModelPtr model;
  try {
    model = LoadModelFromXml(exporting::WriteScene(scene, exporting::Format::kMjcf));
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(std::string("the physics model of the scene cannot be simulated: ") +
                             error.what());
  }
  const DataPtr data = MakeData(*model);
  const std::vector<FreeJoint> joints = FindFreeJoints(scene, *model);
  const int steps = static_cast<int>(std::ceil(options.duration_s / model->opt.timestep));
  double resting_since_s = 0;
  for (int step = 0; step < steps; ++step) {
    mj_step(model.get(), data.get());
    const double t = data->time;
    bool moving = false;
    for (size_t k = 0; k < joints.size(); ++k) {
      if (IsPastTolerance(MeasureMotion(joints[k], *data), options)) {
        report.culprit = static_cast<int>(k);
        break;
      }
      moving |= IsMoving(joints[k], *data);
    }
    if (report.culprit >= 0) break;
    if (moving || t < kFirstRestCheck_s) resting_since_s = t;
    if (t - resting_since_s >= kRestWindow_s) {
      report.at_rest = true;
      break;
    }
  }
  report.simulated_s = data->time;
  for (const FreeJoint& j : joints) report.free_bodies.push_back(MeasureMotion(j, *data));
  if (report.culprit < 0 && !report.at_rest) {
    // Time ran out with something still moving: the fastest is to blame.
    report.culprit = 0;
    for (size_t k = 1; k < report.free_bodies.size(); ++k) {
      if (report.free_bodies[k].speed_m_s > report.free_bodies[report.culprit].speed_m_s) {
        report.culprit = static_cast<int>(k);
      }
    }
  }
  return report;
}

std::optional<lang::Rejection> CheckStable(const lang::Scene& scene,
                                           const StabilityOptions& options) {
  const StabilityReport report =
      SimulateUnderGravity(exporting::MakeExportScene(scene, "stability"), options);
  if (report.culprit < 0) return std::nullopt;
  const BodyMotion& m = report.free_bodies[report.culprit];
  const lang::SceneObject& object = scene.objects[m.object];
  lang::Rejection rejection;
  rejection.kind = lang::RejectionKind::kUnstable;
  rejection.culprit = object.DisplayName(m.object);
  rejection.span = object.span;
  rejection.detail = rejection.culprit + " " +
                     DescribeMotion(m, options, report.at_rest, report.simulated_s) +
                     " under gravity";
  return rejection;
}

std::function<std::optional<lang::Rejection>(const lang::Scene&)> MakeStabilityTest(
    const StabilityOptions& options) {
  CheckStabilityOptions(options);
  return [options](const lang::Scene& scene) { return CheckStable(scene, options); };
}

}  // namespace prs::sim
