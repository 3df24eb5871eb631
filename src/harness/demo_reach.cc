// `demo-reach`: a demonstration of the harness without any simulation, deterministic and
// instant. It is NOT the paper's controller: it only checks, from the sampled scene itself,
// that every Cube lies within a Franka Panda's reach (0.25 to 0.855 m) of the nearest Robot.
#include <fmt/format.h>

#include <limits>
#include <optional>

#include "harness/registry.h"

namespace prs::harness {
namespace {

constexpr double kPandaReach_m = 0.855;  // Franka Emika's stated maximum reach
// Closer than this to the base the arm folds into itself (the paper's "too close" no-path).
constexpr double kPandaMinReach_m = 0.25;

bool IsInstanceOf(const lang::SceneObject& object, const std::string& class_name) {
  for (const lang::ClassInfo* cls = object.cls; cls; cls = cls->parent) {
    if (cls->name == class_name) return true;
  }
  return false;
}

struct Reach {
  double distance_m = std::numeric_limits<double>::infinity();
  std::string robot;
};

// The Robot nearest to `p_WC` (base to cube centre, metres).
Reach FindNearestRobot(const lang::Scene& scene, const Eigen::Vector3d& p_WC) {
  Reach nearest;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const lang::SceneObject& robot = scene.objects[i];
    if (!IsInstanceOf(robot, "Robot")) continue;
    const double distance_m = (robot.p_WO - p_WC).norm();
    if (distance_m < nearest.distance_m) nearest = {distance_m, robot.DisplayName(int(i))};
  }
  return nearest;
}

EpisodeResult ClassifyReach(const std::string& cube, const Reach& reach) {
  const nlohmann::json extra = {
      {"cube", cube}, {"robot", reach.robot}, {"distance_m", reach.distance_m}};
  if (reach.distance_m > kPandaReach_m) {
    return {"no-path",
            fmt::format("{} is {:.3f} m from the nearest Robot ({}), beyond the arm's {} m reach",
                        cube, reach.distance_m, reach.robot, kPandaReach_m),
            extra};
  }
  if (reach.distance_m < kPandaMinReach_m) {
    return {"no-path",
            fmt::format("{} is {:.3f} m from {}, too close to the base (under {} m)", cube,
                        reach.distance_m, reach.robot, kPandaMinReach_m),
            extra};
  }
  return {"success",
          fmt::format("{} is {:.3f} m from {}, within the arm's reach", cube, reach.distance_m,
                      reach.robot),
          extra};
}

class DemoReachController : public Controller {
 public:
  // The first Cube out of reach decides; every Cube in reach is a success.
  EpisodeResult RunEpisode(const sampling::SampledScene& sampled, const std::string&) override {
    const lang::Scene& scene = sampled.scene;
    std::optional<EpisodeResult> result;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      if (!IsInstanceOf(scene.objects[i], "Cube")) continue;
      const Reach reach = FindNearestRobot(scene, scene.objects[i].p_WO);
      if (reach.robot.empty()) break;
      result = ClassifyReach(scene.objects[i].DisplayName(int(i)), reach);
      if (result->outcome != "success") return *result;
    }
    if (!result) return {"missing-object", "the scene needs at least one Cube and one Robot"};
    return *result;
  }
};

}  // namespace

std::unique_ptr<Controller> MakeDemoReachController() {
  return std::make_unique<DemoReachController>();
}

}  // namespace prs::harness
