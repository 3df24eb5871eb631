// Serial kinematic chains as plain data: revolute and prismatic joints from a base frame to a
// tool frame (fixed joints folded into the transforms), with forward kinematics, the geometric
// Jacobian and joint-limit helpers. The error type of the whole kinematics stage lives here.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <stdexcept>
#include <string>
#include <vector>

namespace prs::kinematics {

/// Every error of the kinematics stage (bad arguments, unreadable robot files, bad options):
/// the message says what is wrong in words a user can act on.
class KinematicsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class JointType { kRevolute, kPrismatic };

/// One movable joint. Its frame J sits at X_PJ in the previous joint's frame P (the base frame
/// for the first joint) when every joint is at 0; at value q the frame moves by a rotation of
/// q radians about axis_J (revolute) or a translation of q metres along it (prismatic).
struct Joint {
  std::string name;
  JointType type = JointType::kRevolute;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis_J = Eigen::Vector3d::UnitZ();  // unit
  double lower = 0;                                   // rad or m
  double upper = 0;                                   // rad or m, >= lower
};

/// A serial chain from a base frame to a tool frame: X_BaseTool(q) = X_PJ₁·M₁(q₁)·…·X_PJₙ·
/// Mₙ(qₙ)·X_LastTool, with Mᵢ the joint's motion.
struct Chain {
  std::string name;  // for messages: "panda", a URDF file's label
  std::vector<Joint> joints;
  Eigen::Isometry3d X_LastTool = Eigen::Isometry3d::Identity();  // tool in the last joint's frame

  int num_joints() const { return static_cast<int>(joints.size()); }
};

/// Geometric Jacobian of the tool frame's origin: rows 0–2 its linear velocity, rows 3–5 its
/// angular velocity, both expressed in the base frame; one column per joint.
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// Throws KinematicsError naming the chain and joint when the chain has no joints, a joint's
/// axis is not a unit vector (within 1e-9), a limit or transform is not finite, or a joint's
/// lower limit exceeds its upper one.
void ValidateChain(const Chain& chain);

/// X_BaseTool at joint values q. Throws KinematicsError when q.size() != num_joints().
Eigen::Isometry3d CalcToolPose(const Chain& chain, const Eigen::VectorXd& q);

/// The tool pose and the geometric Jacobian at q (one pass). Throws as CalcToolPose.
Eigen::Isometry3d CalcToolPoseAndJacobian(const Chain& chain, const Eigen::VectorXd& q,
                                          Jacobian* J);

/// The geometric Jacobian at q (see Jacobian). Throws as CalcToolPose.
Jacobian CalcToolJacobian(const Chain& chain, const Eigen::VectorXd& q);

/// The joints' lower and upper limits as vectors.
Eigen::VectorXd GetLowerLimits(const Chain& chain);
Eigen::VectorXd GetUpperLimits(const Chain& chain);

/// The middle of each joint's range.
Eigen::VectorXd CalcMidRange(const Chain& chain);

/// True when every q_i lies in [lower_i − tolerance, upper_i + tolerance]. False when the
/// size is wrong.
bool IsWithinLimits(const Chain& chain, const Eigen::VectorXd& q, double tolerance = 0);

/// q with each value clamped into its joint's range. Throws KinematicsError on a size mismatch.
Eigen::VectorXd ClampToLimits(const Chain& chain, const Eigen::VectorXd& q);

}  // namespace prs::kinematics
