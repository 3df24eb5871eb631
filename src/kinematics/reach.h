// Where an arm can put its tool with a given grasp: an inner approximation of the reachable
// set as a union of convex cells with disjoint interiors, in the arm's base frame, computed
// once per arm and options and cached on disk (docs/kinematics.md has the algorithm).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/region.h"
#include "kinematics/chain.h"
#include "kinematics/ik.h"

namespace prs::kinematics {

enum class Grasp {
  kDown,  // the tool's z axis along −z of the base, any rotation about it
  kSide,  // the tool's z axis horizontal, pointing radially away from the base's z axis, any roll
  kAny,   // position only
};

struct ReachOptions {
  Grasp grasp = Grasp::kDown;
  /// Keep only points whose whole ball of this radius is reachable too (metres, >= 0).
  double margin_m = 0;
  /// Keep only points from which the tool can also back off this far along its approach —
  /// straight up for kDown, radially toward the base's z axis for kSide — staying reachable
  /// (metres, >= 0; must be 0 for kAny).
  double approach_m = 0;
  /// Grid spacing of the reachability map (metres, in [0.001, 0.1]). Chains without the
  /// rotational symmetry use a 3-D grid at least 0.02 m coarse.
  double resolution_m = 0.005;
  /// The widest angular sector one cell spans (radians, in [0.01, π/2]).
  double max_sector_rad = 0.1745;  // 10°
};

/// How a reachable set was computed.
struct ReachStats {
  bool symmetric = false;  // the half-plane map turned about joint 1 (else the 3-D grid)
  int grid_nodes = 0;      // nodes in the map's bounding grid
  int nodes_tested = 0;    // nodes whose reachability was decided by IK (incl. cell centres)
  int nodes_reachable = 0;
  int64_t ik_iterations = 0;
  double seconds = 0;  // the computation's wall time (not a cache load's)
};

/// The inner approximation: every point of every cell is reachable with the grasp (IK within
/// the joint limits, up to the map's resolution; see docs/kinematics.md), and cells have
/// pairwise disjoint interiors, so a uniform point of the union is a cell picked by volume
/// then a uniform point of it. Cells are in the arm's base frame and finalized
/// (ConvexRegion::Finalize), so a set may be queried from several threads at once.
struct ReachableSet {
  std::vector<geometry::ConvexRegion> cells_Base;
  std::vector<double> cell_volumes_m3;  // one per cell
  double volume_m3 = 0;                 // their sum
  ReachStats stats;
  std::string key;  // CalcReachKey of the chain and options
};

/// A short hexadecimal key (64-bit FNV-1a) of the algorithm's format version, the chain (joint
/// types, transforms, axes and limits printed with %.17g) and the options: equal keys mean
/// equal reachable sets.
std::string CalcReachKey(const Chain& chain, const ReachOptions& options);

/// Computes the reachable set (single-threaded; deterministic). Throws KinematicsError for an
/// invalid chain or options: a negative or non-finite margin or approach, an approach with
/// kAny (or with kSide on a chain without the rotational symmetry), a resolution or sector
/// width out of range.
ReachableSet ComputeReachableSet(const Chain& chain, const ReachOptions& options);

struct ReachLoad {
  std::shared_ptr<const ReachableSet> set;
  bool from_cache = false;
  double seconds = 0;   // loading or computing
  std::string warning;  // why a cache file was not used or written; empty when all went well
};

/// The reachable set from `cache_dir`/reach-<key>.txt when that file is present and valid;
/// otherwise computed and, when cache_dir is not empty, written there atomically (a temporary
/// file in the same directory, then a rename; directories are created). A corrupt or
/// mismatching cache file, or one that cannot be written, sets `warning` and is never fatal.
/// An empty cache_dir disables the disk cache. Throws as ComputeReachableSet.
ReachLoad LoadOrComputeReachableSet(const Chain& chain, const ReachOptions& options,
                                    const std::string& cache_dir);

/// An independent, thorough reachability test of one point (joint 1 free, unlike the map):
/// IK for the grasp at p_Base from a pose turned toward the point and from `restarts`
/// pseudo-random joint vectors (seeded by `seed`), within the joint limits, to within
/// kReachCheckPosition_m and kReachCheckRotation_rad (300 iterations, releasing limited joints,
/// an attempt dropped after 40 without progress). For kSide, a point on the base's z axis (no
/// radial direction) is unreachable. Throws KinematicsError for an invalid chain.
bool IsReachable(const Chain& chain, const Eigen::Vector3d& p_Base, Grasp grasp, int restarts,
                 uint64_t seed = 1);

inline constexpr double kReachCheckPosition_m = 1e-3;
inline constexpr double kReachCheckRotation_rad = 0.01;

/// The IK target for the grasp at p_Base (see Grasp). Throws KinematicsError for kSide on the
/// base's z axis.
IkTarget MakeGraspTarget(const Eigen::Vector3d& p_Base, Grasp grasp);

/// "down", "side", "any".
const char* GraspName(Grasp grasp);

}  // namespace prs::kinematics
