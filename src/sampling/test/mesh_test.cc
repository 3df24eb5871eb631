// Mesh shapes (spec §10) on examples/kitchen_meshes.prs: every vertex of every mesh lies on
// the tabletop (checked on the whole mesh, not the hull the sampler erodes by); no two meshes
// overlap by an independent FCL test; and mesh placement accepts scenes whose bounding boxes
// overlap (which box shapes would reject). Sizes come from the mesh, scaled.
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
  for (int i = 0; i < 1000; ++i) {
    const SampledScene s = sampler.Sample(3, i);
    const SceneObject& table = Find(s.scene, "t");
    const double top = table.p_WO.z() + table.dimensions.z() / 2;
    std::vector<const SceneObject*> meshes;
    for (const SceneObject& o : s.scene.objects) {
      if (!o.mesh) continue;
      meshes.push_back(&o);
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
    ASSERT_EQ(meshes.size(), 3u);
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
