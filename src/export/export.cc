// The export library's entry points: format names, the scene-to-bodies step, dispatch to the
// writers, and the number and angle formatting the writers share.
#include "export/export.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "export/body_rules.h"
#include "export/writers.h"
#include "lang/program.h"

namespace prs::exporting {
namespace {

struct FormatInfo {
  Format format;
  const char* name;
  const char* extension;
};

constexpr std::array<FormatInfo, 6> kFormats = {{
    {Format::kMjcf, "mjcf", ".xml"},
    {Format::kUrdf, "urdf", ".urdf"},
    {Format::kSdf, "sdf", ".sdf"},
    {Format::kUsda, "usda", ".usda"},
    {Format::kGltf, "gltf", ".gltf"},
    {Format::kGlb, "glb", ".glb"},
}};

const FormatInfo& Info(Format format) {
  for (const FormatInfo& info : kFormats) {
    if (info.format == format) return info;
  }
  return kFormats[0];  // unreachable: every enumerator is in the table
}

}  // namespace

std::optional<Format> ParseFormat(std::string_view name) {
  for (const FormatInfo& info : kFormats) {
    if (name == info.name) return info.format;
  }
  return std::nullopt;
}

const char* FormatName(Format format) { return Info(format).name; }
const char* FileExtension(Format format) { return Info(format).extension; }

std::optional<Format> FormatFromExtension(std::string_view extension) {
  for (const FormatInfo& info : kFormats) {
    if (extension == info.extension) return info.format;
  }
  return std::nullopt;
}

std::string ListFormatNames() {
  std::string list;
  for (const FormatInfo& info : kFormats)
    list += (list.empty() ? "" : ", ") + std::string(info.name);
  return list;
}

ExportScene MakeExportScene(const lang::Scene& scene, std::string title) {
  ExportScene out;
  out.title = std::move(title);
  internal::NameTable names;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const lang::SceneObject& object = scene.objects[i];
    internal::ObjectFacts facts;
    facts.name = object.name.value_or("");
    facts.class_name = object.cls != nullptr ? object.cls->name : "Object";
    facts.index = int(i);
    facts.p_WO = object.p_WO;
    facts.R_WO = object.R_WO;
    facts.dimensions = object.dimensions;
    facts.allow_collisions = object.allow_collisions;
    for (const auto& [name, value] : object.properties) facts.properties.emplace_back(name, value);
    out.bodies.push_back(internal::MakeBody(facts, names, out.warnings));
  }
  out.settled = scene.settled_s.has_value();
  return out;
}

std::string WriteScene(const ExportScene& scene, Format format) {
  switch (format) {
    case Format::kMjcf:
      return internal::WriteMjcf(scene);
    case Format::kUrdf:
      return internal::WriteUrdf(scene);
    case Format::kSdf:
      return internal::WriteSdf(scene);
    case Format::kUsda:
      return internal::WriteUsda(scene);
    case Format::kGltf:
      return internal::WriteGltf(scene, /*binary=*/false);
    case Format::kGlb:
      return internal::WriteGltf(scene, /*binary=*/true);
  }
  return {};
}

namespace internal {

std::string FormatMeshUri(const Body& body) {
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(body.mesh->path, error);
  return "file://" + (error ? body.mesh->path : absolute.lexically_normal().string());
}

Eigen::Vector3d CalcMeshFileOffset(const Body& body) {
  return -body.mesh->p_FileCenter * body.mesh_scale;
}

std::string FormatNumber(double x) {
  if (x == 0) return "0";  // also for -0, which some parsers reject
  return fmt::format("{}", x);
}

std::string FormatVector(const Eigen::Vector3d& v, const char* separator) {
  return FormatNumber(v.x()) + separator + FormatNumber(v.y()) + separator + FormatNumber(v.z());
}

std::string FormatRgba(const Rgba& color, const char* separator) {
  return FormatNumber(color.r) + separator + FormatNumber(color.g) + separator +
         FormatNumber(color.b) + separator + FormatNumber(color.a);
}

Eigen::Vector3d CalcRollPitchYaw(const Eigen::Quaterniond& R_WO) {
  const Eigen::Matrix3d R = R_WO.normalized().toRotationMatrix();
  // atan2 keeps full precision near pitch = +-pi/2, where asin would not.
  const double cos_pitch = std::hypot(R(0, 0), R(1, 0));
  const double pitch = std::atan2(-R(2, 0), cos_pitch);
  // Away from gimbal lock the third row gives roll and the first column yaw; at lock only
  // yaw - roll (or yaw + roll) is defined, so roll is taken as 0.
  if (cos_pitch > 1e-12) {
    return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
  }
  return {0.0, pitch, std::atan2(-R(0, 1), R(1, 1))};
}

}  // namespace internal
}  // namespace prs::exporting
