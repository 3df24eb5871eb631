// Reachability maps on grids (see reach_internal.h): IK at grid nodes by flood fill from seeds,
// each node warm-started from a reachable neighbour's joints, then cells whose corners and
// centre are reachable, filtered for the approach and eroded for the margin.
#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>

#include "geometry/random.h"
#include "kinematics/reach_internal.h"

namespace prs::kinematics::internal {

namespace {

constexpr int kUnknown = 0, kReachable = 1, kUnreachable = 2;
// Restarts from pseudo-random joints before a node is declared unreachable, and for seeds.
constexpr int kNodeRestarts = 2;
constexpr int kSeedRestarts = 1;
// Seed lattices: 4 cm in the half-plane, 10 cm in 3-D (where a lattice has far more nodes).
constexpr double kSeedSpacing2d_m = 0.04, kSeedSpacing3d_m = 0.1;

// A bound on how far the tool can be from joint `first`'s origin: the sum of the chain's
// offsets after it (and prismatic travel).
double CalcReachBound(const Chain& chain, int first) {
  double bound = chain.X_LastTool.translation().norm();
  for (int i = first; i < chain.num_joints(); ++i) {
    const Joint& j = chain.joints[i];
    if (i > first) bound += j.X_PJ.translation().norm();
    if (j.type == JointType::kPrismatic) bound += std::max(std::abs(j.lower), std::abs(j.upper));
  }
  return bound;
}

// Grid nodes with IK solutions, filled by BFS from seeds.
class NodeMap {
 public:
  // Nodes at resolution·(origin + index) in map coordinates, turned by R_BaseMap into the base
  // frame for IK.
  NodeMap(const Chain& chain, Grasp grasp, const IkOptions& ik, const Eigen::VectorXd& q_home,
          const Eigen::Matrix3d& R_BaseMap, double resolution, std::array<int, 3> origin,
          std::array<int, 3> size, ReachStats* stats)
      : chain_(chain),
        grasp_(grasp),
        ik_(ik),
        q_home_(q_home),
        R_BaseMap_(R_BaseMap),
        resolution_(resolution),
        origin_(origin),
        size_(size),
        stats_(stats),
        n_(chain.num_joints()) {
    const size_t count = static_cast<size_t>(size[0]) * size[1] * size[2];
    state_.assign(count, kUnknown);
    q_.resize(count * n_);
    stats_->grid_nodes += static_cast<int>(count);
  }

  size_t Index(int i, int j, int k) const {
    return i + size_[0] * (j + size_[1] * static_cast<size_t>(k));
  }
  bool IsReachable(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < size_[0] && j < size_[1] && k < size_[2] &&
           state_[Index(i, j, k)] == kReachable;
  }
  Eigen::Vector3d Point(double i, double j, double k) const {
    return resolution_ * Eigen::Vector3d(origin_[0] + i, origin_[1] + j, origin_[2] + k);
  }
  const double* q(size_t index) const { return &q_[index * n_]; }

  // Tries seeds on a coarse lattice (`seed_spacing` apart) within `bound` of p_center and
  // floods out from each.
  void Fill(const Eigen::Vector3d& p_center, double bound, double seed_spacing) {
    const int step = std::max(1, static_cast<int>(std::lround(seed_spacing / resolution_)));
    for (int k = 0; k < size_[2]; k += step) {
      for (int j = 0; j < size_[1]; j += step) {
        for (int i = 0; i < size_[0]; i += step) {
          if (state_[Index(i, j, k)] != kUnknown) continue;
          if ((Point(i, j, k) - p_center).norm() > bound) continue;
          if (Decide(i, j, k, {q_home_.data()}, kSeedRestarts)) Flood(Index(i, j, k));
        }
      }
    }
  }

