// Shared helpers for the geometry tests: random rotations/boxes, chi-square thresholds, and
// an iteration scale (PRS_TEST_SCALE env var; sanitizer builds default to a smaller scale).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "geometry/box.h"
#include "geometry/random.h"
#include "geometry/rotation.h"

namespace prs::geometry::testing {

#ifndef PRS_TEST_DEFAULT_SCALE
#define PRS_TEST_DEFAULT_SCALE 1.0  // sanitizer builds compile in a smaller default
#endif

/// Scales an iteration count by PRS_TEST_SCALE if set, else by PRS_TEST_DEFAULT_SCALE
/// (1 in normal builds); at least 1 iteration.
inline int Scaled(int count) {
  const char* env = std::getenv("PRS_TEST_SCALE");
  double scale = env ? std::atof(env) : PRS_TEST_DEFAULT_SCALE;
  if (!(scale > 0)) scale = 1.0;
  return std::max(1, static_cast<int>(count * scale));
}

inline Eigen::Matrix3d RandomRotation(Rng& rng) {
  return CalcRotationFromYawPitchRoll(rng.Uniform(-std::numbers::pi, std::numbers::pi),
                                      rng.Uniform(-std::numbers::pi / 2, std::numbers::pi / 2),
                                      rng.Uniform(-std::numbers::pi, std::numbers::pi));
}

inline Eigen::Vector3d RandomVector(Rng& rng, double lo, double hi) {
  return {rng.Uniform(lo, hi), rng.Uniform(lo, hi), rng.Uniform(lo, hi)};
}

/// A uniform point of the box (not using the region code).
inline Eigen::Vector3d RandomPointInBox(const OrientedBox& box, Rng& rng) {
  const Eigen::Vector3d s = RandomVector(rng, -1, 1);
  return box.p_center + box.R_WB * s.cwiseProduct(box.half_extents);
}

/// How deep p lies inside the box (negative outside): min over faces of the distance.
inline double CalcDepthInBox(const OrientedBox& box, const Eigen::Vector3d& p) {
  const Eigen::Vector3d p_B = box.R_WB.transpose() * (p - box.p_center);
  return (box.half_extents - p_B.cwiseAbs()).minCoeff();
}

/// The 0.999 quantile of chi-square with df degrees of freedom (Wilson–Hilferty; within
/// about 1% for df >= 3).
inline double ChiSquareQuantile999(int df) {
  const double z = 3.090232306167813;  // 0.999 quantile of the standard normal
  const double a = 2.0 / (9.0 * df);
  return df * std::pow(1.0 - a + z * std::sqrt(a), 3);
}

/// Pearson's chi-square statistic and its degrees of freedom after pooling the bins whose
/// expected count is below 5 (the pool is folded into the largest bin if still below 5).
struct ChiSquareResult {
  double statistic = 0;
  int degrees_of_freedom = 0;
};
inline ChiSquareResult CalcChiSquare(const std::vector<double>& expected,
                                     const std::vector<double>& observed) {
  std::vector<double> e, o;
  double pool_e = 0, pool_o = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    if (expected[i] < 5) {
      pool_e += expected[i];
      pool_o += observed[i];
    } else {
      e.push_back(expected[i]);
      o.push_back(observed[i]);
    }
  }
  if (pool_e >= 5 || e.empty()) {
    e.push_back(pool_e);
    o.push_back(pool_o);
  } else {
    const size_t big = std::max_element(e.begin(), e.end()) - e.begin();
    e[big] += pool_e;
    o[big] += pool_o;
  }
  ChiSquareResult r;
  for (size_t i = 0; i < e.size(); ++i) {
    if (e[i] > 0) r.statistic += (o[i] - e[i]) * (o[i] - e[i]) / e[i];
  }
  r.degrees_of_freedom = static_cast<int>(e.size()) - 1;
  return r;
}

}  // namespace prs::geometry::testing
