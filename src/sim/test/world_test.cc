// The simulated Table-Cube world: every scene object is in the model where the scene put it,
// an arm stands on each robot, trays have walls, and the world rests under gravity.
#include <gtest/gtest.h>

#include "sim/control.h"
#include "sim/test/table_cube_scenes.h"
#include "sim/world.h"

namespace prs::sim {
namespace {

using testing_scenes::SampleTableCube;

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
    EXPECT_NEAR(p_base.z(), robot->p_WO.z() + robot->size.z() / 2, 1e-9);  // on the top face
    // The arm faces where the robot faces (+y in Table-Cube): its hand is ahead of its base.
    EXPECT_GT(GetTcpPose(*world.data, arm.index).translation().y(), p_base.y() + 0.2);
  }
  for (const exporting::Body& b : world.scene.bodies) {
    if (b.class_name == "Tray") EXPECT_GE(world.body(b.name + "_walls"), 0);
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

}  // namespace
}  // namespace prs::sim
