// Camera-aware specifiers (spec §10): `in view of` and `completely in view of` draw positions
// exactly from the view frustum (every sample, and for `completely` every corner of its box,
// projects into the image, with no rejection); `not in view of` draws from the frustum's
// outside (a union of pieces, uniform across them); `visible from` rejects an attempt whose line
// of sight is blocked, naming the occluder, and accepts a clear one. Checked with projection
// arithmetic written here, not with the sampler's regions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using namespace testing_checks;

constexpr double kPi = std::numbers::pi;

const char* kPrologue = R"(
class Table:
    width: 1.8
    length: 0.8
    height: 0.8
class Cube:
    width: 0.05
    length: 0.05
    height: 0.05
class Camera:
    width: 0.05
    length: 0.05
    height: 0.05
    allowCollisions: True
    fovy_deg: 45
    aspect: 640 / 480
    near: 0.05
    far: 5
class Board:
    width: 0.3
    length: 0.3
    height: 0.02
t = Table at V3D(0, 0, 0.4)
)";

// Where a world point lands in a 640 × 480 image of a camera object (looking along its +y,
// its +z up, 45° vertical field of view): (column, row, depth). Written from the pinhole
// model directly, independent of the camera stage.
Vector3d ProjectToImage(const SceneObject& camera, const Vector3d& p_W) {
  const Matrix3d R = camera.R_WO.toRotationMatrix();
  const Vector3d d = R.transpose() * (p_W - camera.p_WO);  // x right, y forward, z up
  const double f = 240 / std::tan(22.5 * kPi / 180);
  return {320 + f * d.x() / d.y(), 240 - f * d.z() / d.y(), d.y()};
}

bool IsInImage(const Vector3d& pixel, double slack = 1e-6) {
  return pixel.z() > 0.05 - slack && pixel.z() < 5 + slack && pixel.x() > -slack &&
         pixel.x() < 640 + slack && pixel.y() > -slack && pixel.y() < 480 + slack;
}

// Whether the line from the camera at (0, 0, 2) to p passes under a 0.3 m × 0.3 m × 0.02 m
// shelf centred at (x, y, 1.4): where the line crosses the shelf's top or bottom plane, it is
// within the shelf's square grown by `grow` (similar triangles).
bool IsUnderShelf(const Vector3d& p, double shelf_x, double shelf_y, double grow = 0) {
  for (double z : {1.39, 1.41}) {
    const double t = (2 - z) / (2 - p.z());
    if (std::abs(t * p.x() - shelf_x) < 0.15 + grow && std::abs(t * p.y() - shelf_y) < 0.15 + grow) {
      return true;
    }
  }
  return false;
}

std::vector<SampledScene> SampleMany(const lang::CompiledProgram& program, int n, uint64_t seed = 1) {
  SceneSampler sampler(program);
  std::vector<SampledScene> scenes;
  for (int i = 0; i < n; ++i) scenes.push_back(sampler.Sample(seed, i));
  return scenes;
}

TEST(ViewsTest, CompletelyInViewPutsEveryCornerInTheImageWithoutRejection) {
  auto program = CompileOrDie(std::string(kPrologue) + R"(
cam = Camera at V3D((-0.4, 0.4), (-0.3, 0.3), (1.5, 2.1)), facing V3D(0, 0, -1), with yaw (-0.3, 0.3)
c = Cube on t, completely in view of cam
)");
  ASSERT_NE(program, nullptr);
  for (const SampledScene& s : SampleMany(*program, 1000)) {
    EXPECT_EQ(s.attempts, 1);
    const SceneObject& cam = Find(s.scene, "cam");
    const SceneObject& c = Find(s.scene, "c");
    for (const Vector3d& corner : Corners(c)) {
      ASSERT_TRUE(IsInImage(ProjectToImage(cam, corner))) << "scene " << s.index << " corner "
                                                           << ProjectToImage(cam, corner).transpose();
    }
  }
}