  // IK at any point of the map (a cell centre), warm-started from the given joint vectors.
  bool Solve(const Eigen::Vector3d& p_map, const std::vector<const double*>& starts, int restarts,
             uint64_t seed, Eigen::VectorXd* q_out) {
    const Eigen::Vector3d p_Base = R_BaseMap_ * p_map;
    if (grasp_ == Grasp::kSide && p_Base.head<2>().norm() < 1e-9) return false;
    const IkTarget target = MakeGraspTarget(p_Base, grasp_);
    ++stats_->nodes_tested;
    Eigen::VectorXd q(n_);
    for (const double* start : starts) {
      q = Eigen::Map<const Eigen::VectorXd>(start, n_);
      const IkResult result = SolveIk(chain_, target, q, ik_);
      stats_->ik_iterations += result.iterations;
      if (result.converged) return *q_out = result.q, true;
    }
    geometry::Rng rng(seed, 0x5eed);
    for (int r = 0; r < restarts; ++r) {
      for (int i = 0; i < n_; ++i) {
        const Joint& joint = chain_.joints[i];
        q[i] = IsHeld(i) ? q_home_[i] : rng.Uniform(joint.lower, joint.upper);
      }
      const IkResult result = SolveIk(chain_, target, q, ik_);
      stats_->ik_iterations += result.iterations;
      if (result.converged) return *q_out = result.q, true;
    }
    return false;
  }

 private:
  bool IsHeld(int joint) const {
    return std::find(ik_.held_joints.begin(), ik_.held_joints.end(), joint) !=
           ik_.held_joints.end();
  }

  bool Decide(int i, int j, int k, const std::vector<const double*>& starts, int restarts) {
    const size_t index = Index(i, j, k);
    Eigen::VectorXd q;
    const bool reachable = Solve(Point(i, j, k), starts, restarts, index + 1, &q);
    state_[index] = reachable ? kReachable : kUnreachable;
    if (reachable) {
      std::copy(q.data(), q.data() + n_, &q_[index * n_]);
      ++stats_->nodes_reachable;
    }
    return reachable;
  }

  void Flood(size_t seed) {
    std::deque<size_t> queue = {seed};
    while (!queue.empty()) {
      const size_t index = queue.front();
      queue.pop_front();
      const int i = static_cast<int>(index % size_[0]);
      const int j = static_cast<int>(index / size_[0] % size_[1]);
      const int k = static_cast<int>(index / size_[0] / size_[1]);
      for (const auto& d : kFaceSteps) {
        const int a = i + d[0], b = j + d[1], c = k + d[2];
        if (a < 0 || b < 0 || c < 0 || a >= size_[0] || b >= size_[1] || c >= size_[2]) continue;
        if (state_[Index(a, b, c)] != kUnknown) continue;
        if (Decide(a, b, c, NeighbourStarts(a, b, c, index), kNodeRestarts)) {
          queue.push_back(Index(a, b, c));
        }
      }
    }
  }

  // The discovering node's joints first, then one other reachable neighbour's.
  std::vector<const double*> NeighbourStarts(int i, int j, int k, size_t from) const {
    std::vector<const double*> starts = {q(from)};
    for (const auto& d : kFaceSteps) {
      if (!IsReachable(i + d[0], j + d[1], k + d[2])) continue;
      const size_t other = Index(i + d[0], j + d[1], k + d[2]);
      if (other == from) continue;
      starts.push_back(q(other));
      break;
    }
    return starts;
  }

