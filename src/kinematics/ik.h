// Inverse kinematics on a Chain: damped least squares on the chain's own geometric Jacobian,
// within the joint limits (each step clamped into them), for a full pose, a position with the
// tool's z axis along a direction (free rotation about it), or a position alone.
// docs/kinematics.md says why this is ours rather than a library's.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "kinematics/chain.h"

namespace prs::kinematics {

enum class IkTargetKind {
  kPose,             // position and full orientation
  kPositionAndAxis,  // position, and the tool's z axis along a direction (any rotation about it)
  kPosition,         // position only
};

/// What the tool frame should reach, in the base frame. Make one with the Make…Target helpers.
struct IkTarget {
  IkTargetKind kind = IkTargetKind::kPose;
  Eigen::Vector3d p_BaseTool = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_BaseTool = Eigen::Matrix3d::Identity();  // kPose only
  Eigen::Vector3d z_Base = Eigen::Vector3d::UnitZ();         // kPositionAndAxis only; unit
};

/// A full-pose target. Throws KinematicsError when the pose is not finite.
IkTarget MakePoseTarget(const Eigen::Isometry3d& X_BaseTarget);
/// A position with the tool's z axis along `z_Base` (normalized here). Throws KinematicsError
/// when a value is not finite or z_Base is (nearly) zero.
IkTarget MakeAxisTarget(const Eigen::Vector3d& p_BaseTarget, const Eigen::Vector3d& z_Base);
/// A position-only target. Throws KinematicsError when it is not finite.
IkTarget MakePositionTarget(const Eigen::Vector3d& p_BaseTarget);

struct IkOptions {
  int max_iterations = 300;
  double damping = 0.05;  // λ of (J Jᵀ + λ² I)
  double position_tolerance_m = 0.002;
  double rotation_tolerance_rad = 0.02;
  double rotation_weight_m = 0.2;  // metres of position error worth one radian
  double max_step = 0.2;           // per joint per iteration (rad, or m for prismatic)
  /// When > 0: give up once the weighted error has not dropped by 1 % for this many
  /// iterations (a local minimum or a joint limit); 0 runs all max_iterations.
  int stall_iterations = 0;
  /// When true, a joint at a limit whose step would push it further out is left out of that
  /// iteration's solve (its Jacobian column zeroed, then solved again), so the other joints
  /// take up the motion instead of the step being lost to clamping. Converges more often near
  /// joint limits; off by default, which is the plain clamped solver.
  bool release_limited_joints = false;
  /// Indices of joints kept at their starting value (e.g. the first joint of an arm whose
  /// reach is mapped in one half-plane).
  std::vector<int> held_joints;
};

struct IkResult {
  Eigen::VectorXd q;              // within the joint limits (held joints as started)
  double position_error_m = 0;    // at q
  double rotation_error_rad = 0;  // at q; 0 for position-only targets
  int iterations = 0;             // steps taken (summed over the attempts of a restart search)
  bool converged = false;         // both errors within the tolerances
};

/// Joint values that bring the tool to `target`, starting from q_start (clamped into the limits)
/// and staying within the joint limits. converged is false when the tolerances were not met
/// within max_iterations (the target is out of reach, or the search got stuck): q is then where
/// it stopped. Throws KinematicsError when q_start has the wrong size, an option is out of range
/// (negative tolerance or damping, max_iterations < 0, max_step <= 0, a held joint's index
/// outside the chain) or the chain is invalid.
IkResult SolveIk(const Chain& chain, const IkTarget& target, const Eigen::VectorXd& q_start,
                 const IkOptions& options = {});

/// SolveIk from q_start, then, until one converges, from up to `restarts` joint vectors drawn
/// uniformly within the limits by a geometry::Rng seeded with `seed` (held joints keep
/// q_start's values). Deterministic for a seed. Returns the first converged result, or else
/// the attempt that ended nearest the target (weighted error). Throws as SolveIk, and when
/// restarts < 0.
IkResult SolveIkWithRestarts(const Chain& chain, const IkTarget& target,
                             const Eigen::VectorXd& q_start, const IkOptions& options, int restarts,
                             uint64_t seed);

}  // namespace prs::kinematics
