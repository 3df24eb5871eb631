// Failure sets of exact probability for testing `prs estimate` on shapes its design was not
// chosen on (issue 43): a program of two points uniform in the unit cube (six scene
// coordinates, every scene accepted), and controllers that fail on two disjoint disks of
// unequal mass, a thin band along a diagonal, a thin ring, and a corner of the 6-cube that
// depends on all six coordinates at once. Each reports a score (larger is safer, <= 0 inside),
// as a robustness-aware controller would. Shared by the tests and bench/estimate_coverage.cc.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/harness.h"
#include "lang/lang.h"

namespace prs::search::testing_shapes {

/// Two 1 cm points, each at a position uniform in [0, 1)^3, overlapping freely: the six scene
/// coordinates are the two positions, and the program's law is uniform on the 6-cube.
inline constexpr char kTwoPointsProgram[] =
    "a = Object at V3D(Range(0, 1), Range(0, 1), Range(0, 1)), with width 0.01, with length "
    "0.01, with height 0.01, with allowCollisions True\n"
    "b = Object at V3D(Range(0, 1), Range(0, 1), Range(0, 1)), with width 0.01, with length "
    "0.01, with height 0.01, with allowCollisions True\n";

/// A failure set over the six coordinates (a's x, y, z, then b's), with its exact probability.
struct FailureShape {
  std::string name;
  double truth = 0;
  /// Signed: <= 0 inside the failure set, else how far (in the set's own measure) outside.
  double (*score)(const double* u) = nullptr;
};

/// Two disks in (a.x, a.y): one of area 0.25 % around (0.25, 0.7), one of 0.125 % around
/// (0.7, 0.3); 0.375 % in all, as in the issue.
inline double ScoreTwoDisks(const double* u) {
  const double r_big = std::sqrt(0.0025 / M_PI), r_small = std::sqrt(0.00125 / M_PI);
  const double d_big = std::hypot(u[0] - 0.25, u[1] - 0.7) - r_big;
  const double d_small = std::hypot(u[0] - 0.7, u[1] - 0.3) - r_small;
  return std::min(d_big, d_small);
}

/// |a.x - a.y| < w with 2 w - w^2 = 0.1 %: a band of half-width 0.0005 along the diagonal.
inline double ScoreDiagonalBand(const double* u) {
  const double w = 1 - std::sqrt(1 - 0.001);
  return std::abs(u[0] - u[1]) - w;
}

/// A ring of radius 0.3 around (0.5, 0.5) in (a.x, a.y), of half-width h with 4 pi 0.3 h = 0.1 %.
inline double ScoreThinRing(const double* u) {
  const double h = 0.001 / (4 * M_PI * 0.3);
  return std::abs(std::hypot(u[0] - 0.5, u[1] - 0.5) - 0.3) - h;
}

/// The sum of all six coordinates above t, where P(sum > t) = (6 - t)^6 / 6! = 0.1 %.
inline double ScoreSixCoordinates(const double* u) {
  const double t = 6 - std::pow(0.001 * 720, 1.0 / 6);
  double sum = 0;
  for (int j = 0; j < 6; ++j) sum += u[j];
  return t - sum;
}

/// The four shapes, with their exact probabilities.
inline std::vector<FailureShape> ListFailureShapes() {
  return {{"two-disks", 0.00375, ScoreTwoDisks},
          {"diagonal-band", 0.001, ScoreDiagonalBand},
          {"thin-ring", 0.001, ScoreThinRing},
          {"six-coordinates", 0.001, ScoreSixCoordinates}};
}

/// Fails with outcome `shape.name` when the scene's two points are in the shape's set.
class ShapeController : public harness::Controller {
 public:
  explicit ShapeController(FailureShape shape) : shape_(std::move(shape)) {}
  harness::EpisodeResult RunEpisode(const sampling::SampledScene& s, const std::string&) override {
    const Eigen::Vector3d &a = s.scene.objects.at(0).p_WO, &b = s.scene.objects.at(1).p_WO;
    const double u[6] = {a.x(), a.y(), a.z(), b.x(), b.y(), b.z()};
    harness::EpisodeResult result{"success", ""};
    result.score = shape_.score(u);
    if (*result.score <= 0) result.outcome = shape_.name;
    return result;
  }

 private:
  FailureShape shape_;
};

inline harness::ControllerFactory MakeShapeControllerFactory(const FailureShape& shape) {
  return [shape] { return std::make_unique<ShapeController>(shape); };
}

/// kTwoPointsProgram compiled; throws std::runtime_error if it does not compile.
inline std::unique_ptr<lang::CompiledProgram> CompileTwoPoints() {
  lang::DiagnosticEngine diagnostics;
  auto program =
      lang::CompileText("two_points.prs", kTwoPointsProgram, lang::CompileOptions{}, diagnostics);
  if (!program || diagnostics.has_errors()) {
    throw std::runtime_error("the two-points program does not compile");
  }
  return program;
}

}  // namespace prs::search::testing_shapes
