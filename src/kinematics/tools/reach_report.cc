// A developer tool for docs/kinematics.md: computes an arm's reachable set (cold, then from
// the cache), and measures it against the independent IK check — the share of points sampled
// from the cells that pass, and the coverage of the truly reachable points of a cylinder (with
// an approach, points whose approach passes too; a margin is not checked here).
// Usage: prs_reach_report [--urdf FILE [--base LINK] [--tool LINK]] [--grasp down|side|any]
//          [--approach M] [--margin M] [--resolution M] [--sector RAD] [--inside N]
//          [--coverage N] [--restarts N] [--cache DIR] [--seed S]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geometry/random.h"
#include "geometry/sampling.h"
#include "kinematics/panda.h"
#include "kinematics/reach.h"
#include "kinematics/urdf.h"

namespace {

using namespace prs;

struct Args {
  std::string urdf, base, tool, cache;
  kinematics::ReachOptions options;
  int inside = 1000, coverage = 2000, restarts = 30;
  uint64_t seed = 7;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "prs_reach_report: %s needs a value\n", flag.c_str());
      std::exit(2);
    }
    const std::string value = argv[++i];
    if (flag == "--urdf")
      a.urdf = value;
    else if (flag == "--base")
      a.base = value;
    else if (flag == "--tool")
      a.tool = value;
    else if (flag == "--cache")
      a.cache = value;
    else if (flag == "--grasp") {
      a.options.grasp = value == "side"  ? kinematics::Grasp::kSide
                        : value == "any" ? kinematics::Grasp::kAny
                                         : kinematics::Grasp::kDown;
    } else if (flag == "--approach")
      a.options.approach_m = std::atof(value.c_str());
    else if (flag == "--margin")
      a.options.margin_m = std::atof(value.c_str());
    else if (flag == "--resolution")
      a.options.resolution_m = std::atof(value.c_str());
    else if (flag == "--sector")
      a.options.max_sector_rad = std::atof(value.c_str());
    else if (flag == "--inside")
      a.inside = std::atoi(value.c_str());
    else if (flag == "--coverage")
      a.coverage = std::atoi(value.c_str());
    else if (flag == "--restarts")
      a.restarts = std::atoi(value.c_str());
    else if (flag == "--seed")
      a.seed = std::strtoull(value.c_str(), nullptr, 10);
    else {
      std::fprintf(stderr, "prs_reach_report: unknown flag %s\n", flag.c_str());
      std::exit(2);
    }
  }
  return a;
}

kinematics::Chain LoadChain(const Args& a) {
  if (a.urdf.empty()) return kinematics::MakePandaChain();
  std::ifstream in(a.urdf);
  std::stringstream text;
  text << in.rdbuf();
  return kinematics::LoadUrdfChain(text.str(), a.urdf, a.base, a.tool);
}

// A cell by volume, then a uniform point of it.
Eigen::Vector3d SampleSet(const kinematics::ReachableSet& set,
                          const std::vector<geometry::RegionSampler>& samplers,
                          geometry::Rng& rng) {
  double u = rng.Uniform(0, set.volume_m3);
  for (size_t c = 0; c < samplers.size(); ++c) {
    if (u < set.cell_volumes_m3[c] || c + 1 == samplers.size()) return samplers[c].Sample(rng);
    u -= set.cell_volumes_m3[c];
  }
  return Eigen::Vector3d::Zero();
}

// The point, and with an approach the points every centimetre back along it (up for a down
// grasp, toward the base's z axis for a side grasp), pass the IK check.
bool IsReachableWithApproach(const kinematics::Chain& chain, const Eigen::Vector3d& p,
                             const kinematics::ReachOptions& o, int restarts, uint64_t seed) {
  Eigen::Vector3d back = Eigen::Vector3d::UnitZ();
  if (o.grasp == kinematics::Grasp::kSide) back = -Eigen::Vector3d(p.x(), p.y(), 0).normalized();
  const int steps = static_cast<int>(std::ceil(o.approach_m / 0.01 - 1e-9));
  for (int k = 0; k <= steps; ++k) {
    const Eigen::Vector3d p_k = p + std::min(k * 0.01, o.approach_m) * back;
    if (!kinematics::IsReachable(chain, p_k, o.grasp, restarts, seed)) return false;
  }
  return true;
}

