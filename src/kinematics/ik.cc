// Damped-least-squares inverse kinematics on a Chain (see ik.h): the algorithm the simulator
// used on MuJoCo's Jacobian, on the chain's own, with partial-orientation targets added.
#include "kinematics/ik.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/random.h"

namespace prs::kinematics {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

void RequireFinite(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite()) throw KinematicsError(std::string("IK target: ") + what + " is not finite");
}

void ValidateOptions(const Chain& chain, const IkOptions& o) {
  auto fail = [](const std::string& what) { throw KinematicsError("IK options: " + what); };
  if (o.max_iterations < 0) fail("max_iterations is " + std::to_string(o.max_iterations));
  if (!(o.damping >= 0)) fail("damping is " + std::to_string(o.damping));
  if (!(o.position_tolerance_m >= 0) || !(o.rotation_tolerance_rad >= 0)) {
    fail("a tolerance is negative");
  }
  if (!(o.rotation_weight_m > 0)) fail("rotation_weight_m must be positive");
  if (!(o.max_step > 0)) fail("max_step must be positive");
  for (int i : o.held_joints) {
    if (i < 0 || i >= chain.num_joints()) {
      fail("held joint " + std::to_string(i) + " is not a joint of '" + chain.name + "' (0.." +
           std::to_string(chain.num_joints() - 1) + ")");
    }
  }
}

// Two unit vectors completing z to an orthonormal basis.
void CalcPerpendiculars(const Eigen::Vector3d& z, Eigen::Vector3d* b1, Eigen::Vector3d* b2) {
  const Eigen::Vector3d helper =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  *b1 = z.cross(helper).normalized();
  *b2 = z.cross(*b1);
}

// The rotation vector (angle·axis) taking direction `from` onto direction `to` (both unit).
Eigen::Vector3d CalcAxisError(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d cross = from.cross(to);
  const double sin_angle = cross.norm(), angle = std::atan2(sin_angle, from.dot(to));
  if (sin_angle > 1e-12) return angle * cross / sin_angle;
  if (angle < 1.0) return Eigen::Vector3d::Zero();
  Eigen::Vector3d b1, b2;  // opposite directions: any perpendicular axis turns one onto the other
  CalcPerpendiculars(from, &b1, &b2);
  return angle * b1;
}

// The weighted 6-D error from the tool pose to the target and the Jacobian's rows to match:
// rows of orientation that the target leaves free are zeroed in both.
struct Residual {
  Vector6d e;
  double position_error_m = 0, rotation_error_rad = 0;
};

Residual CalcResidual(const IkTarget& target, const Eigen::Isometry3d& X_BaseTool, double weight,
                      Jacobian* J) {
  Residual r;
  r.e.head<3>() = target.p_BaseTool - X_BaseTool.translation();
  r.position_error_m = r.e.head<3>().norm();
  switch (target.kind) {
    case IkTargetKind::kPose: {
      const Eigen::AngleAxisd R_error(target.R_BaseTool * X_BaseTool.linear().transpose());
      r.e.tail<3>() = weight * R_error.angle() * R_error.axis();
      r.rotation_error_rad = R_error.angle();
      J->bottomRows<3>() *= weight;
      break;
    }
    case IkTargetKind::kPositionAndAxis: {
      // Only the two rotation directions that tilt the tool's z axis matter.
      const Eigen::Vector3d z_tool = X_BaseTool.linear().col(2);
      const Eigen::Vector3d rot = CalcAxisError(z_tool, target.z_Base);
      r.rotation_error_rad = rot.norm();
      Eigen::Vector3d b1, b2;
      CalcPerpendiculars(z_tool, &b1, &b2);
      for (int i = 0; i < J->cols(); ++i) {
        const Eigen::Vector3d w = J->col(i).tail<3>();
        (*J)(3, i) = weight * b1.dot(w);
        (*J)(4, i) = weight * b2.dot(w);
        (*J)(5, i) = 0;
      }
      r.e.tail<3>() << weight * b1.dot(rot), weight * b2.dot(rot), 0;
      break;
    }
    case IkTargetKind::kPosition:
      J->bottomRows<3>().setZero();
      r.e.tail<3>().setZero();
      break;
  }
  return r;
}

// Zeroes the columns of joints at a limit that dq pushes further out. True when any was.
bool ReleaseLimitedJoints(const Chain& chain, const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                          Jacobian* J) {
  bool any = false;
  for (int i = 0; i < chain.num_joints(); ++i) {
    const Joint& joint = chain.joints[i];
    if ((q[i] <= joint.lower && dq[i] < 0) || (q[i] >= joint.upper && dq[i] > 0)) {
      J->col(i).setZero();
      any = true;
    }
  }
  return any;
}

}  // namespace

