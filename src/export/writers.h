// Internal to the export library: one writer per format, and the number and angle formatting
// they share.
#pragma once

#include <string>

#include "export/export.h"

namespace prs::exporting::internal {

std::string WriteMjcf(const ExportScene& scene);
std::string WriteUrdf(const ExportScene& scene);
std::string WriteSdf(const ExportScene& scene);
std::string WriteUsda(const ExportScene& scene);
/// glTF 2.0: JSON with the buffer embedded as a base64 data URI, or binary .glb.
std::string WriteGltf(const ExportScene& scene, bool binary);

/// The shortest text that reads back as exactly `x` ("0.1", "1e-07"; integral values as "2").
std::string FormatNumber(double x);
/// "x y z" (separator " "), or "x, y, z" with separator ", ".
std::string FormatVector(const Eigen::Vector3d& v, const char* separator = " ");
std::string FormatRgba(const Rgba& color, const char* separator = " ");

/// Fixed-axis roll, pitch, yaw as URDF and SDF poses use them: R = Rz(yaw) Ry(pitch) Rx(roll).
/// Pitch is in [-pi/2, pi/2]; at pitch +-pi/2 the roll is 0.
Eigen::Vector3d CalcRollPitchYaw(const Eigen::Quaterniond& R_WO);

/// A mesh body's file as an absolute file:// URI, for formats that name the file (URDF, SDF).
std::string FormatMeshUri(const Body& body);
/// Where a mesh body's file frame sits in the body's frame: the file's coordinates are scaled,
/// then moved by this, so that the bounding box's centre lands on the body's origin.
Eigen::Vector3d CalcMeshFileOffset(const Body& body);

/// Standard gravity along world -z, m/s^2, written into every physics format.
inline constexpr double kGravity = 9.81;
/// The ground is the plane z = 0; where a format has no plane, a slab this thick below it.
inline constexpr double kGroundThickness = 0.1;
inline constexpr double kGroundHalfWidth = 10.0;

}  // namespace prs::exporting::internal
