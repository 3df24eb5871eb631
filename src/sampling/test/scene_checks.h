// Checks shared by the scenario tests: compile helpers, finding objects in a scene,
// relations (completely on, beyond a plane, box overlap) computed with plain arithmetic,
// independent of the sampler's regions, and a two-sample test.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "sampling/sampler.h"

namespace prs::sampling::testing_checks {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using lang::Scene;
using lang::SceneObject;

constexpr double kTol = 1e-7;

inline std::string RepoPath(const std::string& relative) {
  const char* root = std::getenv("PRS_SOURCE_DIR");
  return std::string(root ? root : ".") + "/" + relative;
}

inline std::unique_ptr<lang::CompiledProgram> CompileOrDie(const std::string& text,
                                                    const std::string& path = "examples/test.prs") {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  auto program = lang::CompileText(RepoPath(path), text, options, diagnostics);
  std::string rendered;
  for (const auto& d : diagnostics.diagnostics()) rendered += d.message + "\n";
  EXPECT_FALSE(diagnostics.has_errors()) << rendered;
  if (diagnostics.has_errors()) return nullptr;
  return program;
}

// examples/NAME compiled as `prs` would, with examples/ on the search path.
inline std::unique_ptr<lang::CompiledProgram> CompileExample(const std::string& name) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.search_path = {RepoPath("examples")};
  auto program = lang::CompileFile(RepoPath("examples/" + name), options, diagnostics);
  EXPECT_FALSE(diagnostics.has_errors()) << name;
  return program;
}

inline const SceneObject& Find(const Scene& scene, const std::string& name) {
  for (const SceneObject& o : scene.objects) {
    if (o.name && *o.name == name) return o;
  }
  ADD_FAILURE() << "no object named " << name;
  static const SceneObject kNone;
  return kNone;
}

inline const SceneObject& FindClass(const Scene& scene, const std::string& cls) {
  for (const SceneObject& o : scene.objects) {
    if (o.cls->name == cls) return o;
  }
  ADD_FAILURE() << "no object of class " << cls;
  static const SceneObject kNone;
  return kNone;
}

// The corners of an object's box, in the world frame.
inline std::vector<Vector3d> Corners(const SceneObject& o) {
  std::vector<Vector3d> corners;
  const Matrix3d R = o.R_WO.toRotationMatrix();
  for (int i = 0; i < 8; ++i) {
    const Vector3d s((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    corners.push_back(o.p_WO + R * s.cwiseProduct(o.dimensions / 2));
  }
  return corners;
}

// `o completely on x`: every corner's footprint lies within x's top rectangle, and o's centre
// sits half its height above x's top face (for axis-aligned, upright objects and surfaces).
inline void ExpectCompletelyOn(const SceneObject& o, const SceneObject& x) {
  const Matrix3d R_X = x.R_WO.toRotationMatrix();
  for (const Vector3d& corner : Corners(o)) {
    const Vector3d local = R_X.transpose() * (corner - x.p_WO);
    EXPECT_LE(std::abs(local.x()), x.dimensions.x() / 2 + kTol);
    EXPECT_LE(std::abs(local.y()), x.dimensions.y() / 2 + kTol);
  }
  const double top = (R_X.transpose() * (o.p_WO - x.p_WO)).z();
  EXPECT_NEAR(top, x.dimensions.z() / 2 + o.dimensions.z() / 2, kTol);
}

// Every corner of o lies at least `d` beyond the plane through p with normal n.
inline void ExpectBeyond(const SceneObject& o, const Vector3d& p, const Vector3d& n, double d = 0) {
  for (const Vector3d& corner : Corners(o)) EXPECT_GE(n.dot(corner - p), d - kTol);
}


// Independent of the separating-axis test: does a point of a's box lie deep inside b's box?
inline bool BoxesOverlapByPoints(const SceneObject& a, const SceneObject& b) {
  const Matrix3d R_a = a.R_WO.toRotationMatrix(), R_b = b.R_WO.toRotationMatrix();
  const int n = 6;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      for (int k = 0; k <= n; ++k) {
        const Vector3d s(2.0 * i / n - 1, 2.0 * j / n - 1, 2.0 * k / n - 1);
        const Vector3d p = a.p_WO + R_a * s.cwiseProduct(a.dimensions / 2);
        const Vector3d local = R_b.transpose() * (p - b.p_WO);
        if ((local.cwiseAbs() - b.dimensions / 2).maxCoeff() < -1e-4) return true;
      }
    }
  }
  return false;
}

// Every number of a scene, exactly (hex floats), so equal fingerprints mean equal scenes.
inline std::string Fingerprint(const SampledScene& sampled) {
  std::string text = std::to_string(sampled.index) + " " + std::to_string(sampled.attempts);
  char buffer[64];
  for (const lang::SceneObject& o : sampled.scene.objects) {
    text += " " + o.cls->name + ":" + o.name.value_or("-");
    const double numbers[] = {o.p_WO.x(),       o.p_WO.y(),      o.p_WO.z(), o.R_WO.w(),
                              o.R_WO.x(),       o.R_WO.y(),      o.R_WO.z(), o.dimensions.x(),
                              o.dimensions.y(), o.dimensions.z()};
    for (double x : numbers) {
      std::snprintf(buffer, sizeof buffer, " %a", x);
      text += buffer;
    }
  }
  for (const auto& [key, n] : sampled.rejections.by_culprit) {
    text += ' ';
    text += lang::RejectionKindName(key.first);
    text += '/';
    text += key.second;
    text += '=';
    text += std::to_string(n);
  }
  return text;
}

// The two-sample Kolmogorov-Smirnov statistic: the largest gap between the empirical
// distribution functions of a and b.
inline double KolmogorovSmirnov(std::vector<double> a, std::vector<double> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  size_t i = 0, j = 0;
  double d = 0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    d = std::max(d, std::abs(double(i) / a.size() - double(j) / b.size()));
  }
  return d;
}

}  // namespace prs::sampling::testing_checks
