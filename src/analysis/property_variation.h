// Which properties are random, found empirically for `prs check` and Scenario.check(): scenes
// are sampled and, per creation site, every property of its k-th object is compared exactly.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "analysis/scenario_outline.h"
#include "lang/scene.h"

namespace prs::analysis {

/// What one creation site did across the observed scenes.
struct SiteVariation {
  int64_t scenes_present = 0;  // scenes in which the site created at least one object
  int64_t min_objects = 0;     // objects it created in one scene, over the scenes it ran in
  int64_t max_objects = 0;
  std::vector<std::string> varied;  // properties seen with more than one value, first seen first
};

class VariationObserver {
 public:
  /// Compares `scene` with the first scene observed.
  void Observe(const lang::Scene& scene);

  int64_t scenes() const { return scenes_; }
  /// The sites that created objects in at least one scene; absent sites never ran.
  const std::map<SiteKey, SiteVariation>& sites() const { return sites_; }

 private:
  using PropertyValues = std::vector<std::pair<std::string, std::string>>;  // name, exact text
  struct Baseline {
    std::vector<PropertyValues> objects;  // the k-th object's values, from its first scene
  };
  void CompareObject(const lang::SceneObject& object, size_t k, Baseline& baseline,
                     SiteVariation& variation);

  int64_t scenes_ = 0;
  std::map<SiteKey, SiteVariation> sites_;
  std::map<SiteKey, Baseline> baselines_;
};

/// An exact text for a value (numbers with 17 significant digits), equal only for equal values.
std::string FormatExactValue(const lang::Value& value);

}  // namespace prs::analysis
