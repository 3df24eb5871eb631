// Scenes read back from spec §8 JSON lines (`prs sample -o`, `--save-failures`) as the sampler's
// own SampledScene, so that a saved scene can be run again by any controller (`prs test
// SCENES.jsonl`, probrobscene.read_scenes). The inverse of scene_json.h.
#pragma once

#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "sampling/sampler.h"

namespace prs::output {

/// Reads scene lines. Objects point at their classes (SceneObject::cls): a scene line names
/// only its classes, so the reader makes one lang::ClassInfo per name (no parent, no defaults)
/// and keeps them in classes(), which must outlive the scenes read. Not thread-safe.
class SceneReader {
 public:
  SceneReader();

  /// The scene of one spec §8 line: seed, index, attempts, objects (name, class, pose,
  /// dimensions, properties in the line's order, shapes: meshes loaded from their recorded
  /// path, built-in shapes made at the object's size), params and settled_s. The scene written
  /// again with FormatSceneJson is the same line for a line `prs sample` wrote. A mesh whose
  /// file cannot be read leaves the object a box, with a sentence in `warnings` (optional).
  /// Throws std::invalid_argument saying what is wrong ("not valid JSON", "object 2 has no
  /// \"class\"", ...).
  sampling::SampledScene Read(std::string_view line, std::vector<std::string>* warnings = nullptr);

  /// The program that owns the classes of the scenes read (it holds nothing else).
  std::shared_ptr<const lang::CompiledProgram> classes() const { return classes_; }

 private:
  const lang::ClassInfo* FindOrMakeClass(const std::string& name);
  lang::SceneObject ReadObject(const nlohmann::ordered_json& object, int index,
                               std::vector<std::string>* warnings);
  static void SetShape(lang::SceneObject& object);

  std::shared_ptr<lang::CompiledProgram> classes_;
  std::unordered_map<std::string, const lang::ClassInfo*> by_name_;
};

}  // namespace prs::output
