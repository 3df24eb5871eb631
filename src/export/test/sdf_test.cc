// SDFormat read back by libsdformat (Gazebo's parser): a world with the ground and one model per
// object, static or not as the rules say, at the scene's exact pose, with geometry and mass.
#include <gtest/gtest.h>

#include <sdf/sdf.hh>

#include "export/test/example_scenes.h"
#include "export/test/mesh_file_check.h"

namespace prs::exporting {
namespace {

using testing_scenes::ExampleScenes;
using testing_scenes::SameRotation;
using testing_scenes::SameVector;
using testing_scenes::ExpectMeshFileFits;

void ExpectGeometry(const sdf::Link& link, const Body& body) {
  ASSERT_EQ(link.VisualCount(), 1u) << body.name;
  const sdf::Geometry& geometry = *link.VisualByIndex(0)->Geom();
  if (body.shape == Shape::kSphere) {
    ASSERT_EQ(geometry.Type(), sdf::GeometryType::SPHERE) << body.name;
    EXPECT_DOUBLE_EQ(geometry.SphereShape()->Radius(), body.size.x() / 2);
  } else if (body.shape == Shape::kCapsule) {
    ASSERT_EQ(geometry.Type(), sdf::GeometryType::CAPSULE) << body.name;
    EXPECT_DOUBLE_EQ(geometry.CapsuleShape()->Radius(), body.size.x() / 2);
    EXPECT_DOUBLE_EQ(geometry.CapsuleShape()->Length(), body.size.z() - body.size.x());
  } else if (body.shape == Shape::kMesh && body.has_mesh_file()) {
    ASSERT_EQ(geometry.Type(), sdf::GeometryType::MESH) << body.name;
    const auto& s = geometry.MeshShape()->Scale();
    const auto& p = link.VisualByIndex(0)->RawPose().Pos();
    ExpectMeshFileFits(geometry.MeshShape()->Uri(), {s.X(), s.Y(), s.Z()}, {p.X(), p.Y(), p.Z()}, body);
  } else if (body.shape == Shape::kCylinder) {
    ASSERT_EQ(geometry.Type(), sdf::GeometryType::CYLINDER) << body.name;
    EXPECT_DOUBLE_EQ(geometry.CylinderShape()->Length(), body.size.z());
  } else {
    ASSERT_EQ(geometry.Type(), sdf::GeometryType::BOX) << body.name;
    const auto& size = geometry.BoxShape()->Size();
    EXPECT_TRUE(SameVector({size.X(), size.Y(), size.Z()}, body.size, 0)) << body.name;
  }
  EXPECT_FLOAT_EQ(link.VisualByIndex(0)->Material()->Diffuse().B(), float(body.color.b));
  EXPECT_EQ(link.CollisionCount(), body.collides ? 1u : 0u) << body.name;
}

void ExpectModelAsInScene(const sdf::World& world, const Body& body, const std::string& label) {
  const sdf::Model* model = world.ModelByName(body.name);
  ASSERT_NE(model, nullptr) << label << ": no model " << body.name;
  EXPECT_EQ(model->Static(), !body.is_free()) << body.name;
  const auto& pose = model->RawPose();
  EXPECT_TRUE(SameVector({pose.Pos().X(), pose.Pos().Y(), pose.Pos().Z()}, body.p_WO, 0))
      << label << " " << body.name;
  const auto& q = pose.Rot();
  EXPECT_TRUE(SameRotation(Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z()), body.R_WO))
      << label << " " << body.name;
  ASSERT_EQ(model->LinkCount(), 1u);
  const sdf::Link& link = *model->LinkByIndex(0);
  if (body.is_free()) {
    EXPECT_DOUBLE_EQ(link.Inertial().MassMatrix().Mass(), body.mass_kg);
    EXPECT_DOUBLE_EQ(link.Inertial().MassMatrix().DiagonalMoments().X(), body.inertia_diag.x());
  }
  if (body.shape != Shape::kNone) ExpectGeometry(link, body);
}

TEST(SdfTest, LibsdformatReadsEveryExampleSceneAsSampled) {
  ASSERT_FALSE(ExampleScenes().empty());
  for (const auto& example : ExampleScenes()) {
    sdf::Root root;
    const sdf::Errors errors = root.LoadSdfString(WriteScene(example.exported, Format::kSdf));
    for (const sdf::Error& error : errors)
      ADD_FAILURE() << example.label << ": " << error.Message();
    ASSERT_EQ(root.WorldCount(), 1u) << example.label;
    const sdf::World& world = *root.WorldByIndex(0);
    EXPECT_EQ(world.ModelCount(), example.exported.bodies.size() + 1);  // + ground
    EXPECT_DOUBLE_EQ(world.Gravity().Z(), -9.81);
    for (const Body& body : example.exported.bodies)
      ExpectModelAsInScene(world, body, example.label);
  }
}

TEST(SdfTest, LibsdformatRejectsABrokenFile) {
  // The check above is only as good as the parser's strictness: a model without a link's name
  // must be reported.
  sdf::Root root;
  std::string text = WriteScene(ExampleScenes().front().exported, Format::kSdf);
  text.replace(text.find("<link name=\"link\">"), 18, "<link>");
  EXPECT_FALSE(root.LoadSdfString(text).empty());
}

}  // namespace
}  // namespace prs::exporting
