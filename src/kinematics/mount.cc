// The arm-mount convention (see mount.h).
#include "kinematics/mount.h"

#include <numbers>

namespace prs::kinematics {

Eigen::Isometry3d CalcArmMount(const Eigen::Vector3d& p_WO, const Eigen::Matrix3d& R_WO,
                               const Eigen::Vector3d& dimensions) {
  Eigen::Isometry3d X_WBase = Eigen::Isometry3d::Identity();
  X_WBase.translation() = p_WO - R_WO.col(2) * (dimensions.z() / 2);
  // The object's +y (forward) becomes the base's +x: a quarter turn about the object's z.
  X_WBase.linear() =
      R_WO * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X_WBase;
}

}  // namespace prs::kinematics