TEST(ViewsTest, InViewHoldsTheCentreOnlyAndIsUniform) {
  // A fixed camera 2 m up looking down: the cube's centre plane is z = 0.825, so the view there
  // is |x| <= 1.175 · tan(22.5°) · 4/3 (0.649 m) — inside the table's 0.9 m — and |y| covers the
  // whole 0.4 m of the table: x is uniform on [-0.649, 0.649].
  auto program = CompileOrDie(std::string(kPrologue) + R"(
cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)
c = Cube on t, in view of cam
)");
  ASSERT_NE(program, nullptr);
  const double half_x = 1.175 * std::tan(22.5 * kPi / 180) * 4 / 3;
  std::vector<double> xs, uniform;
  bool some_corner_out = false;
  geometry::Rng reference(99, 0);
  for (const SampledScene& s : SampleMany(*program, 2000)) {
    EXPECT_EQ(s.attempts, 1);
    const SceneObject& c = Find(s.scene, "c");
    ASSERT_TRUE(IsInImage(ProjectToImage(Find(s.scene, "cam"), c.p_WO)));
    for (const Vector3d& corner : Corners(c)) {
      some_corner_out = some_corner_out || !IsInImage(ProjectToImage(Find(s.scene, "cam"), corner));
    }
    xs.push_back(c.p_WO.x());
    uniform.push_back(reference.Uniform(-half_x, half_x));
  }
  EXPECT_TRUE(some_corner_out) << "'in view of' holds the centre, not the whole box";
  // Two-sample KS at n = m = 2000: 1.95 · sqrt(2 / 2000) is the 0.001 critical value.
  EXPECT_LT(KolmogorovSmirnov(xs, uniform), 1.95 * std::sqrt(2.0 / 2000));
}

TEST(ViewsTest, NotInViewDrawsUniformlyFromTheOutsidePieces) {
  // The table top outside the fixed camera's view: x in [-0.9, -0.649] or [0.649, 0.9].
  auto program = CompileOrDie(std::string(kPrologue) + R"(
cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)
c = Cube on t, not in view of cam
)");
  ASSERT_NE(program, nullptr);
  const double half_x = 1.175 * std::tan(22.5 * kPi / 180) * 4 / 3;
  std::vector<double> xs, reference_xs;
  geometry::Rng reference(98, 0);
  for (const SampledScene& s : SampleMany(*program, 2000)) {
    EXPECT_EQ(s.attempts, 1);
    const SceneObject& c = Find(s.scene, "c");
    ASSERT_FALSE(IsInImage(ProjectToImage(Find(s.scene, "cam"), c.p_WO), -1e-6));
    xs.push_back(c.p_WO.x());
    const double u = reference.Uniform(0, 2 * (0.9 - half_x));
    reference_xs.push_back(u < 0.9 - half_x ? -0.9 + u : half_x + (u - (0.9 - half_x)));
  }
  EXPECT_LT(KolmogorovSmirnov(xs, reference_xs), 1.95 * std::sqrt(2.0 / 2000));
}

TEST(ViewsTest, AnOccludedObjectIsRejectedNamingTheOccluderAndAClearOneAccepted) {
  const std::string scene = std::string(kPrologue) + R"(
cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)
shelf = Board at V3D(SHELF_X, 0, 1.4)
c = Cube at V3D(0, 0, 0.825), visible from cam
)";
  auto with_shelf_at = [&](const std::string& x) {
    std::string text = scene;
    text.replace(text.find("SHELF_X"), 7, x);
    return text;
  };
  auto blocked = CompileOrDie(with_shelf_at("0"));
  ASSERT_NE(blocked, nullptr);
  try {
    SampleScene(*blocked, 1, 0);
    FAIL() << "a cube under the shelf is hidden from the camera";
  } catch (const lang::ScenarioError& e) {
    EXPECT_NE(e.diagnostic().message.find("occluded"), std::string::npos) << e.diagnostic().message;
    EXPECT_NE(e.diagnostic().message.find("shelf"), std::string::npos) << e.diagnostic().message;
  }
  auto clear = CompileOrDie(with_shelf_at("0.5"));
  ASSERT_NE(clear, nullptr);
  EXPECT_EQ(SampleScene(*clear, 1, 0).attempts, 1);
}

