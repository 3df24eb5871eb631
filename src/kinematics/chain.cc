// Forward kinematics, Jacobians and limits of serial chains (see chain.h).
#include "kinematics/chain.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace prs::kinematics {

namespace {

void RequireSize(const Chain& chain, const Eigen::VectorXd& q) {
  if (q.size() != chain.num_joints()) {
    throw KinematicsError("chain '" + chain.name + "' has " + std::to_string(chain.num_joints()) +
                          " joints but " + std::to_string(q.size()) + " joint values were given");
  }
}

// The joint's motion at value q, as a transform of its own frame.
Eigen::Isometry3d CalcMotion(const Joint& joint, double q) {
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  if (joint.type == JointType::kRevolute) {
    M.linear() = Eigen::AngleAxisd(q, joint.axis_J).toRotationMatrix();
  } else {
    M.translation() = q * joint.axis_J;
  }
  return M;
}

bool IsFinite(const Eigen::Isometry3d& X) { return X.matrix().allFinite(); }

}  // namespace

void ValidateChain(const Chain& chain) {
  // Messages are built only on failure: the IK validates its chain on every call.
  auto where = [&] { return "chain '" + chain.name + "'"; };
  if (chain.joints.empty()) throw KinematicsError(where() + " has no movable joint");
  for (const Joint& j : chain.joints) {
    auto joint = [&] { return where() + ", joint '" + j.name + "'"; };
    if (!IsFinite(j.X_PJ) || !j.axis_J.allFinite()) {
      throw KinematicsError(joint() + ": a transform or axis is not finite");
    }
    if (std::abs(j.axis_J.norm() - 1) > 1e-9) {
      throw KinematicsError(joint() + ": the axis is not a unit vector (length " +
                            std::to_string(j.axis_J.norm()) + ")");
    }
    if (!std::isfinite(j.lower) || !std::isfinite(j.upper)) {
      throw KinematicsError(joint() + ": a limit is not finite");
    }
    if (j.lower > j.upper) {
      throw KinematicsError(joint() + ": the lower limit " + std::to_string(j.lower) +
                            " is above the upper limit " + std::to_string(j.upper));
    }
  }
  if (!IsFinite(chain.X_LastTool)) {
    throw KinematicsError(where() + ": the tool transform is not finite");
  }
}

Eigen::Isometry3d CalcToolPose(const Chain& chain, const Eigen::VectorXd& q) {
  RequireSize(chain, q);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int i = 0; i < chain.num_joints(); ++i) {
    X = X * chain.joints[i].X_PJ * CalcMotion(chain.joints[i], q[i]);
  }
  return X * chain.X_LastTool;
}

Eigen::Isometry3d CalcToolPoseAndJacobian(const Chain& chain, const Eigen::VectorXd& q,
                                          Jacobian* J) {
  RequireSize(chain, q);
  const int n = chain.num_joints();
  J->resize(6, n);
  // First pass: each joint's origin (rows 0–2) and axis (rows 3–5) in the base frame, kept in
  // J's own columns (no allocation on the IK's hot path); second pass: the columns.
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Joint& joint = chain.joints[i];
    p += R * joint.X_PJ.translation();
    R = R * joint.X_PJ.linear();
    const Eigen::Vector3d axis_Base = R * joint.axis_J;
    J->col(i).head<3>() = p;
    J->col(i).tail<3>() = axis_Base;
    if (joint.type == JointType::kRevolute) {
      R = R * Eigen::AngleAxisd(q[i], joint.axis_J).toRotationMatrix();
    } else {
      p += q[i] * axis_Base;
    }
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = p + R * chain.X_LastTool.translation();
  X.linear() = R * chain.X_LastTool.linear();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d axis_Base = J->col(i).tail<3>();
    if (chain.joints[i].type == JointType::kRevolute) {
      J->col(i).head<3>() = axis_Base.cross(X.translation() - J->col(i).head<3>());
    } else {
      J->col(i).head<3>() = axis_Base;
      J->col(i).tail<3>().setZero();
    }
  }
  return X;
}

Jacobian CalcToolJacobian(const Chain& chain, const Eigen::VectorXd& q) {
  Jacobian J;
  CalcToolPoseAndJacobian(chain, q, &J);
  return J;
}

Eigen::VectorXd GetLowerLimits(const Chain& chain) {
  Eigen::VectorXd v(chain.num_joints());
  for (int i = 0; i < chain.num_joints(); ++i) v[i] = chain.joints[i].lower;
  return v;
}

Eigen::VectorXd GetUpperLimits(const Chain& chain) {
  Eigen::VectorXd v(chain.num_joints());
  for (int i = 0; i < chain.num_joints(); ++i) v[i] = chain.joints[i].upper;
  return v;
}

Eigen::VectorXd CalcMidRange(const Chain& chain) {
  return 0.5 * (GetLowerLimits(chain) + GetUpperLimits(chain));
}

bool IsWithinLimits(const Chain& chain, const Eigen::VectorXd& q, double tolerance) {
  if (q.size() != chain.num_joints()) return false;
  for (int i = 0; i < chain.num_joints(); ++i) {
    if (!(q[i] >= chain.joints[i].lower - tolerance && q[i] <= chain.joints[i].upper + tolerance)) {
      return false;
    }
  }
  return true;
}

Eigen::VectorXd ClampToLimits(const Chain& chain, const Eigen::VectorXd& q) {
  RequireSize(chain, q);
  Eigen::VectorXd clamped = q;
  for (int i = 0; i < chain.num_joints(); ++i) {
    clamped[i] = std::clamp(q[i], chain.joints[i].lower, chain.joints[i].upper);
  }
  return clamped;
}

}  // namespace prs::kinematics