IkTarget MakePoseTarget(const Eigen::Isometry3d& X_BaseTarget) {
  if (!X_BaseTarget.matrix().allFinite())
    throw KinematicsError("IK target: the pose is not finite");
  IkTarget t;
  t.kind = IkTargetKind::kPose;
  t.p_BaseTool = X_BaseTarget.translation();
  t.R_BaseTool = X_BaseTarget.linear();
  return t;
}

IkTarget MakeAxisTarget(const Eigen::Vector3d& p_BaseTarget, const Eigen::Vector3d& z_Base) {
  RequireFinite(p_BaseTarget, "the position");
  RequireFinite(z_Base, "the axis");
  if (z_Base.norm() < 1e-12) throw KinematicsError("IK target: the tool axis is zero");
  IkTarget t;
  t.kind = IkTargetKind::kPositionAndAxis;
  t.p_BaseTool = p_BaseTarget;
  t.z_Base = z_Base.normalized();
  return t;
}

IkTarget MakePositionTarget(const Eigen::Vector3d& p_BaseTarget) {
  RequireFinite(p_BaseTarget, "the position");
  IkTarget t;
  t.kind = IkTargetKind::kPosition;
  t.p_BaseTool = p_BaseTarget;
  return t;
}

IkResult SolveIk(const Chain& chain, const IkTarget& target, const Eigen::VectorXd& q_start,
                 const IkOptions& options) {
  ValidateChain(chain);
  ValidateOptions(chain, options);
  const int n = chain.num_joints();
  IkResult result;
  result.q = ClampToLimits(chain, q_start);
  std::vector<bool> held(n, false);
  for (int i : options.held_joints) held[i] = true;
  for (int i = 0; i < n; ++i) {
    if (held[i]) result.q[i] = q_start[i];  // held where asked, even outside the limits
  }
  const double damping2 = options.damping * options.damping;
  Jacobian J(6, n);
  Eigen::VectorXd dq(n);
  double best_error = std::numeric_limits<double>::infinity();
  int best_iteration = 0;
  for (result.iterations = 0; result.iterations <= options.max_iterations; ++result.iterations) {
    const Eigen::Isometry3d X_BaseTool = CalcToolPoseAndJacobian(chain, result.q, &J);
    const Residual r = CalcResidual(target, X_BaseTool, options.rotation_weight_m, &J);
    result.position_error_m = r.position_error_m;
    result.rotation_error_rad = r.rotation_error_rad;
    if (r.position_error_m <= options.position_tolerance_m &&
        r.rotation_error_rad <= options.rotation_tolerance_rad) {
      result.converged = true;
      return result;
    }
    if (result.iterations == options.max_iterations) break;
    if (options.stall_iterations > 0) {
      const double error = r.e.norm();
      if (error < 0.99 * best_error) best_error = error, best_iteration = result.iterations;
      if (result.iterations - best_iteration >= options.stall_iterations) break;
    }
    for (int i = 0; i < n; ++i) {
      if (held[i]) J.col(i).setZero();
    }
    Matrix6d JJt = J * J.transpose() + damping2 * Matrix6d::Identity();
    dq.noalias() = J.transpose() * JJt.ldlt().solve(r.e);
    if (options.release_limited_joints && ReleaseLimitedJoints(chain, result.q, dq, &J)) {
      JJt = J * J.transpose() + damping2 * Matrix6d::Identity();
      dq.noalias() = J.transpose() * JJt.ldlt().solve(r.e);
    }
    for (int i = 0; i < n; ++i) {
      if (held[i]) continue;
      const double step = std::clamp(dq[i], -options.max_step, options.max_step);
      result.q[i] = std::clamp(result.q[i] + step, chain.joints[i].lower, chain.joints[i].upper);
    }
  }
  return result;
}

IkResult SolveIkWithRestarts(const Chain& chain, const IkTarget& target,
                             const Eigen::VectorXd& q_start, const IkOptions& options, int restarts,
                             uint64_t seed) {
  if (restarts < 0) throw KinematicsError("IK: restarts is " + std::to_string(restarts));
  IkResult best = SolveIk(chain, target, q_start, options);
  int iterations = best.iterations;
  auto weighted = [&](const IkResult& r) {
    return std::hypot(r.position_error_m, options.rotation_weight_m * r.rotation_error_rad);
  };
  std::vector<bool> held(chain.num_joints(), false);
  for (int i : options.held_joints) held[i] = true;
  geometry::Rng rng(seed, 0x1c);
  Eigen::VectorXd q = q_start;
  for (int k = 0; k < restarts && !best.converged; ++k) {
    for (int i = 0; i < chain.num_joints(); ++i) {
      q[i] = held[i] ? q_start[i] : rng.Uniform(chain.joints[i].lower, chain.joints[i].upper);
    }
    IkResult attempt = SolveIk(chain, target, q, options);
    iterations += attempt.iterations;
    if (attempt.converged || weighted(attempt) < weighted(best)) best = std::move(attempt);
  }
  best.iterations = iterations;
  return best;
}

}  // namespace prs::kinematics
