// Mesh shapes (spec §10) on examples/kitchen_meshes.prs: every vertex of every mesh on the
// table lies on the tabletop (checked on the whole mesh, not the hull the sampler erodes by),
// and the mug on the shelf stands on one of its boards, wholly on it, on both boards as often;
// no two meshes overlap by an independent FCL test; and mesh placement accepts scenes whose
// bounding boxes overlap (which box shapes would reject). Sizes come from the mesh, scaled. A
// mesh whose orientation depends on its position is placed wholly on the table.
#include <gtest/gtest.h>

#include <map>

#include "geometry/box.h"
#include "shapes/collide.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using namespace testing_checks;

Eigen::Isometry3d PoseOf(const SceneObject& o) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = o.R_WO.toRotationMatrix();
  X.translation() = o.p_WO;
  return X;
}

TEST(MeshSceneTest, MeshesLieOnTheTableAndNeverOverlap) {
  auto program = CompileExample("kitchen_meshes.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int boxes_overlap = 0;
  std::map<const shapes::MeshShape*, std::shared_ptr<const shapes::Collider>> colliders;
  auto collider = [&](const SceneObject& o) {
    auto& c = colliders[o.mesh.get()];  // ten times finer than the sampler's touching allowance
    if (!c) c = shapes::Collider::MakeMesh(*o.mesh, o.mesh_scale, 1e-7);
    return c;
  };
  int on_board[2] = {0, 0};
  for (int i = 0; i < 1000; ++i) {
    const SampledScene s = sampler.Sample(3, i);
    const SceneObject& table = Find(s.scene, "t");
    const double top = table.p_WO.z() + table.dimensions.z() / 2;
    std::vector<const SceneObject*> meshes;
    for (const SceneObject& o : s.scene.objects) {
      if (!o.mesh) continue;
      meshes.push_back(&o);
      if (*o.name == "spare") continue;  // on the shelf: below
      const Eigen::Isometry3d X = PoseOf(o);
      double lowest = INFINITY;
      for (const Vector3d& p_O : o.mesh->mesh.vertices_O) {
        const Vector3d p = X * (p_O * o.mesh_scale);
        ASSERT_LE(std::abs(p.x()), 0.9 + kTol) << "scene " << i << " " << *o.name;
        ASSERT_LE(std::abs(p.y()), 0.4 + kTol) << "scene " << i << " " << *o.name;
        lowest = std::min(lowest, p.z());
      }
      EXPECT_NEAR(lowest, top, 1e-9) << "scene " << i << " " << *o.name;  // standing on it
    }
    ASSERT_EQ(meshes.size(), 4u);
    // The spare mug: wholly over a board of the shelf (0.56 x 0.3 m, tops 0.12 and 0.37 m
    // above the shelf's bottom), its lowest point on that board's top.
    const SceneObject& shelf = Find(s.scene, "shelf");
    const SceneObject& spare = Find(s.scene, "spare");
    const Eigen::Isometry3d X_SW = PoseOf(shelf).inverse();
    double lowest = INFINITY;
    for (const Vector3d& p_O : spare.mesh->mesh.vertices_O) {
      const Vector3d p_S = X_SW * (PoseOf(spare) * (p_O * spare.mesh_scale));
      ASSERT_LE(std::abs(p_S.x()), 0.28 + kTol) << "scene " << i;
      ASSERT_LE(std::abs(p_S.y()), 0.15 + kTol) << "scene " << i;
      lowest = std::min(lowest, p_S.z() + 0.25);  // above the shelf's bottom
    }
    const bool lower = std::abs(lowest - 0.12) < 1e-9, upper = std::abs(lowest - 0.37) < 1e-9;
    ASSERT_TRUE(lower || upper) << "scene " << i << ": the mug's bottom is " << lowest;
    ++on_board[upper];
    for (size_t a = 0; a < meshes.size(); ++a) {
      for (size_t b = a + 1; b < meshes.size(); ++b) {
        const SceneObject& A = *meshes[a];
        const SceneObject& B = *meshes[b];
        EXPECT_FALSE(shapes::DoCollidersOverlap(*collider(A), PoseOf(A), *collider(B), PoseOf(B)))
            << "scene " << i << ": " << *A.name << " and " << *B.name;
        boxes_overlap += BoxesOverlapByPoints(A, B);
      }
    }
  }
  // The bowl under the shelf's lower board, the mug's handle over the bowl: kept, not rejected.
  EXPECT_GT(boxes_overlap, 50);
  // Both boards have the same area: each holds the mug about half the time (n = 1000, the
  // binomial's standard deviation is 16; 6 of them either side).
  EXPECT_NEAR(on_board[0], 500, 95) << on_board[1];
}

// A mug whose orientation depends on its position ('facing toward') `completely on` the table:
// its position is drawn from the top eroded by the round core of its hull (a superset for every
// turn), then checked exactly once it has turned. Every vertex ends on the tabletop, the mug
// faces the point, and the superset is tight enough that few scenes are rejected.
TEST(MeshSceneTest, AMugFacingTowardAPointStaysWhollyOnTheTable) {
  auto program = CompileOrDie(R"(
from model import *
class Mug:
    shape: Mesh("assets/mug.obj")
t = Table on V3D(0, 0, 0)
m = Mug completely on t, facing toward V3D(0.3, 2, 1)
)");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int attempts = 0;
  double min_yaw = INFINITY, max_yaw = -INFINITY;
  for (int i = 0; i < 500; ++i) {
    const SampledScene s = sampler.Sample(5, i);
    attempts += s.attempts;
    const SceneObject& table = Find(s.scene, "t");
    const SceneObject& mug = Find(s.scene, "m");
    const double top = table.p_WO.z() + table.dimensions.z() / 2;
    const Eigen::Isometry3d X = PoseOf(mug);
    double lowest = INFINITY;
    for (const Vector3d& p_O : mug.mesh->mesh.vertices_O) {
      const Vector3d p = X * p_O;
      ASSERT_LE(std::abs(p.x()), 0.9 + kTol) << "scene " << i;
      ASSERT_LE(std::abs(p.y()), 0.4 + kTol) << "scene " << i;
      lowest = std::min(lowest, p.z());
    }
    EXPECT_NEAR(lowest, top, 1e-9) << "scene " << i;
    // Its forward axis points at the target, seen from above.
    const Vector3d forward = X.linear().col(1);
    const Vector3d to_target = Vector3d(0.3, 2, 1) - mug.p_WO;
    EXPECT_GT(forward.head<2>().normalized().dot(to_target.head<2>().normalized()), 1 - 1e-9);
    const double yaw = std::atan2(forward.y(), forward.x());
    min_yaw = std::min(min_yaw, yaw);
    max_yaw = std::max(max_yaw, yaw);
  }
  EXPECT_GT(max_yaw - min_yaw, 0.5);  // the turn really depends on the position
  EXPECT_LT(attempts, 2 * 500);       // the round core is not a loose superset
}

TEST(MeshSceneTest, SizeComesFromTheScaledMesh) {
  auto program = CompileOrDie(R"(
from model import *
class Mug:
    shape: Mesh("assets/mug.obj", scale=2)
m = Mug on floor
n = Mug on floor, with shape Mesh("assets/bowl.obj"), with width 0.16
)");
  ASSERT_NE(program, nullptr);
  const SampledScene s = SceneSampler(*program).Sample(1, 0);
  EXPECT_TRUE(Find(s.scene, "m").dimensions.isApprox(Vector3d(0.22, 0.16, 0.2), 1e-12))
      << Find(s.scene, "m").dimensions.transpose();
  EXPECT_TRUE(Find(s.scene, "n").dimensions.isApprox(Vector3d(0.16, 0.16, 0.06), 1e-12))
      << Find(s.scene, "n").dimensions.transpose();
  EXPECT_NEAR(Find(s.scene, "m").p_WO.z(), 0.1, 1e-12);
}

TEST(MeshSceneTest, UnitsThatLookWrongAreWarnedAbout) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.search_path = {RepoPath("examples")};
  auto program = lang::CompileText(RepoPath("examples/test.prs"),
                                   "from model import *\n"
                                   "class Mug:\n"
                                   "    shape: Mesh(\"assets/mug.obj\", scale=1000)\n"
                                   "m = Mug on floor\n",
                                   options, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  ASSERT_EQ(diagnostics.diagnostics().size(), 1u);
  EXPECT_EQ(diagnostics.diagnostics()[0].id, "mesh-warning");
  EXPECT_NE(diagnostics.diagnostics()[0].message.find("scale=0.001"), std::string::npos)
      << diagnostics.diagnostics()[0].message;
}

}  // namespace
}  // namespace prs::sampling
