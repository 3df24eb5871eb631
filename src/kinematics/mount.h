// Where an arm stands for a robot object of a scene: the one convention shared by the language
// (reachable sets in the world) and the simulator (the arm's body in MuJoCo).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace prs::kinematics {

/// X_WBase of the arm a Robot object stands for, from the object's pose (p_WO, R_WO; R_WO
/// orthonormal) and its box's dimensions (width x, length y, height z; metres): the base at the
/// centre of the box's bottom face (a Robot object stands `on` its support and its box is the
/// whole robot, so the arm stands where the box does), the base's x axis along the object's
/// forward +y and its z axis along the object's up. Independent of the box's height otherwise.
Eigen::Isometry3d CalcArmMount(const Eigen::Vector3d& p_WO, const Eigen::Matrix3d& R_WO,
                               const Eigen::Vector3d& dimensions);

}  // namespace prs::kinematics