TEST(ViewsTest, VisibleFromRejectsExactlyTheScenesWhoseLineOfSightIsBlocked) {
  // A random shelf between a fixed camera and the table: accepted cubes are those whose
  // centre the shelf does not hide (checked by similar triangles at the shelf's height).
  auto program = CompileOrDie(std::string(kPrologue) + R"(
cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)
shelf = Board at V3D((-0.3, 0.3), (-0.2, 0.2), 1.4)
c = Cube on t, visible from cam
)");
  ASSERT_NE(program, nullptr);
  int64_t occluded = 0;
  for (const SampledScene& s : SampleMany(*program, 500)) {
    const SceneObject& shelf = Find(s.scene, "shelf");
    const SceneObject& c = Find(s.scene, "c");
    ASSERT_FALSE(IsUnderShelf(c.p_WO, shelf.p_WO.x(), shelf.p_WO.y(), -1e-6))
        << "scene " << s.index << ": the shelf hides the cube's centre";
    for (const auto& [key, n] : s.rejections.by_culprit) {
      if (key.first != lang::RejectionKind::kOccluded) continue;
      EXPECT_EQ(key.second, "c hidden from cam by shelf");
      occluded += n;
    }
  }
  EXPECT_GT(occluded, 10) << "some attempts must have been hidden";
}

TEST(ViewsTest, CompletelyVisibleNeedsEveryFacingPointClear) {
  // The shelf's edge at x = 0.15 (seen from the camera, at the table x = 0.15 · 1.175 / 0.6):
  // a cube straddling that line has its centre clear but part of its top hidden.
  const double edge = 0.15 * 1.175 / 0.6;
  const std::string prologue = std::string(kPrologue) + R"(
cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)
shelf = Board at V3D(0, 0, 1.4)
)";
  const std::string at = "V3D(" + std::to_string(edge + 0.02) + ", 0, 0.825)";
  auto partly = CompileOrDie(prologue + "c = Cube at " + at + ", visible from cam\n");
  ASSERT_NE(partly, nullptr);
  EXPECT_EQ(SampleScene(*partly, 1, 0).attempts, 1);
  auto wholly = CompileOrDie(prologue + "c = Cube at " + at + ", completely visible from cam\n");
  ASSERT_NE(wholly, nullptr);
  EXPECT_THROW(SampleScene(*wholly, 1, 0), lang::ScenarioError);
  auto on_table = CompileOrDie(prologue + "c = Cube on t, completely visible from cam\n");
  ASSERT_NE(on_table, nullptr);
  for (const SampledScene& s : SampleMany(*on_table, 300)) {
    const SceneObject& c = Find(s.scene, "c");
    // No corner of the top face is in the shelf's shadow (less 1 mm for the sight targets'
    // 2 % inset).
    for (const Vector3d& corner : Corners(c)) {
      if (corner.z() < c.p_WO.z()) continue;
      EXPECT_FALSE(IsUnderShelf(corner, 0, 0, -1e-3)) << "scene " << s.index;
    }
  }
}

TEST(ViewsTest, NotVisibleFromKeepsOnlyHiddenOrOutOfViewCentres) {
  auto program = CompileOrDie(std::string(kPrologue) + R"(
cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)
shelf = Board at V3D(0, 0, 1.4)
c = Cube on t, not visible from cam
)");
  ASSERT_NE(program, nullptr);
  int hidden = 0, out_of_view = 0;
  for (const SampledScene& s : SampleMany(*program, 400)) {
    const SceneObject& c = Find(s.scene, "c");
    const bool seen = IsInImage(ProjectToImage(Find(s.scene, "cam"), c.p_WO));
    const bool under = IsUnderShelf(c.p_WO, 0, 0, 1e-6);
    ASSERT_TRUE(!seen || under) << "scene " << s.index;
    hidden += seen && under;
    out_of_view += !seen;
  }
  EXPECT_GT(hidden, 0);
  EXPECT_GT(out_of_view, 0);
}

TEST(ViewsTest, ImpossibleCameraIntrinsicsAreLocatedErrors) {
  for (const char* bad : {"fovy_deg 180", "fovy_deg 0", "aspect 0", "near 0", "far 0.01"}) {
    auto program = CompileOrDie(std::string(kPrologue) + "cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1), with " +
                                bad + "\nc = Cube on t, in view of cam\n");
    ASSERT_NE(program, nullptr);
    try {
      SampleScene(*program, 1, 0);
      FAIL() << bad;
    } catch (const lang::ScenarioError& e) {
      EXPECT_EQ(e.diagnostic().id, "bad-camera") << bad;
      EXPECT_NE(e.diagnostic().message.find("camera cam"), std::string::npos) << e.diagnostic().message;
    }
  }
}

}  // namespace
}  // namespace prs::sampling
