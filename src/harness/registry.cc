// The controller registry: a name-ordered map behind a mutex, with the built-ins added the
// first time it is used (not from static initialisers, which a static library may drop).
#include "harness/registry.h"

#include <map>
#include <mutex>
#include <stdexcept>

namespace prs::harness {
namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::string, ControllerInfo> by_name;  // nodes are stable: FindController's pointers
};

void AddLocked(Registry& registry, std::string name, std::string description,
               ControllerFactory factory) {
  if (!IsOutcomeName(name)) {
    throw std::invalid_argument("RegisterController: '" + name +
                                "' is not a lowercase-hyphenated name");
  }
  if (!factory) throw std::invalid_argument("RegisterController: no factory for '" + name + "'");
  if (registry.by_name.contains(name)) {
    throw std::invalid_argument("RegisterController: '" + name + "' is already registered");
  }
  ControllerInfo info{name, std::move(description), std::move(factory)};
  registry.by_name.emplace(std::move(name), std::move(info));
}

Registry& GetRegistry() {
  static Registry* registry = [] {
    auto* built = new Registry;  // never destroyed: controllers may be looked up at exit
    AddLocked(*built, "demo-reach",
              "a demonstration without simulation, not the paper's controller: success when "
              "each Cube is 0.25 to 0.855 m from the nearest Robot, else no-path",
              MakeDemoReachController);
    AddLocked(*built, "planted-1-percent",
              "a test controller for failure searches: fails iff the Cube lies within 9 cm of "
              "(-0.8, 0.3) (about 1 % of table_cube.prs); score = distance to that disk",
              [] { return MakePlantedController(PlantedOnePercent()); });
    AddLocked(*built, "planted-1-permille",
              "a test controller for failure searches: fails iff the Cube lies within 2.88 cm "
              "of (-0.8, 0.3) (about 0.1 % of table_cube.prs); score = distance to that disk",
              [] { return MakePlantedController(PlantedOnePermille()); });
    return built;
  }();
  return *registry;
}

}  // namespace

void RegisterController(std::string name, std::string description, ControllerFactory factory) {
  Registry& registry = GetRegistry();
  std::lock_guard lock(registry.mutex);
  AddLocked(registry, std::move(name), std::move(description), std::move(factory));
}

const ControllerInfo* FindController(const std::string& name) {
  Registry& registry = GetRegistry();
  std::lock_guard lock(registry.mutex);
  const auto found = registry.by_name.find(name);
  return found == registry.by_name.end() ? nullptr : &found->second;
}

std::vector<ControllerInfo> ListControllers() {
  Registry& registry = GetRegistry();
  std::lock_guard lock(registry.mutex);
  std::vector<ControllerInfo> list;
  for (const auto& [name, info] : registry.by_name) list.push_back(info);
  return list;
}

}  // namespace prs::harness
