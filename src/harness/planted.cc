// The planted-failure controllers: test controllers for failure searches (docs/search.md) that
// fail exactly when the first Cube's centre lies within a small disk of the table (world x, y),
// and report as their score the distance to that disk. On examples/table_cube.prs the disks
// hold about 1 % and 0.1 % of the scenes, so a search's speed-up over i.i.d. sampling can be
// measured against a failure whose place and rate are known.
#include <fmt/format.h>

#include "harness/registry.h"

namespace prs::harness {
namespace {

bool IsCube(const lang::SceneObject& object) {
  for (const lang::ClassInfo* cls = object.cls; cls; cls = cls->parent) {
    if (cls->name == "Cube") return true;
  }
  return false;
}

class PlantedController : public Controller {
 public:
  explicit PlantedController(PlantedFailure failure) : failure_(failure) {}

  EpisodeResult RunEpisode(const sampling::SampledScene& sampled, const std::string&) override {
    const lang::Scene& scene = sampled.scene;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      if (!IsCube(scene.objects[i])) continue;
      const Eigen::Vector2d p_xy = scene.objects[i].p_WO.head<2>();
      const double distance_m = (p_xy - failure_.p_center_xy).norm() - failure_.radius_m;
      const std::string cube = scene.objects[i].DisplayName(static_cast<int>(i));
      EpisodeResult result;
      result.score = distance_m;
      result.extra = {{"cube", cube}, {"distance_to_region_m", distance_m}};
      if (distance_m <= 0) {
        result.outcome = "planted-failure";
        result.detail = fmt::format(
            "{} is inside the planted failure disk (r = {} m around "
            "({}, {}))",
            cube, failure_.radius_m, failure_.p_center_xy.x(), failure_.p_center_xy.y());
      } else {
        result.outcome = "success";
        result.detail =
            fmt::format("{} is {:.3f} m from the planted failure disk", cube, distance_m);
      }
      return result;
    }
    return {"missing-object", "the scene needs a Cube"};
  }

 private:
  PlantedFailure failure_;
};

}  // namespace

PlantedFailure PlantedOnePercent() { return {{-0.8, 0.3}, 0.090}; }
PlantedFailure PlantedOnePermille() { return {{-0.8, 0.3}, 0.0288}; }

std::unique_ptr<Controller> MakePlantedController(const PlantedFailure& failure) {
  return std::make_unique<PlantedController>(failure);
}

}  // namespace prs::harness