bool IsInSet(const kinematics::ReachableSet& set, const Eigen::Vector3d& p) {
  for (const auto& cell : set.cells_Base) {
    if (cell.Contains(p)) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = ParseArgs(argc, argv);
  const kinematics::Chain chain = LoadChain(a);
  const std::string cache =
      a.cache.empty() ? (std::filesystem::temp_directory_path() / "prs-reach-report").string()
                      : a.cache;
  std::filesystem::remove(std::filesystem::path(cache) /
                          ("reach-" + kinematics::CalcReachKey(chain, a.options) + ".txt"));
  const kinematics::ReachLoad cold = kinematics::LoadOrComputeReachableSet(chain, a.options, cache);
  const kinematics::ReachLoad warm = kinematics::LoadOrComputeReachableSet(chain, a.options, cache);
  const kinematics::ReachableSet& set = *cold.set;
  std::printf("arm %s, grasp %s, approach %.3g m, margin %.3g m, resolution %.3g m\n",
              chain.name.c_str(), kinematics::GraspName(a.options.grasp), a.options.approach_m,
              a.options.margin_m, a.options.resolution_m);
  std::printf(
      "computed in %.2f s (%s map, %d grid nodes, %d IK-tested, %d reachable, %lld IK "
      "iterations); loaded from the cache in %.3f s%s\n",
      cold.seconds, set.stats.symmetric ? "half-plane" : "3-D", set.stats.grid_nodes,
      set.stats.nodes_tested, set.stats.nodes_reachable,
      static_cast<long long>(set.stats.ik_iterations), warm.seconds,
      warm.from_cache ? "" : " (NOT from the cache)");
  std::printf("%zu cells, %.4f m^3\n", set.cells_Base.size(), set.volume_m3);
  if (set.cells_Base.empty()) return 0;

  std::vector<geometry::RegionSampler> samplers;
  for (const auto& cell : set.cells_Base) samplers.emplace_back(cell);
  geometry::Rng rng(a.seed, 1);
  int failed = 0;
  for (int i = 0; i < a.inside; ++i) {
    const Eigen::Vector3d p = SampleSet(set, samplers, rng);
    if (!IsReachableWithApproach(chain, p, a.options, a.restarts, i + 1)) {
      ++failed;
      std::printf("  unreachable sample (%.4f, %.4f, %.4f)\n", p.x(), p.y(), p.z());
    }
  }
  std::printf("inside: %d of %d points sampled from the cells pass the IK check\n",
              a.inside - failed, a.inside);

  // The cylinder around the base that holds the cells, grown by 0.15 m.
  double radius = 0, z_lo = 1e9, z_hi = -1e9;
  for (const auto& cell : set.cells_Base) {
    for (const Eigen::Vector3d& v : cell.CalcVertices()) {
      radius = std::max(radius, v.head<2>().norm());
      z_lo = std::min(z_lo, v.z());
      z_hi = std::max(z_hi, v.z());
    }
  }
  radius += 0.15, z_lo -= 0.15, z_hi += 0.15;
  int reachable = 0, covered = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < a.coverage; ++i) {
    Eigen::Vector3d p;
    do {
      p = {rng.Uniform(-radius, radius), rng.Uniform(-radius, radius), rng.Uniform(z_lo, z_hi)};
    } while (p.head<2>().norm() > radius);
    if (!IsReachableWithApproach(chain, p, a.options, a.restarts, 1000 + i)) continue;
    ++reachable;
    covered += IsInSet(set, p);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "coverage: %d of %d truly reachable points of the cylinder (r %.2f m, z %.2f..%.2f m, "
      "%d points, %.1f s) lie in the cells: %.3f\n",
      covered, reachable, radius, z_lo, z_hi, a.coverage, seconds,
      reachable ? static_cast<double>(covered) / reachable : 0.0);
  return 0;
}
