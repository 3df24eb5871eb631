// The simulated Table-Cube world: every scene object is in the model where the scene put it,
// an arm stands where each robot does, on its support, whatever the robot box's height and yaw,
// trays have walls, and the world rests under gravity.
#include "sim/world.h"

#include <gtest/gtest.h>

#include <numbers>

#include "sim/control.h"
#include "sim/motion.h"
#include "sim/test/table_cube_scenes.h"

namespace prs::sim {
namespace {

using testing_scenes::SampleTableCube;
using testing_scenes::WithRobotBoxes;

// Robot boxes as short as examples/model.prs's, and as tall as the original tool's Panda.
constexpr double kRobotHeights_m[] = {0.1, 0.5, 1.026};
constexpr double kRobotYaws_rad[] = {0, 0.6, -2.2, std::numbers::pi};

Eigen::Vector3d BodyPosition(const World& world, const std::string& name) {
  return Eigen::Map<const Eigen::Vector3d>(world.data->xpos + 3 * world.body(name));
}

TEST(WorldTest, EveryObjectIsWhereTheSceneSaysAndArmsStandOnRobots) {
  const lang::Scene scene = SampleTableCube(0);
  World world = BuildWorld(exporting::MakeExportScene(scene, "test"));
  ASSERT_EQ(world.scene.bodies.size(), scene.objects.size());
  for (const exporting::Body& b : world.scene.bodies) {
    EXPECT_LT((BodyPosition(world, b.name) - b.p_WO).norm(), 1e-9) << b.name;
  }
  ASSERT_EQ(world.arms.size(), 2u);
  for (const WorldArm& arm : world.arms) {
    const exporting::Body* robot = nullptr;
    for (const exporting::Body& b : world.scene.bodies) robot = b.name == arm.robot_name ? &b : robot;
    ASSERT_NE(robot, nullptr);
    const Eigen::Vector3d p_base = BodyPosition(world, arm.names.base());
    EXPECT_NEAR(p_base.z(), robot->p_WO.z() - robot->size.z() / 2, 1e-9);  // on the table
    // The arm faces where the robot faces (+y in Table-Cube): its hand is ahead of its base.
    EXPECT_GT(GetTcpPose(*world.data, arm.index).translation().y(), p_base.y() + 0.2);
  }
  for (const exporting::Body& b : world.scene.bodies) {
    if (b.class_name == "Tray") {
      EXPECT_GE(world.body(b.name + "_walls"), 0);
    }
  }
}

// The world of a settled scene keeps MuJoCo's default contact model (pyramidal cones, impratio
// 1), though the scene's own export carries the elliptic cones it was settled with.
TEST(WorldTest, SettledScenesAreSimulatedInTheSameContactModel) {
  lang::Scene scene = SampleTableCube(0);
  scene.settled_s = 0.5;
  const exporting::ExportScene exported = exporting::MakeExportScene(scene, "test");
  ASSERT_TRUE(exported.settled);
  const ModelPtr own = LoadModelFromXml(exporting::WriteScene(exported, exporting::Format::kMjcf));
  EXPECT_EQ(own->opt.cone, mjCONE_ELLIPTIC);
  const World world = BuildWorld(exported);
  EXPECT_EQ(world.model->opt.cone, mjCONE_PYRAMIDAL);
  EXPECT_EQ(world.model->opt.impratio, 1);
}

TEST(WorldTest, TheArmMountIsTheRobotBoxsBottomFaceForAnyHeightAndYaw) {
  for (const double height : kRobotHeights_m) {
    for (const double yaw : kRobotYaws_rad) {
      exporting::Body robot;
      robot.class_name = "Robot";
      robot.size = Eigen::Vector3d(0.14, 0.22, height);
      robot.p_WO = Eigen::Vector3d(0.3, -0.2, 0.8 + height / 2);  // on a support at z = 0.8
      robot.R_WO = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
      SCOPED_TRACE(::testing::Message() << "height " << height << " m, yaw " << yaw << " rad");
      const Eigen::Isometry3d X_WBase = CalcArmMount(robot);
      EXPECT_LT((X_WBase.translation() - Eigen::Vector3d(0.3, -0.2, 0.8)).norm(), 1e-12);
      EXPECT_TRUE(X_WBase.linear().col(2).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
      // The arm's forward x is the robot's forward y.
      EXPECT_TRUE(X_WBase.linear().col(0).isApprox(robot.R_WO * Eigen::Vector3d::UnitY(), 1e-12));
    }
  }
}

// In the built world: each arm's base is on the table top, the Robot's body has no geometry
// (the arm is in its box), and the arms hold their ready pose, with nothing pushing them.
TEST(WorldTest, ArmsStandOnTheTableInsideRobotBoxesOfAnyHeight) {
  const lang::Scene scene = SampleTableCube(0);
  const double table_top = 0.8;
  for (int i = 0; i < 3; ++i) {
    const double height = kRobotHeights_m[i], yaw = kRobotYaws_rad[i + 1];
    SCOPED_TRACE(::testing::Message() << "height " << height << " m, yaw " << yaw << " rad");
    const lang::Scene boxed = WithRobotBoxes(scene, height, yaw);
    World world = BuildWorld(exporting::MakeExportScene(boxed, "test"));
    ASSERT_EQ(world.arms.size(), 2u);
    std::vector<Eigen::Vector3d> p_tcp_start;
    for (const WorldArm& arm : world.arms) {
      EXPECT_NEAR(BodyPosition(world, arm.names.base()).z(), table_top, 1e-9);
      EXPECT_EQ(world.model->body_geomnum[world.body(arm.robot_name)], 0);
      p_tcp_start.push_back(GetTcpPose(*world.data, arm.index).translation());
    }
    SimulateFor(*world.model, *world.data, world.arm_indices(), 1.0);
    for (size_t a = 0; a < world.arms.size(); ++a) {
      const Eigen::Vector3d p_tcp = GetTcpPose(*world.data, world.arms[a].index).translation();
      EXPECT_LT((p_tcp - p_tcp_start[a]).norm(), 0.002);
      EXPECT_GT(p_tcp.z(), table_top + 0.2);  // the ready pose is above the table
    }
  }
}

TEST(WorldTest, TheWorldRestsUnderGravity) {
  for (uint64_t index = 0; index < 5; ++index) {
    World world = BuildWorld(exporting::MakeExportScene(SampleTableCube(index), "test"));
    const exporting::Body* cube = world.FindFirst("Cube");
    ASSERT_NE(cube, nullptr);
    std::vector<Eigen::Vector3d> p_tcp_start;
    for (const WorldArm& arm : world.arms) p_tcp_start.push_back(GetTcpPose(*world.data, arm.index).translation());
    SimulateFor(*world.model, *world.data, world.arm_indices(), 1.0);
    EXPECT_LT((BodyPosition(world, cube->name) - cube->p_WO).norm(), 0.002) << index;
    for (size_t a = 0; a < world.arms.size(); ++a) {
      EXPECT_LT((GetTcpPose(*world.data, world.arms[a].index).translation() - p_tcp_start[a]).norm(), 0.002);
    }
  }
}

// A top-down grasp at the cube's true centre, with both cubes of the case study: the 5 cm,
// 0.1 kg one of model.prs and the original model's massless 4 cm one made free (64 g), and the
// light one with the hand a few millimetres off. The fingers close on it from both sides alike
// (their coupling holds to a millimetre), press into it by less than 4 mm, and lift it with
// the hand. With soft finger contacts and coupling the fingers sat 9 mm apart and 5.5 mm deep.
TEST(WorldTest, AGraspHoldsTheCubeCentredAndLiftsIt) {
  struct Case {
    lang::Scene scene;
    Eigen::Vector3d p_off;  // where the hand goes, from the cube's centre: a sighting error
  };
  const Case cases[] = {{SampleTableCube(0), Eigen::Vector3d::Zero()},
                        {testing_scenes::SamplePaperModel(1), Eigen::Vector3d::Zero()},
                        {testing_scenes::SamplePaperModel(1), Eigen::Vector3d(0.007, 0.007, 0)}};
  for (const auto& [scene, p_off] : cases) {
    exporting::ExportScene exported = exporting::MakeExportScene(scene, "test");
    for (exporting::Body& b : exported.bodies) {
      if (b.class_name == "Cube") MakePickTargetFree(b);
    }
    World world = BuildWorld(std::move(exported));
    const exporting::Body& cube = *world.FindFirst("Cube");
    const WorldArm& arm = world.arms[0];
    SCOPED_TRACE(::testing::Message() << cube.name << " of " << cube.size.x() << " m, the hand "
                                      << p_off.transpose() << " m off its centre");
    const Eigen::Vector3d up(0, 0, 0.12);
    const Eigen::Vector3d p_hand = cube.p_WO + p_off;
    const TcpPlan plan = PlanDownwardPath(world, arm, {{p_hand + up, "above"}, {p_hand, "at"},
                                                       {p_hand + up, "lift"}});
    ASSERT_EQ(plan.failed, -1);
    MoveJointsTo(world, arm, plan.q[0], 1.2);
    MoveJointsTo(world, arm, plan.q[1], 0.8);
    MoveGripper(world, arm, 0.0);
    const mjData& data = *world.data;
    const double q_left = data.qpos[arm.index.finger_qpos_address[0]];
    const double q_right = data.qpos[arm.index.finger_qpos_address[1]];
    EXPECT_NEAR(q_left, q_right, 0.001);
    const int cube_body = world.body(cube.name);
    int finger_contacts = 0;
    for (int i = 0; i < data.ncon; ++i) {
      const mjContact& c = data.contact[i];
      const int* body_of = world.model->geom_bodyid;
      if (body_of[c.geom1] != cube_body && body_of[c.geom2] != cube_body) continue;
      if (c.pos[2] < cube.p_WO.z() - cube.size.z() / 2 + 0.001) continue;  // the support
      ++finger_contacts;
      EXPECT_GT(c.dist, -0.004);
    }
    EXPECT_GE(finger_contacts, 2);
    MoveJointsTo(world, arm, plan.q[2], 0.8);
    EXPECT_GT(BodyPosition(world, cube.name).z() - cube.p_WO.z(), 0.1);
  }
}

}  // namespace
}  // namespace prs::sim
