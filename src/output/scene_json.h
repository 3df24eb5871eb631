// Scene output in the spec §8 format ("prs-scene/1"), one JSON object per scene.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sampling/sampler.h"

namespace prs::output {

/// Renders one sampled scene as a single line of JSON (no trailing newline).
std::string FormatSceneJson(const sampling::SampledScene& sampled);
/// Appends the same line to `out`.
void AppendSceneJson(const sampling::SampledScene& sampled, std::string& out);

/// Writes a finite double exactly as fmt's "{}" does (the shortest digits that read back as
/// the same double) and returns the end; at most 24 characters. The scene writer's numbers.
char* WriteShortest(double x, char* out);

/// A scene's features for failure reports and datasets' provenance (docs/search.md, "Failure
/// maps"): per object, "NAME.x", "NAME.y", "NAME.z" (metres, world frame) and "NAME.yaw" (the
/// heading of its x axis in the world's xy plane, radians), in scene order.
std::vector<std::pair<std::string, double>> CalcSceneFeatures(const lang::Scene& scene);

/// True for the properties §8 writes outside "properties" (position, orientation, width,
/// length, height, yaw, pitch, roll).
bool IsCoreProperty(std::string_view name);

}  // namespace prs::output
