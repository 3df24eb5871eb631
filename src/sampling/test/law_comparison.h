// Comparing two samplers' laws on clutter (the Gibbs and partial-rejection tests): programs of
// cubes in a bin, a batch of scenes, and two-sample Kolmogorov-Smirnov tests on statistics
// of the objects that move.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "sampling/batch.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling::testing_law {

// Scenes a law comparison draws from each sampler. Under AddressSanitizer (the test command's
// second build, 25 times slower here) fewer: the sanitizer looks for memory errors along the
// same paths, and the statistical verdict at full size is the Release build's, whose tests run
// first.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int64_t kLawScenes = 400;
#else
inline constexpr int64_t kLawScenes = 3000;
#endif

// N objects (5 cm cubes) with any yaw completely on a bin (0.5 x 0.4 m).
inline std::string BinProgram(int n, const std::string& cls = "Cube",
                              const std::string& size = "0.5, with length 0.4") {
  return "from model import *\n"
         "bin = Table on V3D(0, 0, 0), with width " +
         size +
         "\n"
         "for i in range(" +
         std::to_string(n) +
         "):\n"
         "    " +
         cls + " completely on bin, with yaw Range(0, 2 * math.pi)\n";
}

inline std::vector<SampledScene> SampleAll(const lang::CompiledProgram& program,
                                           SampleOptions sample, uint64_t seed, int64_t count,
                                           int threads, uint64_t start = 0) {
  BatchOptions options;
  options.sample = std::move(sample);
  options.seed = seed;
  options.start = start;
  options.count = count;
  options.threads = threads;
  std::vector<SampledScene> scenes;
  SampleBatch(program, options,
              {.consume = [&](BatchScene&& s) { scenes.push_back(std::move(s.sampled)); }});
  return scenes;
}

// The objects that move from scene to scene, in the order they were made.
inline std::vector<const lang::SceneObject*> Cubes(const lang::Scene& scene) {
  std::vector<const lang::SceneObject*> cubes;
  for (const lang::SceneObject& o : scene.objects) {
    if (!o.fixed) cubes.push_back(&o);
  }
  return cubes;
}

inline double Yaw(const lang::SceneObject& o) {
  const Eigen::Vector3d forward = o.R_WO * Eigen::Vector3d::UnitY();
  return std::atan2(forward.y(), forward.x());
}

// Statistics of a scene the laws are compared on: the first and last cube's position and yaw,
// the first two cubes' distance, and the smallest distance between any two cubes.
inline std::map<std::string, std::vector<double>> Statistics(
    const std::vector<SampledScene>& scenes) {
  std::map<std::string, std::vector<double>> stats;
  for (const SampledScene& s : scenes) {
    const auto cubes = Cubes(s.scene);
    const lang::SceneObject& first = *cubes.front();
    const lang::SceneObject& last = *cubes.back();
    stats["first.x"].push_back(first.p_WO.x());
    stats["first.y"].push_back(first.p_WO.y());
    stats["last.x"].push_back(last.p_WO.x());
    stats["last.y"].push_back(last.p_WO.y());
    stats["first.yaw"].push_back(Yaw(first));
    stats["dist(first, second)"].push_back((first.p_WO - cubes[1]->p_WO).head<2>().norm());
    double nearest = INFINITY;
    for (size_t a = 0; a < cubes.size(); ++a) {
      for (size_t b = a + 1; b < cubes.size(); ++b) {
        nearest = std::min(nearest, (cubes[a]->p_WO - cubes[b]->p_WO).head<2>().norm());
      }
    }
    stats["nearest pair"].push_back(nearest);
  }
  return stats;
}

// The two-sample KS statistic's critical value at level 0.001 (Smirnov's asymptotic
// c(0.001) = 1.949), with the chain's scenes counted as `effective` independent ones.
inline double CriticalKs(double n_rejection, double effective) {
  return 1.949 * std::sqrt((n_rejection + effective) / (n_rejection * effective));
}

struct Comparison {
  std::string worst;  // the statistic with the largest D / critical
  double ratio = 0;   // its D / critical
};

inline Comparison Compare(const std::vector<SampledScene>& rejection,
                          const std::vector<SampledScene>& chain, double effective) {
  const auto a = Statistics(rejection), b = Statistics(chain);
  const double critical = CriticalKs(static_cast<double>(rejection.size()), effective);
  Comparison c;
  for (const auto& [name, values] : a) {
    const double ratio = testing_checks::KolmogorovSmirnov(values, b.at(name)) / critical;
    if (ratio > c.ratio) c = {name, ratio};
  }
  return c;
}

// A fixed robot base in the bin, turned, and the first two of six cubes at least 0.2 m apart.
inline constexpr const char* kObstacleAndRequirementProgram =
    "from model import *\n"
    "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
    "Robot at V3D(0.05, 0, 0.85), with yaw 0.3\n"
    "a = Cube completely on bin, with yaw Range(0, 2 * math.pi)\n"
    "b = Cube completely on bin, with yaw Range(0, 2 * math.pi)\n"
    "for i in range(4):\n"
    "    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n"
    "require (distance from a to b) > 0.2\n";

// In every scene of kObstacleAndRequirementProgram: the requirement holds and no cube meets the
// robot.
inline void ExpectRequirementAndObstacleHold(const std::vector<SampledScene>& scenes) {
  for (const SampledScene& s : scenes) {
    const auto cubes = Cubes(s.scene);
    ASSERT_GT((cubes[0]->p_WO - cubes[1]->p_WO).norm(), 0.2) << s.index;
    for (const lang::SceneObject* cube : cubes) {
      ASSERT_FALSE(
          testing_checks::BoxesOverlapByPoints(*cube, testing_checks::FindClass(s.scene, "Robot")))
          << s.index;
    }
  }
}

// Two-sample chi-square test of homogeneity on the cell of the first and of the last moving
// object in a 4 x 4 grid over the 0.5 x 0.4 m bin (positions outside it count in the edge
// cells): the larger statistic over its critical value at level 0.001 (15 degrees of freedom:
// 37.70). For samples of independent scenes.
inline double ChiSquareRatio(const std::vector<SampledScene>& a,
                             const std::vector<SampledScene>& b) {
  auto cell = [](const lang::SceneObject& o) {
    const int i = std::clamp(static_cast<int>(std::floor((o.p_WO.x() + 0.25) / 0.125)), 0, 3);
    const int j = std::clamp(static_cast<int>(std::floor((o.p_WO.y() + 0.2) / 0.1)), 0, 3);
    return 4 * i + j;
  };
  double worst = 0;
  for (const bool last : {false, true}) {
    std::vector<double> ca(16, 0), cb(16, 0);
    for (const SampledScene& s : a) {
      const auto moving = Cubes(s.scene);
      ++ca[cell(last ? *moving.back() : *moving.front())];
    }
    for (const SampledScene& s : b) {
      const auto moving = Cubes(s.scene);
      ++cb[cell(last ? *moving.back() : *moving.front())];
    }
    const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
    double chi2 = 0;
    for (int k = 0; k < 16; ++k) {
      if (ca[k] + cb[k] == 0) continue;
      const double d = ca[k] / na - cb[k] / nb;
      chi2 += na * nb * d * d / (ca[k] + cb[k]);
    }
    worst = std::max(worst, chi2 / 37.70);
  }
  return worst;
}

}  // namespace prs::sampling::testing_law
