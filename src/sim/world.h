// A simulated world from a sampled scene (issue 6): the scene's objects as exported for MuJoCo
// (export/export.h: static fixtures, free bodies with mass, cameras), a Panda arm in place of
// every Robot object, and four walls around every Tray, so that "against a tray wall" is physical.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "export/export.h"
#include "sim/ik.h"

namespace prs::sim {

/// Tray walls stand on the tray's rim, outside its footprint (the sampler's `completely on`
/// keeps objects inside the footprint, so walls never start inside an object).
inline constexpr double kTrayWallThickness_m = 0.006;
inline constexpr double kTrayWallHeight_m = 0.03;

/// One Panda and the Robot object it stands in for.
struct WorldArm {
  std::string robot_name;  // the scene object's (export) name
  PandaNames names;
  Eigen::Isometry3d X_WBase = Eigen::Isometry3d::Identity();
  ArmIndex index;
};

struct World {
  exporting::ExportScene scene;
  ModelPtr model;
  DataPtr data;
  std::vector<WorldArm> arms;
  std::string xml;  // the MJCF the model was compiled from, for debugging and --save-failures

  std::vector<ArmIndex> arm_indices() const;
  /// The body of the scene object `name` (export name). Throws std::out_of_range if none.
  int body(const std::string& name) const;
  /// The first scene object of a class (e.g. "Cube"), or nullptr.
  const exporting::Body* FindFirst(const std::string& class_name) const;
};

/// X_WBase of the arm a Robot object stands for (kinematics::CalcArmMount, the language's
/// convention too): at the centre of the object's bottom face (on whatever the object is on),
/// facing where the object faces (the arm's forward x along the object's forward y, its z along
/// the object's up). Independent of the box's height: the box is the robot's bounding volume,
/// 0.1 m or 1.026 m tall alike.
Eigen::Isometry3d CalcArmMount(const exporting::Body& robot);

/// The world's MJCF: export's MuJoCo document with the arms, tray walls and their actuators.
/// Robot objects are bodies without geometry there: the arm stands in the box's place, and
/// the box (the volume the sampler keeps other objects out of) would enclose the arm's links
/// and, drawn, hide the arm and, 1 m tall, much of the table from a ceiling camera.
std::string WriteWorldMjcf(const exporting::ExportScene& scene);

/// The density a pick target without a mass is simulated at: MuJoCo's default for geoms
/// (water's), so the original tool's 4 cm cube weighs 64 g.
inline constexpr double kDefaultPickTargetDensity_kg_m3 = 1000;

/// An object a controller must pick up cannot be static. When `body` has no positive mass (so
/// docs/export.md's rules fix it in the world), makes it a free body of its solid shape at
/// kDefaultPickTargetDensity_kg_m3 and returns one sentence for the user saying so and how to
/// choose the mass; otherwise leaves it and returns nullopt. A point (no volume) is left too.
std::optional<std::string> MakePickTargetFree(exporting::Body& body);

/// Compiles the world and puts each arm in its ready pose. The world keeps MuJoCo's default
/// contact model even for a settled scene (`scene.settled` is ignored; docs/physics.md). Throws
/// std::runtime_error when MuJoCo rejects the model.
World BuildWorld(exporting::ExportScene scene);

}  // namespace prs::sim