  static constexpr int kFaceSteps[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                           {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};

  const Chain& chain_;
  const Grasp grasp_;
  const IkOptions ik_;
  const Eigen::VectorXd q_home_;
  const Eigen::Matrix3d R_BaseMap_;
  const double resolution_;
  const std::array<int, 3> origin_, size_;
  ReachStats* const stats_;
  const int n_;
  std::vector<uint8_t> state_;
  std::vector<double> q_;
};

IkOptions MakeMapIkOptions() {
  IkOptions o;
  o.max_iterations = 100;
  o.position_tolerance_m = kMapPosition_m;
  o.rotation_tolerance_rad = kMapRotation_rad;
  o.stall_iterations = 15;
  o.release_limited_joints = true;
  return o;
}

// Cells whose corners (4 in the half-plane, 8 in 3-D) and centre are reachable.
CellGrid MarkReachableCells(NodeMap& map, std::array<int, 3> node_size, double resolution,
                            std::array<int, 3> origin) {
  CellGrid grid;
  grid.resolution_m = resolution;
  grid.origin = origin;
  const bool flat = node_size[1] == 1;
  grid.size = {node_size[0] - 1, flat ? 1 : node_size[1] - 1, node_size[2] - 1};
  grid.in.assign(static_cast<size_t>(grid.size[0]) * grid.size[1] * grid.size[2], 0);
  for (int k = 0; k < grid.size[2]; ++k) {
    for (int j = 0; j < grid.size[1]; ++j) {
      for (int i = 0; i < grid.size[0]; ++i) {
        std::vector<const double*> starts;
        bool corners = true;
        for (int c = 0; c < (flat ? 4 : 8) && corners; ++c) {
          const int a = i + (c & 1), b = j + (flat ? 0 : (c >> 2) & 1), d = k + ((c >> 1) & 1);
          corners = map.IsReachable(a, b, d);
          if (corners && starts.size() < 2) starts.push_back(map.q(map.Index(a, b, d)));
        }
        if (!corners) continue;
        const Eigen::Vector3d p_centre = map.Point(i + 0.5, flat ? 0 : j + 0.5, k + 0.5);
        Eigen::VectorXd q;
        const size_t cell = i + grid.size[0] * (j + grid.size[1] * static_cast<size_t>(k));
        if (map.Solve(p_centre, starts, 0, cell + 1, &q)) grid.in[cell] = 1;
      }
    }
  }
  return grid;
}

// Keeps a cell only when the cells its tool backs off through are in too: K cells up (kDown),
// or K cells toward x = 0 on the same side (kSide, half-plane grids).
void FilterForApproach(const ReachOptions& options, CellGrid* grid) {
  if (options.approach_m <= 0) return;
  const int steps = static_cast<int>(std::ceil(options.approach_m / grid->resolution_m - 1e-9));
  const CellGrid before = *grid;
  for (int k = 0; k < grid->size[2]; ++k) {
    for (int j = 0; j < grid->size[1]; ++j) {
      for (int i = 0; i < grid->size[0]; ++i) {
        const size_t cell = i + grid->size[0] * (j + grid->size[1] * static_cast<size_t>(k));
        if (!grid->in[cell]) continue;
        const int x = grid->origin[0] + i;  // the cell's signed index along x
        bool ok = true;
        for (int s = 1; s <= steps && ok; ++s) {
          if (options.grasp == Grasp::kDown) {
            ok = before.is_in(i, j, k + s);
          } else {
            const int toward = x >= 0 ? -s : s;
            ok = (x >= 0) == (x + toward >= 0) && before.is_in(i + toward, j, k);
          }
        }
        grid->in[cell] = ok;
      }
    }
  }
}

// Erosion by a cube of `radius` cells (Chebyshev), one axis at a time.
void Erode(int radius, CellGrid* grid) {
  for (int axis = 0; axis < 3; ++axis) {
    if (grid->size[axis] == 1 && axis == 1) continue;  // the half-plane grid's single y cell
    const CellGrid before = *grid;
    for (int k = 0; k < grid->size[2]; ++k) {
      for (int j = 0; j < grid->size[1]; ++j) {
        for (int i = 0; i < grid->size[0]; ++i) {
          const size_t cell = i + grid->size[0] * (j + grid->size[1] * static_cast<size_t>(k));
          if (!grid->in[cell]) continue;
          for (int s = -radius; s <= radius && grid->in[cell]; ++s) {
            const std::array<int, 3> p = {i + (axis == 0) * s, j + (axis == 1) * s,
                                          k + (axis == 2) * s};
            if (!before.is_in(p[0], p[1], p[2])) grid->in[cell] = 0;
          }
        }
      }
    }
  }
}

void ApplyFilters(const ReachOptions& options, CellGrid* grid) {
  FilterForApproach(options, grid);
  if (options.margin_m > 0) {
    Erode(static_cast<int>(std::ceil(options.margin_m / grid->resolution_m - 1e-9)) + 1, grid);
  }
}

}  // namespace

bool TurnsAllTheWay(const Symmetry& symmetry) {
  return symmetry.upper - symmetry.lower >= 2 * std::numbers::pi - 1e-12;
}

std::vector<double> CalcSheetAngles(const Symmetry& symmetry) {
  if (TurnsAllTheWay(symmetry)) return {0.0};
  std::vector<double> angles = {0.0};
  const double gap = 2 * std::numbers::pi - (symmetry.upper - symmetry.lower);
  if (gap > 1e-3) angles.push_back(gap);
  angles.push_back(std::numbers::pi / 2);
  return angles;
}

CellGrid ComputeHalfPlaneGrid(const Chain& chain, const Symmetry& symmetry, double sheet_rad,
                              const ReachOptions& options, ReachStats* stats) {
  const double res = options.resolution_m;
  const double z_shoulder = chain.joints[0].X_PJ.translation().z();
  const double bound = CalcReachBound(chain, 0);
  const int half = static_cast<int>(std::ceil(bound / res));
  const std::array<int, 3> origin = {-half, 0,
                                     static_cast<int>(std::floor((z_shoulder - bound) / res))};
  const std::array<int, 3> size = {
      2 * half + 1, 1, static_cast<int>(std::ceil((z_shoulder + bound) / res)) - origin[2] + 1};
  Eigen::VectorXd q_home = CalcMidRange(chain);
  q_home[0] = symmetry.q_ref;
  IkOptions ik = MakeMapIkOptions();
  // A joint 1 that turns all the way round gives every azimuth from any solution, wherever its
  // own value ends up: it is left free (arms whose wrist is offset from the plane of joint 1's
  // axis, like a UR, reach no point of that plane with joint 1 held).
  if (!TurnsAllTheWay(symmetry)) ik.held_joints = {0};
  const Eigen::Matrix3d R_BaseMap =
      Eigen::AngleAxisd(symmetry.sign * symmetry.q_ref + sheet_rad, Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  NodeMap map(chain, options.grasp, ik, q_home, R_BaseMap, res, origin, size, stats);
  map.Fill(Eigen::Vector3d(0, 0, z_shoulder), bound, kSeedSpacing2d_m);
  CellGrid grid = MarkReachableCells(map, size, res, origin);
  ApplyFilters(options, &grid);
  return grid;
}

CellGrid ComputeVolumeGrid(const Chain& chain, const ReachOptions& options, ReachStats* stats) {
  const double res = std::max(0.02, options.resolution_m);
  const Eigen::Vector3d p_first = chain.joints[0].X_PJ.translation();
  const double bound = CalcReachBound(chain, 0);
  std::array<int, 3> origin{}, size{};
  for (int a = 0; a < 3; ++a) {
    origin[a] = static_cast<int>(std::floor((p_first[a] - bound) / res));
    size[a] = static_cast<int>(std::ceil((p_first[a] + bound) / res)) - origin[a] + 1;
  }
  IkOptions ik = MakeMapIkOptions();
  NodeMap map(chain, options.grasp, ik, CalcMidRange(chain), Eigen::Matrix3d::Identity(), res,
              origin, size, stats);
  map.Fill(p_first, bound, kSeedSpacing3d_m);
  CellGrid grid = MarkReachableCells(map, size, res, origin);
  ApplyFilters(options, &grid);
  return grid;
}

}  // namespace prs::kinematics::internal
