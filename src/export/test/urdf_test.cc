// URDF read back by urdfdom (the parser of ROS tools): one link per object hanging from "world",
// fixed or floating as the rules say, at the scene's exact pose, with its geometry, colour and
// inertia.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include "export/test/example_scenes.h"
#include "export/test/mesh_file_check.h"

namespace prs::exporting {
namespace {

using testing_scenes::ExampleScenes;
using testing_scenes::SameRotation;
using testing_scenes::SameVector;
using testing_scenes::ExpectMeshFileFits;

Eigen::Vector3d ToEigen(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

void ExpectGeometry(const urdf::Link& link, const Body& body) {
  ASSERT_NE(link.visual, nullptr) << body.name;
  const urdf::GeometrySharedPtr& geometry = link.visual->geometry;
  if (body.shape == Shape::kSphere) {
    const auto sphere = std::dynamic_pointer_cast<urdf::Sphere>(geometry);
    ASSERT_NE(sphere, nullptr) << body.name;
    EXPECT_DOUBLE_EQ(sphere->radius, body.size.x() / 2);
  } else if (body.shape == Shape::kCapsule) {  // URDF has none: the cylinder around it
    const auto cylinder = std::dynamic_pointer_cast<urdf::Cylinder>(geometry);
    ASSERT_NE(cylinder, nullptr) << body.name;
    EXPECT_DOUBLE_EQ(cylinder->length, body.size.z());
    EXPECT_DOUBLE_EQ(cylinder->radius, body.size.x() / 2);
  } else if (body.shape == Shape::kMesh && body.has_mesh_file()) {
    const auto mesh = std::dynamic_pointer_cast<urdf::Mesh>(geometry);
    ASSERT_NE(mesh, nullptr) << body.name;
    const Eigen::Vector3d scale = ToEigen(mesh->scale);
    ExpectMeshFileFits(mesh->filename, scale, ToEigen(link.visual->origin.position), body);
  } else if (body.shape == Shape::kCylinder) {
    const auto cylinder = std::dynamic_pointer_cast<urdf::Cylinder>(geometry);
    ASSERT_NE(cylinder, nullptr) << body.name;
    EXPECT_DOUBLE_EQ(cylinder->length, body.size.z());
    EXPECT_DOUBLE_EQ(cylinder->radius, std::min(body.size.x(), body.size.y()) / 2);
  } else {
    const auto box = std::dynamic_pointer_cast<urdf::Box>(geometry);
    ASSERT_NE(box, nullptr) << body.name;
    EXPECT_TRUE(SameVector(ToEigen(box->dim), body.size, 0)) << body.name;
  }
  ASSERT_NE(link.visual->material, nullptr);
  EXPECT_FLOAT_EQ(link.visual->material->color.b, float(body.color.b));
  EXPECT_EQ(link.collision != nullptr, body.collides) << body.name;
}

void ExpectLinkAsInScene(const urdf::ModelInterface& model, const Body& body,
                         const std::string& label) {
  const urdf::LinkConstSharedPtr link = model.getLink(body.name);
  ASSERT_NE(link, nullptr) << label << ": no link " << body.name;
  const urdf::JointConstSharedPtr joint = model.getJoint(body.name + "_joint");
  ASSERT_NE(joint, nullptr) << label << ": no joint for " << body.name;
  EXPECT_EQ(joint->parent_link_name, "world");
  EXPECT_EQ(joint->child_link_name, body.name);
  EXPECT_EQ(joint->type, body.is_free() ? urdf::Joint::FLOATING : urdf::Joint::FIXED);
  const urdf::Pose& pose = joint->parent_to_joint_origin_transform;
  EXPECT_TRUE(SameVector(ToEigen(pose.position), body.p_WO, 0)) << label << " " << body.name;
  double x, y, z, w;
  pose.rotation.getQuaternion(x, y, z, w);
  EXPECT_TRUE(SameRotation(Eigen::Quaterniond(w, x, y, z), body.R_WO)) << label << body.name;
  if (body.shape != Shape::kNone) ExpectGeometry(*link, body);
  ASSERT_EQ(link->inertial != nullptr, body.is_free()) << body.name;
  if (body.is_free()) {
    EXPECT_DOUBLE_EQ(link->inertial->mass, body.mass_kg);
    EXPECT_DOUBLE_EQ(link->inertial->izz, body.inertia_diag.z());
  }
}

TEST(UrdfTest, UrdfdomReadsEveryExampleSceneAsSampled) {
  ASSERT_FALSE(ExampleScenes().empty());
  for (const auto& example : ExampleScenes()) {
    const urdf::ModelInterfaceSharedPtr model =
        urdf::parseURDF(WriteScene(example.exported, Format::kUrdf));
    ASSERT_NE(model, nullptr) << example.label;
    EXPECT_EQ(model->getRoot()->name, "world");
    EXPECT_EQ(model->links_.size(), example.exported.bodies.size() + 2);  // + world and ground
    for (const Body& body : example.exported.bodies)
      ExpectLinkAsInScene(*model, body, example.label);
  }
}

// Poses at gimbal lock (pitch +-90 degrees) and upside down survive the roll-pitch-yaw form.
TEST(UrdfTest, AnglesSurviveGimbalLockAndHalfTurns) {
  ExportScene scene;
  const Eigen::Quaterniond rotations[] = {
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY())),
      Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY())) *
          Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d(1, 1, 0).normalized())),
      Eigen::Quaterniond(0.3, -0.5, 0.2, 0.7).normalized(),
  };
  for (const Eigen::Quaterniond& R : rotations) {
    Body body;
    body.name = fmt::format("b{}", scene.bodies.size());
    body.R_WO = R;
    body.size = Eigen::Vector3d(0.1, 0.2, 0.3);
    scene.bodies.push_back(body);
  }
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(WriteScene(scene, Format::kUrdf));
  ASSERT_NE(model, nullptr);
  for (const Body& body : scene.bodies) ExpectLinkAsInScene(*model, body, "gimbal");
}

}  // namespace
}  // namespace prs::exporting
