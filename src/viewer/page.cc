// The viewer page and the records it shows: the embedded template filled with a title, a
// configuration (server mode, or the scenes embedded) and the script (a link, or inline).
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "output/scene_json.h"
#include "shapes/mesh_file.h"
#include "viewer/assets.h"
#include "viewer/viewer.h"

namespace prs::viewer {
namespace {

using nlohmann::json;

// The workspace's vertices, or null when there is nothing bounded to outline.
json MakeWorkspaceJson(const lang::Scene& scene) {
  if (!scene.workspace || scene.workspace->IsEmpty() || !scene.workspace->IsBounded())
    return nullptr;
  json vertices = json::array();
  try {
    for (const Eigen::Vector3d& v : scene.workspace->CalcVertices())
      vertices.push_back({v.x(), v.y(), v.z()});
  } catch (const std::domain_error&) {  // unbounded after all: no outline
    return nullptr;
  }
  return {{"dimension", scene.workspace->dimension()}, {"vertices", std::move(vertices)}};
}

// A mesh's triangles for three.js, in its frame at scale 1: {"vertices": [x, y, z, ...],
// "triangles": [i, j, k, ...]} (flat arrays).
json MakeMeshJson(const shapes::MeshShape& mesh) {
  json vertices = json::array(), triangles = json::array();
  for (const Eigen::Vector3d& p : mesh.mesh.vertices_O) {
    for (int i = 0; i < 3; ++i) vertices.push_back(p[i]);
  }
  for (const Eigen::Vector3i& t : mesh.mesh.triangles) {
    for (int i = 0; i < 3; ++i) triangles.push_back(t[i]);
  }
  return {{"vertices", std::move(vertices)}, {"triangles", std::move(triangles)}};
}

// The meshes of a scene by the path its line records, so that the page draws them.
json MakeMeshesJson(const lang::Scene& scene) {
  json meshes = json::object();
  for (const lang::SceneObject& object : scene.objects) {
    if (object.mesh && !meshes.contains(object.mesh->path))
      meshes[object.mesh->path] = MakeMeshJson(*object.mesh);
  }
  return meshes;
}

// The same for a line read back from a scenes file: each mesh re-read from its recorded path;
// one that cannot be read is left out (the page then draws the object's box).
json MakeMeshesJsonOfLine(std::string_view line) {
  json meshes = json::object();
  const json scene = json::parse(line, nullptr, /*allow_exceptions=*/false);
  const auto objects = scene.is_object() ? scene.find("objects") : scene.end();
  if (!scene.is_object() || objects == scene.end() || !objects->is_array()) return meshes;
  for (const json& object : *objects) {
    const auto properties = object.is_object() ? object.find("properties") : object.end();
    if (!object.is_object() || properties == object.end() || !properties->is_object()) continue;
    const auto shape = properties->find("shape");
    if (shape == properties->end() || !shape->is_object()) continue;
    const auto mesh = shape->find("mesh"), path = shape->find("path");
    if (mesh == shape->end() || path == shape->end() || !mesh->is_string() || !path->is_string() ||
        meshes.contains(path->get<std::string>()))
      continue;
    std::string problem;
    if (auto loaded = shapes::LoadRecordedMesh(mesh->get<std::string>(), path->get<std::string>(), problem))
      meshes[path->get<std::string>()] = MakeMeshJson(*loaded);
  }
  return meshes;
}

std::string EscapeHtml(std::string_view text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&#39;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

void ReplaceAll(std::string& text, std::string_view from, std::string_view to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

// JSON inside <script type="application/json">: '<' only occurs in strings, where \u003c
// means the same, so no "</script>" or "<!--" can end or confuse the element.
std::string EscapeJsonForScript(std::string text) {
  ReplaceAll(text, "<", "\\u003c");
  return text;
}

// The bundle inline: "</script" and "<!--" only occur in its strings and regular
// expressions, where "<\/" and "<\!" mean the same.
std::string EscapeScriptForInline(std::string_view script) {
  std::string text(script);
  ReplaceAll(text, "</script", "<\\/script");
  ReplaceAll(text, "<!--", "<\\!--");
  return text;
}

std::string FillTemplate(const PageInfo& info, const json& config, const std::string& script) {
  std::string page(PageTemplate());
  ReplaceAll(page, "@PRS_TITLE@", EscapeHtml(info.title));
  ReplaceAll(page, "@PRS_CONFIG@", EscapeJsonForScript(config.dump()));
  ReplaceAll(page, "@PRS_SCRIPT@", script);
  return page;
}

json MakeConfig(const PageInfo& info, const char* mode) {
  // Seeds and indices go as strings: JavaScript numbers hold only 53 bits.
  return {{"mode", mode},
          {"file", info.title},
          {"seed", std::to_string(info.seed)},
          {"index", std::to_string(info.index)}};
}

}  // namespace

std::string FormatViewRecord(const sampling::SampledScene& sampled) {
  const json record = {{"line", output::FormatSceneJson(sampled)},
                       {"workspace", MakeWorkspaceJson(sampled.scene)},
                       {"meshes", MakeMeshesJson(sampled.scene)}};
  return record.dump();
}

std::string FormatViewRecordOfLine(std::string_view line) {
  const json record = {{"line", line}, {"workspace", nullptr}, {"meshes", MakeMeshesJsonOfLine(line)}};
  return record.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string FormatErrorRecord(std::string_view id, std::string_view message) {
  const json record = {{"error", {{"id", id}, {"message", message}}}};
  return record.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string MakeServedPage(const PageInfo& info) {
  return FillTemplate(info, MakeConfig(info, "server"), "<script src=\"viewer.js\"></script>");
}

std::string MakeStandalonePage(const PageInfo& info, const std::vector<std::string>& records) {
  json config = MakeConfig(info, "embedded");
  config["start"] = std::to_string(info.index);
  json embedded = json::array();
  for (const std::string& record : records) embedded.push_back(json::parse(record));
  config["records"] = std::move(embedded);
  const std::string script = "<script>" + EscapeScriptForInline(ViewerScript()) + "</script>";
  return FillTemplate(info, config, script);
}

}  // namespace prs::viewer
