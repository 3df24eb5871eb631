// MJCF read back by MuJoCo's own loader: every body where the scene puts it, with its shape,
// size and mass; then one second of simulation under gravity in which no object that rests on
// something at the start moves 5 mm or more, and no two geoms interpenetrate at the start.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <memory>

#include "export/test/example_scenes.h"
#include "sim/mujoco_model.h"

namespace prs::exporting {
namespace {

using testing_scenes::ExampleScenes;
using testing_scenes::SameRotation;
using testing_scenes::SameVector;

constexpr double kContactTolerance = 1e-6;  // metres: touching faces count as touching
constexpr double kMaxDrift = 0.005;         // metres in one second

using sim::DataPtr;
using sim::ModelPtr;

// Null, with MuJoCo's message in `error`, when MuJoCo rejects the document.
ModelPtr LoadMjcf(const std::string& xml, std::string& error) {
  try {
    return sim::LoadModelFromXml(xml);
  } catch (const std::runtime_error& rejected) {
    error = rejected.what();
    return nullptr;
  }
}

struct WorldBox {
  Eigen::Vector3d low, high;
};

WorldBox CalcWorldBox(const Body& body) {
  WorldBox box{Eigen::Vector3d::Constant(HUGE_VAL), Eigen::Vector3d::Constant(-HUGE_VAL)};
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d sign(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
    const Eigen::Vector3d p = body.p_WO + body.R_WO * sign.cwiseProduct(body.size / 2);
    box.low = box.low.cwiseMin(p);
    box.high = box.high.cwiseMax(p);
  }
  return box;
}

bool Overlap2d(const WorldBox& a, const WorldBox& b) {
  return a.low.x() < b.high.x() && b.low.x() < a.high.x() && a.low.y() < b.high.y() &&
         b.low.y() < a.high.y();
}

// Free bodies whose bottom touches the ground, a static body's top, or a resting body's top.
// Objects placed in mid-air (constructs.prs has some) fall, and are not checked.
std::vector<bool> FindRestingBodies(const ExportScene& scene) {
  const size_t n = scene.bodies.size();
  std::vector<WorldBox> boxes;
  std::vector<bool> supports(n), resting(n, false);
  for (size_t i = 0; i < n; ++i) {
    boxes.push_back(CalcWorldBox(scene.bodies[i]));
    supports[i] = !scene.bodies[i].is_free() && scene.bodies[i].collides;
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < n; ++i) {
      if (!scene.bodies[i].is_free() || resting[i]) continue;
      bool rests = std::abs(boxes[i].low.z()) < kContactTolerance;
      for (size_t j = 0; j < n && !rests; ++j) {
        rests = j != i && supports[j] &&
                std::abs(boxes[j].high.z() - boxes[i].low.z()) < kContactTolerance &&
                Overlap2d(boxes[i], boxes[j]);
      }
      if (rests) resting[i] = supports[i] = changed = true;
    }
  }
  return resting;
}

// A mesh body's visual geom draws the mesh where the scene has it: its vertices, placed by
// MuJoCo's geom frame (the compiler moves a mesh to its own inertial frame), span the body's
// box in the body's frame. Its collision pieces do not draw and do collide.
void ExpectMeshAsInScene(const mjModel& m, const Body& body, int geom, const std::string& label) {
  ASSERT_EQ(m.geom_type[geom], mjGEOM_MESH) << label << " " << body.name;
  EXPECT_EQ(m.geom_contype[geom] | m.geom_conaffinity[geom], 0) << body.name;
  const int mesh = m.geom_dataid[geom];
  EXPECT_EQ(m.mesh_vertnum[mesh], int(body.mesh->mesh.vertices_O.size())) << body.name;
  EXPECT_EQ(m.mesh_facenum[mesh], int(body.mesh->mesh.triangles.size())) << body.name;
  const Eigen::Map<const Eigen::Vector3d> p_BG(m.geom_pos + 3 * geom);
  const mjtNum* q = m.geom_quat + 4 * geom;
  const Eigen::Quaterniond R_BG(q[0], q[1], q[2], q[3]);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (int v = 0; v < m.mesh_vertnum[mesh]; ++v) {
    const float* p = m.mesh_vert + 3 * (m.mesh_vertadr[mesh] + v);
    const Eigen::Vector3d p_B = p_BG + R_BG * Eigen::Vector3d(p[0], p[1], p[2]);
    lo = lo.cwiseMin(p_B);
    hi = hi.cwiseMax(p_B);
  }
  const double error_m = std::max((lo + body.size / 2).cwiseAbs().maxCoeff(),
                                  (hi - body.size / 2).cwiseAbs().maxCoeff());
  EXPECT_LT(error_m, 1e-5)  // MuJoCo keeps vertices as floats
      << label << " " << body.name << ": mesh spans " << lo.transpose() << " to " << hi.transpose();
  int pieces = 0;
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_bodyid[g] != m.geom_bodyid[geom] || g == geom) continue;
    EXPECT_EQ(m.geom_type[g], mjGEOM_MESH);
    EXPECT_EQ(m.geom_group[g], 3);  // hidden in MuJoCo's default view
    ++pieces;
  }
  EXPECT_EQ(pieces > 0, body.collides) << label << " " << body.name;
}

