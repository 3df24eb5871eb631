// Scenes simulated under gravity until they come to rest (see stability.h).
#include "sim/stability.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lang/diagnostics.h"
#include "sim/mujoco_model.h"

namespace prs::sim {

namespace {

constexpr double kRestSpeed_m_s = 0.005;   // a free body slower than this ...
constexpr double kRestSpin_rad_s = 0.05;   // ... and turning slower than this ...
constexpr double kRestWindow_s = 0.1;      // ... for this long is at rest
constexpr double kFirstRestCheck_s = 0.1;  // (not before: every body starts at rest)
static_assert(kFirstRestCheck_s + kRestWindow_s == kMinStableDuration_s);
// Settling: a pile's bodies never all stand still (MuJoCo 2.2 touches round and mesh shapes at
// one point, and they rock in place), so rest is judged by where they are, as BlenderProc
// judges it: every free body within this distance and angle of where it was a window before
// (BlenderProc checks 1 cm and 0.1 rad, every 2 s). The window slides: poses are kept every
// kSettleCheck_s, and each new one is compared with the one a window before, so the first
// comparison is made a window in: the least time settling can take.
constexpr double kSettleWindow_s = kMinSettleDuration_s;
constexpr double kSettleCheck_s = 0.1;
constexpr double kSettleMove_m = 0.01;
constexpr double kSettleTurn_rad = 0.1;
// A pile found at rest so is then confirmed from standstill (kSettleConfirm_s, stability.h).

// The steps of `step_s` that `duration_s` takes, at least: ceil, but a quotient within a
// millionth of a step of a whole number is that number (0.2 s of 2 ms steps is 100 steps, though
// 0.2 / 0.002 may come out a hair above 100).
int CountSteps(double duration_s, double step_s) {
  return static_cast<int>(std::ceil(duration_s / step_s - 1e-6));
}

// "2.04 m" or "3.1 cm".
std::string FormatDistance(double distance_m) {
  return distance_m >= 0.1 ? fmt::format("{:.2f} m", distance_m)
                           : fmt::format("{:.1f} cm", 100 * distance_m);
}

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
  m.spin_rad_s = Eigen::Vector3d(v[3], v[4], v[5]).norm();
  return m;
}

// MeasureMotion with where the object's frame ended (the body's frame moved with it).
BodyMotion MeasureEnd(const FreeJoint& j, const exporting::Body& body, const mjData& data) {
  BodyMotion m = MeasureMotion(j, data);
  const mjtNum* q = data.qpos + j.qpos;
  const Eigen::Quaterniond R_WB(Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized());
  const Eigen::Quaterniond R_BO = j.q0.conjugate() * body.R_WO;  // the object in the body
  const Eigen::Vector3d p_BO = j.q0.conjugate() * (body.p_WO - j.p0);
  m.p_end_WO = Eigen::Vector3d(q[0], q[1], q[2]) + R_WB * p_BO;
  m.R_end_WO = (R_WB * R_BO).normalized();
  return m;
}

bool IsMoving(const BodyMotion& m) {
  return m.speed_m_s > kRestSpeed_m_s || m.spin_rad_s > kRestSpin_rad_s;
}

// Settling: whether every free body is within kSettleMove_m and kSettleTurn_rad of its pose
// in `window_qpos`; sets how far each moved and turned.
bool IsStillSince(const std::vector<FreeJoint>& joints, const std::vector<mjtNum>& window_qpos,
                  const mjData& data, std::vector<double>& moved_m,
                  std::vector<double>& turned_rad) {
  bool still = true;
  for (size_t k = 0; k < joints.size(); ++k) {
    const mjtNum* q0 = window_qpos.data() + joints[k].qpos;
    const mjtNum* q = data.qpos + joints[k].qpos;
    moved_m[k] = Eigen::Vector3d(q[0] - q0[0], q[1] - q0[1], q[2] - q0[2]).norm();
    turned_rad[k] = Eigen::Quaterniond(q0[3], q0[4], q0[5], q0[6])
                        .normalized()
                        .angularDistance(Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized());
    still &= moved_m[k] < kSettleMove_m && turned_rad[k] < kSettleTurn_rad;
  }
  return still;
}

bool IsPastTolerance(const BodyMotion& m, const StabilityOptions& options) {
  return m.p_moved_W.norm() > options.max_move_m || m.turned_rad > options.max_turn_rad;
}

// "fell 2.04 m", "slid 3.1 cm", "turned 7.2°", "was still moving at 0.200 m/s after 1.00 s".
// A body that stopped too late to have been at rest for kRestWindow_s says when it stopped,
// never "moving at 0.000 m/s".
std::string DescribeMotion(const BodyMotion& m, const StabilityOptions& options, bool at_rest,
                           double simulated_s) {
  const double drop = -m.p_moved_W.z(), across = m.p_moved_W.head<2>().norm();
  const double moved = m.p_moved_W.norm();
  if (moved > options.max_move_m) {
    const char* how = drop >= across ? "fell" : (m.p_moved_W.z() > across ? "rose" : "slid");
    return fmt::format("{} {} in {:.2f} s", how, FormatDistance(moved), simulated_s);
  }
  if (m.turned_rad > options.max_turn_rad) {
    return fmt::format("turned {:.1f}° in {:.2f} s", m.turned_rad * 180 / M_PI, simulated_s);
  }
  if (at_rest) return "stayed put";
  if (m.speed_m_s > kRestSpeed_m_s) {
    return fmt::format("was still moving at {:.3f} m/s after {:.2f} s", m.speed_m_s, simulated_s);
  }
  if (m.spin_rad_s > kRestSpin_rad_s) {
    return fmt::format("was still turning at {:.2f} rad/s after {:.2f} s", m.spin_rad_s,
                       simulated_s);
  }
  return fmt::format(
      "was still moving at {:.2f} s, less than {} s before the end at {:.2f} s (at rest: slower "
      "than {} m/s and {} rad/s for {} s)",
      m.moving_until_s, kRestWindow_s, simulated_s, kRestSpeed_m_s, kRestSpin_rad_s, kRestWindow_s);
}

// A scene's physics model being stepped, with its free bodies.
struct Simulation {
  ModelPtr model;
  DataPtr data;
  std::vector<FreeJoint> joints;
  int steps = 0;  // the most steps options.duration_s allows
  // Per joint: the last time it was moving (--stable); how far it moved and turned over the
  // last window compared (settling), or in the last confirmation when recent_confirmed.
  std::vector<double> moving_until_s, recent_move_m, recent_turn_rad;
  bool recent_confirmed = false;
};

Simulation StartSimulation(const exporting::ExportScene& scene, const StabilityOptions& options) {
  Simulation s;
  try {
    s.model = LoadModelFromXml(exporting::WriteScene(scene, exporting::Format::kMjcf));
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(std::string("the physics model of the scene cannot be simulated: ") +
                             error.what());
  }
  if (options.timestep_s > 0) s.model->opt.timestep = options.timestep_s;
  s.data = MakeData(*s.model);
  s.joints = FindFreeJoints(scene, *s.model);
  s.steps = CountSteps(options.duration_s, s.model->opt.timestep);
  s.moving_until_s.assign(s.joints.size(), 0);
  s.recent_move_m.assign(s.joints.size(), 0);
  s.recent_turn_rad.assign(s.joints.size(), 0);
  return s;
}

// --stable: steps until every free body has been at rest (by velocity) for kRestWindow_s, or
// one moved past the tolerance (its index the culprit). Counted in steps, not in the sum of
// their times, so that rest is decided within kMinStableDuration_s at any step. When time runs
// out, the culprit is the body that moved last (of those, the fastest at the end).
void StepUntilStillOrPastTolerance(Simulation& s, const StabilityOptions& options,
                                   StabilityReport& report) {
  const mjModel& model = *s.model;
  mjData& data = *s.data;
  const int first_check = CountSteps(kFirstRestCheck_s, model.opt.timestep);
  const int window = CountSteps(kRestWindow_s, model.opt.timestep);
  int resting_since = 0;
  for (int step = 1; step <= s.steps; ++step) {
    mj_step(&model, &data);
    bool moving = false;
    for (size_t k = 0; k < s.joints.size(); ++k) {
      const BodyMotion m = MeasureMotion(s.joints[k], data);
      if (IsPastTolerance(m, options)) {
        report.culprit = static_cast<int>(k);
        return;
      }
      if (IsMoving(m)) {
        moving = true;
        s.moving_until_s[k] = data.time;
      }
    }
    if (moving || step < first_check) resting_since = step;
    if (step - resting_since >= window) {
      report.at_rest = true;
      return;
    }
  }
  report.culprit = 0;
  for (size_t k = 1; k < s.joints.size(); ++k) {
    const int c = report.culprit;
    const double later = s.moving_until_s[k] - s.moving_until_s[c];
    if (later > 0 || (later == 0 && MeasureMotion(s.joints[k], data).speed_m_s >
                                        MeasureMotion(s.joints[c], data).speed_m_s)) {
      report.culprit = static_cast<int>(k);
    }
  }
}

// Settling's confirmation (kSettleConfirm_s): starts the pile again from standstill at
// `qpos` (velocities and the solver's warm start zero, as in a fresh mjData: what a settled
// export starts from), steps it and says whether every body ended within the limits of where
// it started; if so, puts the pile back at `qpos` at standstill. Either way the time stepped
// counts, and recent_move_m/recent_turn_rad say how far each body went.
bool ConfirmRest(Simulation& s, const std::vector<mjtNum>& qpos) {
  const mjModel& model = *s.model;
  mjData& data = *s.data;
  const auto from_standstill = [&] {
    std::copy(qpos.begin(), qpos.end(), data.qpos);
    std::fill(data.qvel, data.qvel + model.nv, 0);
    std::fill(data.qacc_warmstart, data.qacc_warmstart + model.nv, 0);
  };
  from_standstill();
  const int steps = CountSteps(kSettleConfirm_s, model.opt.timestep);
  for (int step = 0; step < steps; ++step) mj_step(&model, &data);
  s.recent_confirmed = true;
  const bool still = IsStillSince(s.joints, qpos, data, s.recent_move_m, s.recent_turn_rad);
  if (still) {
    const double time_s = data.time;
    from_standstill();
    mj_forward(&model, &data);
    data.time = time_s;
  }
  return still;
}

// --settle: steps until every free body is where it was a window before (by position, checked
// every kSettleCheck_s) and stays there when started again from standstill (ConfirmRest); a
// pile that does not starts a new window from where the confirmation left it. When time runs
// out, the culprit is the one furthest from rest in the last window or confirmation compared:
// the most moved or turned, each as a share of its limit. The confirmation of a pile found at
// rest within the time is made even when it takes the simulation past it.
void StepUntilSettled(Simulation& s, StabilityReport& report) {
  const mjModel& model = *s.model;
  mjData& data = *s.data;
  const int check_steps =
      std::max(1, static_cast<int>(std::lround(kSettleCheck_s / model.opt.timestep)));
  const int window_checks = static_cast<int>(std::lround(kSettleWindow_s / kSettleCheck_s));
  const int confirm_equivalent_steps = CountSteps(kSettleConfirm_s, model.opt.timestep);
  // The poses of the last window_checks checks, the oldest next to be compared and overwritten.
  std::vector<std::vector<mjtNum>> ring(window_checks,
                                        std::vector<mjtNum>(data.qpos, data.qpos + model.nq));
  int checks = 0;  // since the window started filling
  for (int step = 1; step <= s.steps; ++step) {
    mj_step(&model, &data);
    if (step % check_steps != 0) continue;
    ++checks;
    std::vector<mjtNum>& window_start = ring[checks % window_checks];
    if (checks >= window_checks) {
      if (IsStillSince(s.joints, window_start, data, s.recent_move_m, s.recent_turn_rad)) {
        const std::vector<mjtNum> at_rest(data.qpos, data.qpos + model.nq);
        if (ConfirmRest(s, at_rest)) {
          report.at_rest = true;
          return;
        }
        // Moving again: the time confirming took counts, and a new window starts here.
        step += confirm_equivalent_steps - confirm_equivalent_steps % check_steps;
        checks = 0;
        for (std::vector<mjtNum>& pose : ring) pose.assign(data.qpos, data.qpos + model.nq);
        continue;
      }
      s.recent_confirmed = false;
    }
    window_start.assign(data.qpos, data.qpos + model.nq);
  }
  const auto from_rest = [&](size_t k) {
    return std::max(s.recent_move_m[k] / kSettleMove_m, s.recent_turn_rad[k] / kSettleTurn_rad);
  };
  report.culprit = 0;
  for (size_t k = 1; k < s.joints.size(); ++k) {
    if (from_rest(k) > from_rest(report.culprit)) report.culprit = static_cast<int>(k);
  }
}

// The simulation of `scene` to rest (StabilityReport's at_rest and culprit), or until time ran
// out.
Simulation Simulate(const exporting::ExportScene& scene, const StabilityOptions& options,
                    bool stop_past_tolerance, StabilityReport& report) {
  Simulation simulation = StartSimulation(scene, options);
  if (stop_past_tolerance) {
    StepUntilStillOrPastTolerance(simulation, options, report);
  } else {
    StepUntilSettled(simulation, report);
  }
  return simulation;
}

// Whether a step dropped contacts or constraint rows for want of room.
bool RanOutOfRoom(const mjData& data) {
  return data.warning[mjWARN_CONTACTFULL].number > 0 || data.warning[mjWARN_CNSTRFULL].number > 0;
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
  if (options.duration_s < kMinStableDuration_s) {
    throw std::invalid_argument(fmt::format(
        "the simulated time of --stable must be at least {} s, not {}: a body is at rest once "
        "it has been still for {} s, judged from {} s on (docs/physics.md)",
        kMinStableDuration_s, options.duration_s, kRestWindow_s, kFirstRestCheck_s));
  }
}

std::string DescribeUnsettledMotion(const BodyMotion& m) {
  const std::string when =
      m.recent_from_standstill
          ? fmt::format("in {} s when started again from standstill", kSettleConfirm_s)
          : fmt::format("in the last {} s", kSettleWindow_s);
  return fmt::format("moved {} and turned {:.1f}° {} (at rest: under {} and {:.1f}°)",
                     FormatDistance(m.recent_move_m), m.recent_turn_rad * 180 / M_PI, when,
                     FormatDistance(kSettleMove_m), kSettleTurn_rad * 180 / M_PI);
}

void CheckFreeBodiesCollide(const lang::Scene& scene, const exporting::ExportScene& model,
                            const char* check) {
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const exporting::Body& body = model.bodies[i];
    if (!body.is_free() || body.collides) continue;
    const lang::SceneObject& object = scene.objects[i];
    const std::string name = object.DisplayName(static_cast<int>(i));
    lang::Diagnostic d;
    d.id = "physics-without-contacts";
    d.span = object.span;
    d.message = fmt::format(
        "{} has a mass and allowCollisions: True, so it has no contacts in the physics model: it "
        "falls through whatever holds it up, and {} can accept no scene with it",
        name, check);
    d.notes.push_back({{},
                       false,
                       "allowCollisions lets the sampler overlap an object with others; exports "
                       "and the physics checks then give it visual geometry only "
                       "(docs/export.md)"});
    d.notes.push_back({{},
                       false,
                       fmt::format("give {} allowCollisions: False to simulate it, or no mass to "
                                   "keep it fixed where it is drawn",
                                   name)});
    throw lang::ScenarioError(std::move(d));
  }
}

