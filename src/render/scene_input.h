// What the renderer draws, made from a sampled scene (lang::Scene) or from one line of a
// scenes file (spec §8 JSON): shapes from `shape_type` and the class, colours from `color`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "geometry/region.h"
#include "lang/scene.h"
#include "render/render.h"

namespace prs::render {

/// The objects of a sampled scene, and its workspace's edges when it has one. Colours that do
/// not parse are left at the default and their texts added to `unknown_colors` (if not null).
RenderScene MakeRenderScene(const lang::Scene& scene,
                            std::vector<std::string>* unknown_colors = nullptr);

/// One JSON scene (a line of `prs sample` output). Throws std::invalid_argument saying which
/// object and field is wrong when the text is not a prs-scene/1 object. There is no workspace
/// in the JSON format, so none is drawn.
RenderScene ParseRenderSceneJson(std::string_view line,
                                 std::vector<std::string>* unknown_colors = nullptr);

/// The edges of a bounded polyhedron, polygon or segment (world frame). Empty for a point, an
/// empty or an unbounded region.
std::vector<Segment> CalcOutlineEdges(const geometry::ConvexRegion& region);

}  // namespace prs::render
