// The Panda arm's MJCF body tree (see panda.h).
#include "sim/panda.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "sim/mjcf_text.h"

namespace prs::sim {

namespace {

using internal::FormatQuat;
using internal::FormatVector;

constexpr double kPi = std::numbers::pi;
constexpr double kLinkRadius_m = 0.055;
// Contact groups: the arm touches the world (and the cube) but not itself, as its simple link
// shapes overlap at the joints.
constexpr const char* kArmContact = R"(contype="2" conaffinity="1")";

Eigen::Vector3d CalcChildOffset(const PandaDhRow& row) {
  return {row.a_m, -row.d_m * std::sin(row.alpha_rad), row.d_m * std::cos(row.alpha_rad)};
}

// A capsule from the link's origin to the next joint's origin, or a ball when they coincide.
std::string WriteLinkGeom(const Eigen::Vector3d& p_next) {
  if (p_next.norm() < 1e-6) {
    return fmt::format(R"(<geom type="sphere" size="{}" rgba="0.92 0.92 0.92 1" {}/>)",
                       kLinkRadius_m, kArmContact);
  }
  return fmt::format(R"(<geom type="capsule" fromto="0 0 0 {}" size="{}" rgba="0.92 0.92 0.92 1" {}/>)",
                     FormatVector(p_next), kLinkRadius_m, kArmContact);
}

std::string WriteHand(const PandaNames& n) {
  const Eigen::Quaterniond R_FlangeHand(Eigen::AngleAxisd(-kPi / 4, Eigen::Vector3d::UnitZ()));
  std::string xml = fmt::format(R"(<body name="{}" quat="{}">)", n.hand(), FormatQuat(R_FlangeHand));
  xml += fmt::format(R"(<geom type="box" size="0.02 0.1 0.025" pos="0 0 0.025" mass="0.7" )"
                     R"(rgba="0.92 0.92 0.92 1" {}/>)", kArmContact);
  xml += fmt::format(R"(<site name="{}" pos="0 0 {}" size="0.005"/>)", n.tcp_site(),
                     kPandaFlangeToTcp_m);
  // The finger pads' contacts are stiffer than MuJoCo's default (0.004 s, not 0.02 s): a 70 N
  // grip sank 5.5 mm into the cube with the default.
  for (int side = 0; side < 2; ++side) {
    const double sign = side ? -1 : 1;
    xml += fmt::format(R"(<body name="{0}_body" pos="0 0 0.0584">)"
                       R"(<joint name="{0}" type="slide" axis="0 {1} 0" range="0 {2}" limited="true" damping="5"/>)"
                       R"(<geom type="box" size="0.01 0.008 0.026" pos="0 {3} 0.026" mass="0.05" )"
                       R"(friction="2 0.01 0.001" condim="4" solref="0.004 1" )"
                       R"(rgba="0.2 0.2 0.2 1" {4}/></body>)",
                       n.finger_joint(side), sign, kPandaFingerTravel_m, sign * 0.008, kArmContact);
  }
  return xml + "</body>";
}

}  // namespace

std::string WritePandaBody(const PandaNames& n, const Eigen::Vector3d& p_WBase,
                           const Eigen::Quaterniond& R_WBase) {
  std::string xml = fmt::format(R"(<body name="{}" pos="{}" quat="{}">)", n.base(),
                                FormatVector(p_WBase), FormatQuat(R_WBase));
  xml += fmt::format(R"(<geom type="cylinder" size="0.06 0.05" pos="0 0 0.05" {}/>)", kArmContact);
  for (int i = 0; i < kPandaJoints; ++i) {
    const PandaDhRow& row = kPandaDh[i];
    const Eigen::Quaterniond R_parent_child(Eigen::AngleAxisd(row.alpha_rad, Eigen::Vector3d::UnitX()));
    const double damping = i < 4 ? 40 : 10;
    xml += fmt::format(R"(<body name="{}link{}" pos="{}" quat="{}">)", n.prefix, i + 1,
                       FormatVector(CalcChildOffset(row)), FormatQuat(R_parent_child));
    xml += fmt::format(R"(<joint name="{}" axis="0 0 1" range="{} {}" limited="true" )"
                       R"(damping="{}" armature="0.1" ref="0"/>)",
                       n.joint(i), kPandaLowerLimit_rad[i], kPandaUpperLimit_rad[i], damping);
    // The geometry runs to the next frame's origin, expressed in this frame.
    xml += WriteLinkGeom(CalcChildOffset(kPandaDh[i + 1]));
  }
  // The flange: fixed to link 7.
  xml += fmt::format(R"(<body name="{}flange" pos="{}">)", n.prefix, FormatVector(CalcChildOffset(kPandaDh[7])));
  xml += WriteHand(n) + "</body>";
  for (int i = 0; i < kPandaJoints; ++i) xml += "</body>";
  return xml + "</body>";
}

std::string WritePandaEqualities(const PandaNames& n) {
  // As stiff as the finger pads' contacts: with MuJoCo's default 0.02 s the coupled finger
  // lagged 9 mm behind the driven one under a 70 N grip.
  return fmt::format(R"(<joint joint1="{}" joint2="{}" polycoef="0 1 0 0 0" solref="0.004 1"/>)",
                     n.finger_joint(1), n.finger_joint(0));
}

std::string WritePandaActuators(const PandaNames& n) {
  std::string xml;
  for (int i = 0; i < kPandaJoints; ++i) {
    const double kp = i < 4 ? 2000 : 500;
    xml += fmt::format(R"(<position name="{}" joint="{}" kp="{}" ctrlrange="{} {}" ctrllimited="true"/>)",
                       n.actuator(i), n.joint(i), kp, kPandaLowerLimit_rad[i], kPandaUpperLimit_rad[i]);
  }
  // About 70 N of grip per finger at full closing error, the Panda hand's continuous force.
  xml += fmt::format(R"(<position name="{}" joint="{}" kp="1750" ctrlrange="0 {}" ctrllimited="true" )"
                     R"(forcerange="-70 70" forcelimited="true"/>)",
                     n.gripper_actuator(), n.finger_joint(0), kPandaFingerTravel_m);
  return xml;
}

}  // namespace prs::sim
