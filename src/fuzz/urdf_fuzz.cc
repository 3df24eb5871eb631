// libFuzzer entry point for URDF robot descriptions as an `arm: "robot.urdf"` property has them
// read: kinematics::LoadUrdfChain with the default base and tool links and with named ones, and
// for a chain that loads, its tool pose and Jacobian at mid-range and a short inverse
// kinematics solve. A description may be refused only with KinematicsError (a message for the
// user); any other exception, crash, hang, leak or sanitizer report is a bug (spec §9).
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "kinematics/chain.h"
#include "kinematics/ik.h"
#include "kinematics/urdf.h"

namespace {

constexpr size_t kMaxInputBytes = 64 * 1024;

void LoadAndMove(const std::string& text, const std::string& base, const std::string& tool) {
  try {
    const prs::kinematics::Chain chain = prs::kinematics::LoadUrdfChain(text, "fuzz.urdf", base, tool);
    const Eigen::VectorXd q = prs::kinematics::CalcMidRange(chain);
    prs::kinematics::Jacobian J;
    const Eigen::Isometry3d X = prs::kinematics::CalcToolPoseAndJacobian(chain, q, &J);
    prs::kinematics::IkOptions options;
    options.max_iterations = 20;
    const Eigen::Vector3d p = X.translation() + Eigen::Vector3d(0.01, -0.02, 0.03);
    if (p.allFinite()) {
      volatile bool sink = prs::kinematics::SolveIk(chain, prs::kinematics::MakePositionTarget(p), q, options).converged;
      (void)sink;
    }
  } catch (const prs::kinematics::KinematicsError&) {
    // refused with a message: what a user sees after "r's arm: "
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInputBytes) return -1;
  const std::string text(reinterpret_cast<const char*>(data), size);
  LoadAndMove(text, "", "");
  LoadAndMove(text, "base", "tool");
  return 0;
}
