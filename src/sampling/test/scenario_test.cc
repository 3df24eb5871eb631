// End-to-end scenario tests: programs compile, sample, and every relation they state holds on
// the sampled values, checked here with plain arithmetic independent of the sampler's regions.
#include <gtest/gtest.h>

#include <cstdlib>

#include "sampling/sampler.h"

namespace prs::sampling {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using lang::Scene;
using lang::SceneObject;

constexpr double kTol = 1e-7;

std::string RepoPath(const std::string& relative) {
  const char* root = std::getenv("PRS_SOURCE_DIR");
  return std::string(root ? root : ".") + "/" + relative;
}

std::unique_ptr<lang::CompiledProgram> CompileOrDie(const std::string& text,
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

const SceneObject& Find(const Scene& scene, const std::string& name) {
  for (const SceneObject& o : scene.objects) {
    if (o.name && *o.name == name) return o;
  }
  ADD_FAILURE() << "no object named " << name;
  static const SceneObject kNone;
  return kNone;
}

const SceneObject& FindClass(const Scene& scene, const std::string& cls) {
  for (const SceneObject& o : scene.objects) {
    if (o.cls->name == cls) return o;
  }
  ADD_FAILURE() << "no object of class " << cls;
  static const SceneObject kNone;
  return kNone;
}

// The corners of an object's box, in the world frame.
std::vector<Vector3d> Corners(const SceneObject& o) {
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
void ExpectCompletelyOn(const SceneObject& o, const SceneObject& x) {
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
void ExpectBeyond(const SceneObject& o, const Vector3d& p, const Vector3d& n, double d = 0) {
  for (const Vector3d& corner : Corners(o)) EXPECT_GE(n.dot(corner - p), d - kTol);
}

bool BoxesOverlapByPoints(const SceneObject& a, const SceneObject& b);

TEST(ScenarioTest, PaperFigureOneHoldsInEveryScene) {
  auto program = CompileOrDie(R"(from model import *

t = Table on V3D(0,0,0)
r1 = Robot on (top back t) - V3D(0.4, 0, 0)
r2 = Robot on (top back t) + V3D(0.4, 0, 0)

tr_1 = Tray completely on t, 
            ahead of r1,
            left of t
            
tr_2 = Tray completely on t,
            ahead of r2,
            right of t

Cube completely on tr_1

Camera at V3D((-0.1, 0.1),
              (-0.1, 0.1), 
              (1.9, 2.1)),
       facing V3D(0, 0, -1)
)");
  ASSERT_NE(program, nullptr);
  for (uint64_t i = 0; i < 200; ++i) {
    const Scene scene = SampleScene(*program, 1, i).scene;
    ASSERT_EQ(scene.objects.size(), 7u);
    const SceneObject& t = Find(scene, "t");
    const SceneObject& r1 = Find(scene, "r1");
    const SceneObject& tr_1 = Find(scene, "tr_1");
    const SceneObject& tr_2 = Find(scene, "tr_2");
    EXPECT_NEAR(t.p_WO.z(), t.dimensions.z() / 2, kTol);  // on V3D(0,0,0)
    EXPECT_NEAR(r1.p_WO.x(), -0.4, kTol);
    EXPECT_NEAR(r1.p_WO.y(), -t.dimensions.y() / 2, kTol);
    EXPECT_NEAR(r1.p_WO.z(), t.dimensions.z() + r1.dimensions.z() / 2, kTol);
    ExpectCompletelyOn(tr_1, t);
    ExpectCompletelyOn(tr_2, t);
    ExpectBeyond(tr_1, r1.p_WO, Vector3d::UnitY());   // ahead of r1
    ExpectBeyond(tr_1, t.p_WO, -Vector3d::UnitX());   // left of t
    ExpectBeyond(tr_2, t.p_WO, Vector3d::UnitX());    // right of t
    const SceneObject& cube = FindClass(scene, "Cube");
    EXPECT_FALSE(cube.name.has_value());
    ExpectCompletelyOn(cube, tr_1);
    const SceneObject& camera = FindClass(scene, "Camera");
    EXPECT_LE(std::abs(camera.p_WO.x()), 0.1 + kTol);
    EXPECT_LE(std::abs(camera.p_WO.y()), 0.1 + kTol);
    EXPECT_GE(camera.p_WO.z(), 1.9 - kTol);
    EXPECT_LE(camera.p_WO.z(), 2.1 + kTol);
    EXPECT_TRUE((camera.R_WO * Vector3d::UnitY()).isApprox(-Vector3d::UnitZ(), 1e-9));
    for (size_t a = 0; a < scene.objects.size(); ++a) {
      for (size_t b = a + 1; b < scene.objects.size(); ++b) {
        if (scene.objects[a].allow_collisions || scene.objects[b].allow_collisions) continue;
        EXPECT_FALSE(BoxesOverlapByPoints(scene.objects[a], scene.objects[b])) << a << " " << b;
      }
    }
  }
}

// Independent of the separating-axis test: does a point of a's box lie deep inside b's box?
bool BoxesOverlapByPoints(const SceneObject& a, const SceneObject& b) {
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

TEST(ScenarioTest, RotatedTrayCompletelyOnTableNeverOverhangs) {
  auto program = CompileOrDie(R"(from model import *
table = Table on floor
tray = Tray completely on table, facing V3D(1, 1, 0)
)");
  ASSERT_NE(program, nullptr);
  for (uint64_t i = 0; i < 1000; ++i) {
    const Scene scene = SampleScene(*program, 7, i).scene;
    const SceneObject& tray = Find(scene, "tray");
    const SceneObject& table = Find(scene, "table");
    EXPECT_TRUE((tray.R_WO * Vector3d::UnitY()).isApprox(Vector3d(1, 1, 0).normalized(), 1e-9));
    ExpectCompletelyOn(tray, table);
  }
}

TEST(ScenarioTest, SameSeedAndIndexGiveTheSameScene) {
  auto program = CompileOrDie("from model import *\n"
                              "t = Table on floor\nc = Cube completely on t\n"
                              "x = Normal(0, 1)\nparam p = x\n");
  ASSERT_NE(program, nullptr);
  const Scene a = SampleScene(*program, 5, 17).scene;
  const Scene b = SampleScene(*program, 5, 17).scene;
  const Scene c = SampleScene(*program, 5, 18).scene;
  EXPECT_EQ(Find(a, "c").p_WO, Find(b, "c").p_WO);
  EXPECT_NE(Find(a, "c").p_WO, Find(c, "c").p_WO);
  EXPECT_EQ(a.params[0].second.As<double>(), b.params[0].second.As<double>());
}

TEST(ScenarioTest, ConstructsExampleRuns) {
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileFile(RepoPath("examples/constructs.prs"), {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors()) << (diagnostics.diagnostics().empty()
                                       ? ""
                                       : diagnostics.diagnostics()[0].message);
  for (uint64_t i = 0; i < 50; ++i) {
    const Scene scene = SampleScene(*program, 3, i).scene;
    const SceneObject& cup_1 = Find(scene, "cup_1");
    const SceneObject& cup_2 = Find(scene, "cup_2");
    const SceneObject& table = Find(scene, "table");
    ExpectCompletelyOn(cup_1, table);
    EXPECT_NEAR(cup_1.p_WO.y(), cup_2.p_WO.y(), kTol);  // aligned with cup_1 by "y"
    ExpectBeyond(cup_1, table.p_WO, -Vector3d::UnitX(), 0.2);  // left of table by 0.2
    const SceneObject& c1 = Find(scene, "c1");
    const SceneObject& c2 = Find(scene, "c2");
    EXPECT_NEAR(c1.dimensions.x(), 0.3, 0);
    ExpectBeyond(c1, Vector3d(0, 0, 2.5), -Vector3d::UnitZ());  // below V
    ExpectBeyond(c2, c1.p_WO, Vector3d::UnitX(), 0.2);           // right of c1 by 0.2
    ExpectBeyond(c2, c1.p_WO, Vector3d::UnitZ(), 0.2);           // above c1 by 0.2
    ExpectBeyond(c2, c1.p_WO, Vector3d::UnitY(), 0.1);           // ahead of c1 by 0.1
    const SceneObject& cube_2 = Find(scene, "cube_2");
    EXPECT_NEAR(cube_2.p_WO.z(), c2.p_WO.z() + 0.05, kTol);      // a stack: cube_2 on c2
    const SceneObject& plate = Find(scene, "plate");
    EXPECT_NEAR(plate.p_WO.y(), table.p_WO.y() - 0.75, kTol);
    EXPECT_LT(cup_1.p_WO.x() + 0.04 + 0.01, cup_2.p_WO.x());    // the require holds
    const SceneObject& chair = Find(scene, "chair");
    EXPECT_TRUE((chair.R_WO * Vector3d::UnitY()).isApprox(Vector3d::UnitX(), 1e-9));
    int gears = 0;
    for (const SceneObject& o : scene.objects) gears += o.cls->name == "Gear";
    EXPECT_GE(gears, 1);
    EXPECT_LE(gears, 3);
  }
}

}  // namespace
}  // namespace prs::sampling
