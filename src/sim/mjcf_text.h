// Numbers in MJCF text as the sim's writers (panda.cc, world.cc) print them: enough digits that
// poses survive the round trip through MuJoCo's parser.
#pragma once

#include <fmt/format.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace prs::sim::internal {

/// "x y z" for a pos, size or axis attribute.
inline std::string FormatVector(const Eigen::Vector3d& v) {
  return fmt::format("{:.9g} {:.9g} {:.9g}", v.x(), v.y(), v.z());
}

/// "w x y z", MuJoCo's quat order.
inline std::string FormatQuat(const Eigen::Quaterniond& q) {
  return fmt::format("{:.12g} {:.12g} {:.12g} {:.12g}", q.w(), q.x(), q.y(), q.z());
}

}  // namespace prs::sim::internal