void ExpectBodiesAsInScene(const mjModel& m, const ExportScene& scene, const std::string& label) {
  ASSERT_EQ(m.nbody, int(scene.bodies.size()) + 1) << label;  // + the world body
  for (const Body& body : scene.bodies) {
    const int id = mj_name2id(&m, mjOBJ_BODY, body.name.c_str());
    ASSERT_GE(id, 1) << label << ": no body " << body.name;
    const Eigen::Map<const Eigen::Vector3d> p(m.body_pos + 3 * id);
    const mjtNum* q = m.body_quat + 4 * id;
    EXPECT_TRUE(SameVector(p, body.p_WO)) << label << " " << body.name;
    EXPECT_TRUE(SameRotation(Eigen::Quaterniond(q[0], q[1], q[2], q[3]), body.R_WO))
        << label << " " << body.name;
    EXPECT_EQ(m.body_jntnum[id], body.is_free() ? 1 : 0) << body.name;
    if (body.is_free()) {
      EXPECT_NEAR(m.body_mass[id], body.mass_kg, 1e-12) << body.name;
    }
    if (body.shape == Shape::kNone) continue;
    const int geom = mj_name2id(&m, mjOBJ_GEOM, body.name.c_str());
    ASSERT_GE(geom, 0) << body.name;
    if (body.shape == Shape::kMesh) {
      ExpectMeshAsInScene(m, body, geom, label);
      continue;
    }
    const Eigen::Map<const Eigen::Vector3d> size(m.geom_size + 3 * geom);
    switch (body.shape) {
      case Shape::kBox:
        EXPECT_EQ(m.geom_type[geom], mjGEOM_BOX) << body.name;
        EXPECT_TRUE(SameVector(size, body.size / 2));
        break;
      case Shape::kCylinder:
        EXPECT_EQ(m.geom_type[geom], mjGEOM_CYLINDER) << body.name;
        EXPECT_DOUBLE_EQ(size[1], body.size.z() / 2) << body.name;
        break;
      case Shape::kSphere:
        EXPECT_EQ(m.geom_type[geom], mjGEOM_SPHERE) << body.name;
        EXPECT_DOUBLE_EQ(size[0], body.size.x() / 2) << body.name;
        break;
      case Shape::kCapsule:  // radius and the straight part's half-length
        EXPECT_EQ(m.geom_type[geom], mjGEOM_CAPSULE) << body.name;
        EXPECT_DOUBLE_EQ(size[0], body.size.x() / 2) << body.name;
        EXPECT_NEAR(size[1], (body.size.z() - body.size.x()) / 2, 1e-15) << body.name;
        break;
      default:
        ADD_FAILURE() << body.name;
    }
  }
}

// At the start, no contact is deeper than the tolerance (touching faces have distance ~0).
void ExpectNoInterpenetration(const mjModel& m, mjData& d, const std::string& label) {
  mj_forward(&m, &d);
  for (int i = 0; i < d.ncon; ++i) {
    const mjContact& c = d.contact[i];
    EXPECT_GE(c.dist, -kContactTolerance)
        << label << ": " << mj_id2name(&m, mjOBJ_GEOM, c.geom1) << " and "
        << mj_id2name(&m, mjOBJ_GEOM, c.geom2) << " interpenetrate by " << -c.dist << " m";
  }
}

// Returns the largest drift of a resting body, metres.
double ExpectRestingBodiesStay(const mjModel& m, mjData& d, const ExportScene& scene,
                               const std::string& label) {
  double max_drift = 0;
  const std::vector<bool> resting = FindRestingBodies(scene);
  const int steps = int(std::lround(1.0 / m.opt.timestep));
  for (int i = 0; i < steps; ++i) mj_step(&m, &d);
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    if (!resting[i]) continue;
    const Body& body = scene.bodies[i];
    const int id = mj_name2id(&m, mjOBJ_BODY, body.name.c_str());
    const Eigen::Map<const Eigen::Vector3d> p_WO(d.xpos + 3 * id);
    max_drift = std::max(max_drift, (p_WO - body.p_WO).norm());
    EXPECT_LT((p_WO - body.p_WO).norm(), kMaxDrift)
        << label << ": " << body.name << " moved from (" << body.p_WO.transpose() << ") to ("
        << p_WO.transpose() << ") in 1 s";
  }
  return max_drift;
}

TEST(MjcfTest, MujocoLoadsEveryExampleSceneAsSampled) {
  ASSERT_FALSE(ExampleScenes().empty());
  for (const auto& example : ExampleScenes()) {
    std::string error;
    const ModelPtr model = LoadMjcf(WriteScene(example.exported, Format::kMjcf), error);
    ASSERT_NE(model, nullptr) << example.label << ": " << error;
    ExpectBodiesAsInScene(*model, example.exported, example.label);
  }
}

