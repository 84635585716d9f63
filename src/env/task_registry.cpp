#include "mjarm/env/task_registry.hpp"

#include "mjarm/env/docking_env_task.hpp"
#include "mjarm/env/pick_place_env_task.hpp"
#include "mjarm/env/reach_task.hpp"
#include "mjarm/env/shelf_pick_env_task.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {

const std::vector<std::string>& env_task_names() {
  static const std::vector<std::string> names{"reach", "shelf-pick", "pick-place", "docking"};
  return names;
}

std::unique_ptr<EnvTask> make_env_task(std::string_view name) {
  if (name == "reach") return std::make_unique<ReachTask>();
  if (name == "shelf-pick") return std::make_unique<ShelfPickEnvTask>();
  if (name == "pick-place") return std::make_unique<PickPlaceEnvTask>();
  if (name == "docking") return std::make_unique<DockingEnvTask>();
  std::string choices;
  for (const auto& n : env_task_names()) choices += (choices.empty() ? "" : ", ") + n;
  const std::vector<std::string> close = closest_names(name, env_task_names(), 1);
  throw Error("unknown task '" + std::string(name) + "'" +
              (close.empty() ? "" : " (did you mean '" + close.front() + "'?)") +
              "; tasks: " + choices);
}

}  // namespace mjarm