StabilityReport SimulateUnderGravity(const exporting::ExportScene& scene,
                                     const StabilityOptions& options, bool stop_past_tolerance) {
  CheckStabilityOptions(options);
  if (!stop_past_tolerance && options.duration_s < kMinSettleDuration_s) {
    throw std::invalid_argument(
        fmt::format("settling needs at least {} s of simulated time, not {}", kMinSettleDuration_s,
                    options.duration_s));
  }
  StabilityReport report;
  bool any_free = false;
  for (const exporting::Body& body : scene.bodies) any_free |= body.is_free();
  if (!any_free) {
    report.at_rest = true;
    return report;
  }
  // First with room for options.first_contacts_per_free_body contacts a body; a simulation in
  // which a step ran out of it runs again with the scene's own room, so the result is the same
  // as with that room from the start (MuJoCo computes the same with more room to spare).
  Simulation simulation;
  const int first_room = options.first_contacts_per_free_body;
  if (first_room > 0 && first_room < scene.contacts_per_free_body) {
    exporting::ExportScene tight = scene;
    tight.contacts_per_free_body = first_room;
    render::MujocoWarningsMuted muted;
    simulation = Simulate(tight, options, stop_past_tolerance, report);
  }
  if (!simulation.data || RanOutOfRoom(*simulation.data)) {
    report = StabilityReport();
    simulation = Simulate(scene, options, stop_past_tolerance, report);
  }
  report.simulated_s = simulation.data->time;
  for (size_t k = 0; k < simulation.joints.size(); ++k) {
    const FreeJoint& j = simulation.joints[k];
    BodyMotion m = MeasureEnd(j, scene.bodies[j.object], *simulation.data);
    m.moving_until_s = simulation.moving_until_s[k];
    m.recent_move_m = simulation.recent_move_m[k];
    m.recent_turn_rad = simulation.recent_turn_rad[k];
    m.recent_from_standstill = simulation.recent_confirmed;
    report.free_bodies.push_back(m);
  }
  return report;
}

std::optional<lang::Rejection> CheckStable(const lang::Scene& scene,
                                           const StabilityOptions& options) {
  const exporting::ExportScene model = exporting::MakeExportScene(scene, "stability");
  CheckFreeBodiesCollide(scene, model, "--stable");
  const StabilityReport report = SimulateUnderGravity(model, options);
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
