// Reachable sets (see reach.h): option checks, the key, the independent reachability test, and
// the computation's outline (maps in reach_grid.cc, cells in reach_cells.cc).
#include "kinematics/reach.h"

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "kinematics/reach_internal.h"

namespace prs::kinematics {

namespace {

using internal::CellGrid;
using internal::Symmetry;

constexpr double kPi = std::numbers::pi;

void ValidateOptions(const Chain& chain, const ReachOptions& o, bool symmetric) {
  auto fail = [&](const std::string& what) {
    throw KinematicsError("reachable set of '" + chain.name + "': " + what);
  };
  auto text = [](double v) { return std::to_string(v); };
  if (!std::isfinite(o.margin_m) || o.margin_m < 0)
    fail("the margin must be >= 0 m, not " + text(o.margin_m));
  if (!std::isfinite(o.approach_m) || o.approach_m < 0) {
    fail("the approach must be >= 0 m, not " + text(o.approach_m));
  }
  if (o.approach_m > 0 && o.grasp == Grasp::kAny) {
    fail("an approach needs a grasp with a direction (down or side), not 'any'");
  }
  if (o.approach_m > 0 && o.grasp == Grasp::kSide && !symmetric) {
    fail("a side approach needs an arm whose first joint turns about the base's z axis");
  }
  if (!(o.resolution_m >= 0.001 && o.resolution_m <= 0.1)) {
    fail("the resolution must be within [0.001, 0.1] m, not " + text(o.resolution_m));
  }
  if (!(o.max_sector_rad >= 0.01 && o.max_sector_rad <= kPi / 2)) {
    fail("the widest sector must be within [0.01, pi/2] rad, not " + text(o.max_sector_rad));
  }
}

double CalcAzimuth(const Eigen::Vector3d& p) { return std::atan2(p.y(), p.x()); }

double WrapAngle(double a) { return std::remainder(a, 2 * kPi); }

}  // namespace

namespace internal {

std::optional<Symmetry> FindSymmetry(const Chain& chain) {
  if (chain.joints.empty() || chain.joints[0].type != JointType::kRevolute) return std::nullopt;
  const Joint& j = chain.joints[0];
  const Eigen::Vector3d axis_Base = j.X_PJ.linear() * j.axis_J;
  if (axis_Base.head<2>().norm() > 1e-9 || j.X_PJ.translation().head<2>().norm() > 1e-9) {
    return std::nullopt;
  }
  Symmetry s;
  s.sign = axis_Base.z() > 0 ? 1 : -1;
  s.lower = j.lower;
  s.upper = j.upper;
  s.q_ref = (j.lower <= 0 && 0 <= j.upper) ? 0.0 : 0.5 * (j.lower + j.upper);
  return s;
}

}  // namespace internal

const char* GraspName(Grasp grasp) {
  switch (grasp) {
    case Grasp::kDown:
      return "down";
    case Grasp::kSide:
      return "side";
    case Grasp::kAny:
      return "any";
  }
  return "?";
}

IkTarget MakeGraspTarget(const Eigen::Vector3d& p_Base, Grasp grasp) {
  switch (grasp) {
    case Grasp::kDown:
      return MakeAxisTarget(p_Base, -Eigen::Vector3d::UnitZ());
    case Grasp::kSide: {
      const Eigen::Vector3d radial(p_Base.x(), p_Base.y(), 0);
      if (radial.norm() < 1e-9) {
        throw KinematicsError("a side grasp has no radial direction on the base's z axis");
      }
      return MakeAxisTarget(p_Base, radial);
    }
    case Grasp::kAny:
      return MakePositionTarget(p_Base);
  }
  return MakePositionTarget(p_Base);
}

std::string CalcReachKey(const Chain& chain, const ReachOptions& options) {
  std::string text = "prs-reach " + std::to_string(internal::kReachFormatVersion) + "\n";
  char buffer[64];
  auto add = [&](double v) {
    std::snprintf(buffer, sizeof buffer, "%.17g ", v);
    text += buffer;
  };
  auto add_pose = [&](const Eigen::Isometry3d& X) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) add(X.matrix()(r, c));
    }
  };
  for (const Joint& j : chain.joints) {
    text += j.type == JointType::kRevolute ? "R " : "P ";
    add_pose(j.X_PJ);
    for (int a = 0; a < 3; ++a) add(j.axis_J[a]);
    add(j.lower);
    add(j.upper);
    text += "\n";
  }
  add_pose(chain.X_LastTool);
  text += std::string("\n") + GraspName(options.grasp) + " ";
  for (double v :
       {options.margin_m, options.approach_m, options.resolution_m, options.max_sector_rad})
    add(v);
  uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  std::snprintf(buffer, sizeof buffer, "%016" PRIx64, hash);
  return buffer;
}

ReachableSet ComputeReachableSet(const Chain& chain, const ReachOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ValidateChain(chain);
  const std::optional<Symmetry> symmetry = internal::FindSymmetry(chain);
  ValidateOptions(chain, options, symmetry.has_value());
  ReachableSet set;
  set.key = CalcReachKey(chain, options);
  set.stats.symmetric = symmetry.has_value();
  if (symmetry) {
    const std::vector<double> sheet_rad = internal::CalcSheetAngles(*symmetry);
    std::vector<CellGrid> sheets;
    for (double angle : sheet_rad) {
      sheets.push_back(
          internal::ComputeHalfPlaneGrid(chain, *symmetry, angle, options, &set.stats));
    }
    internal::MakeSectorCells(sheets, sheet_rad, *symmetry, options, &set);
  } else {
    internal::MakeBoxCells(internal::ComputeVolumeGrid(chain, options, &set.stats), &set);
  }
  for (const geometry::ConvexRegion& cell : set.cells_Base) cell.Finalize();
  set.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return set;
}

bool IsReachable(const Chain& chain, const Eigen::Vector3d& p_Base, Grasp grasp, int restarts,
                 uint64_t seed) {
  ValidateChain(chain);
  if (grasp == Grasp::kSide && p_Base.head<2>().norm() < 1e-9) return false;
  const IkTarget target = MakeGraspTarget(p_Base, grasp);
  IkOptions options;
  options.position_tolerance_m = kReachCheckPosition_m;
  options.rotation_tolerance_rad = kReachCheckRotation_rad;
  options.stall_iterations = 40;
  options.release_limited_joints = true;
  // First from the middle of the ranges turned toward the point (and away from it, for over
  // the shoulder), then from pseudo-random joints.
  Eigen::VectorXd q = CalcMidRange(chain);
  std::vector<Eigen::VectorXd> starts = {q};
  if (const std::optional<Symmetry> s = internal::FindSymmetry(chain)) {
    const Eigen::Vector3d p_tool = CalcToolPose(chain, q).translation();
    for (double turn : {0.0, kPi}) {
      double q1 = q[0] + s->sign * WrapAngle(CalcAzimuth(p_Base) + turn - CalcAzimuth(p_tool));
      for (double k : {-2 * kPi, 2 * kPi}) {
        if (q1 < s->lower || q1 > s->upper)
          q1 += (q1 + k >= s->lower && q1 + k <= s->upper) ? k : 0;
      }
      Eigen::VectorXd turned = q;
      turned[0] = q1;
      starts.push_back(ClampToLimits(chain, turned));
    }
  }
  for (const Eigen::VectorXd& start : starts) {
    if (SolveIk(chain, target, start, options).converged) return true;
  }
  return SolveIkWithRestarts(chain, target, starts.back(), options, restarts, seed).converged;
}

}  // namespace prs::kinematics