TEST(MjcfTest, RestingObjectsStayPutForOneSecond) {
  int checked = 0;
  double max_drift = 0;
  for (const auto& example : ExampleScenes()) {
    std::string error;
    const ModelPtr model = LoadMjcf(WriteScene(example.exported, Format::kMjcf), error);
    ASSERT_NE(model, nullptr) << example.label << ": " << error;
    DataPtr data = sim::MakeData(*model);
    ExpectNoInterpenetration(*model, *data, example.label);
    max_drift = std::max(max_drift,
                         ExpectRestingBodiesStay(*model, *data, example.exported, example.label));
    for (const bool rests : FindRestingBodies(example.exported)) checked += rests;
  }
  // table_cube's cube and constructs' cups and gears, over several seeds.
  EXPECT_GE(checked, 6 * 1 + 6 * 3);
  std::printf("%d resting objects checked; the largest drift in 1 s was %.2f mm\n", checked,
              1000 * max_drift);
  RecordProperty("max_drift_mm", std::to_string(1000 * max_drift));
}

// A Camera object becomes a MuJoCo camera looking along the object's forward (+y) axis, upright.
TEST(MjcfTest, CamerasLookWhereTheObjectFaces) {
  const lang::Scene& scene = testing_scenes::SampleText(
      "from model import *\n"
      "down = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1)\n"
      "side = Camera at V3D(1, 0, 1), facing toward V3D(0, 0, 1)\n");
  const ExportScene exported = MakeExportScene(scene, "t");
  std::string error;
  const ModelPtr model = LoadMjcf(WriteScene(exported, Format::kMjcf), error);
  ASSERT_NE(model, nullptr) << error;
  ASSERT_EQ(model->ncam, 2);
  DataPtr data = sim::MakeData(*model);
  mj_forward(model.get(), data.get());
  using RowMajor3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  for (int i = 0; i < 2; ++i) {
    const Body& body = exported.bodies[i];
    // cam_xmat is row-major: column k is the camera's axis k in the world.
    const Eigen::Map<const RowMajor3d> R_WC(data->cam_xmat + 9 * i);
    EXPECT_TRUE(SameVector(-R_WC.col(2), body.R_WO * Eigen::Vector3d::UnitY())) << body.name;
    EXPECT_TRUE(SameVector(R_WC.col(1), body.R_WO * Eigen::Vector3d::UnitZ())) << body.name;
    if (body.name == "side") {  // looks at the origin's x from x = 1
      EXPECT_TRUE(SameVector(-R_WC.col(2), Eigen::Vector3d(-1, 0, 0)));
    }
  }
}

TEST(MjcfTest, ObjectsInMidAirAreNotCountedAsResting) {
  const lang::Scene& scene = testing_scenes::SampleText(
      "from model import *\n"
      "t = Table on V3D(0, 0, 0)\n"
      "a = Cube on t\n"
      "b = Cube at V3D(1, 1, 1)\n");
  const std::vector<bool> resting = FindRestingBodies(MakeExportScene(scene, "t"));
  EXPECT_EQ(resting, (std::vector<bool>{false, true, false}));
}

// A free can (longer than its diameter) gets a hidden capsule along its side with rolling
// friction, so that it lies still on its side; a squat free cylinder and a static one do not.
TEST(MjcfTest, FreeCansGetACapsuleAlongTheirSide) {
  ExportScene scene;
  const auto cylinder = [](const char* name, double height_m, double mass_kg) {
    Body body;
    body.name = name;
    body.shape = Shape::kCylinder;
    body.size = Eigen::Vector3d(0.066, 0.066, height_m);
    body.p_WO = Eigen::Vector3d(0, 0, 1);
    body.mass_kg = mass_kg;
    body.inertia_diag = Eigen::Vector3d::Constant(1e-4);
    return body;
  };
  scene.bodies = {cylinder("can", 0.12, 0.3), cylinder("puck", 0.05, 0.3),
                  cylinder("post", 0.12, 0)};
  std::string error;
  const ModelPtr model = LoadMjcf(WriteScene(scene, Format::kMjcf), error);
  ASSERT_NE(model, nullptr) << error;
  const int spine = mj_name2id(model.get(), mjOBJ_GEOM, "can_spine");
  ASSERT_GE(spine, 0);
  EXPECT_EQ(model->geom_type[spine], mjGEOM_CAPSULE);
  EXPECT_DOUBLE_EQ(model->geom_size[3 * spine], 0.033);             // the can's radius
  EXPECT_DOUBLE_EQ(model->geom_size[3 * spine + 1], 0.06 - 0.033);  // ends at its flat ends
  EXPECT_EQ(model->geom_condim[spine], 6);
  EXPECT_DOUBLE_EQ(model->geom_friction[3 * spine + 2], 0.001);  // rolling, metres
  EXPECT_EQ(model->geom_group[spine], 3);
  EXPECT_LT(mj_name2id(model.get(), mjOBJ_GEOM, "puck_spine"), 0);
  EXPECT_LT(mj_name2id(model.get(), mjOBJ_GEOM, "post_spine"), 0);
  EXPECT_GE(mj_name2id(model.get(), mjOBJ_GEOM, "post_foot"), 0);
}

}  // namespace
}  // namespace prs::exporting
