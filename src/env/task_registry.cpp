#include "mjarm/env/task_registry.hpp"

#include "mjarm/env/docking_env_task.hpp"
#include "mjarm/env/pick_place_env_task.hpp"
#include "mjarm/env/reach_task.hpp"
#include "mjarm/env/shelf_pick_env_task.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"

namespace mjarm {

namespace {

/// One task: its name, its options struct and the task built from them.
template <class Options, class Task>
struct TaskEntry {
  static std::vector<FieldInfo> parameters() {
    return detail::as_parameters(field_table(Options{}));
  }
  static std::unique_ptr<EnvTask> make(std::string_view name,
                                       const nlohmann::ordered_json& values) {
    Options options;
    set_parameters(options, values, "env " + std::string(name));
    return std::make_unique<Task>(options);
  }
};

/// Calls @p f with the entry of the task called @p name.
template <class F>
auto with_task(std::string_view name, F&& f) {
  if (name == "reach") return f(TaskEntry<ReachOptions, ReachTask>{});
  if (name == "shelf-pick") return f(TaskEntry<ShelfPickEnvOptions, ShelfPickEnvTask>{});
  if (name == "pick-place") return f(TaskEntry<PickPlaceEnvOptions, PickPlaceEnvTask>{});
  if (name == "docking") return f(TaskEntry<DockingEnvOptions, DockingEnvTask>{});
  std::string choices;
  for (const auto& n : env_task_names()) choices += (choices.empty() ? "" : ", ") + n;
  const std::vector<std::string> close = closest_names(name, env_task_names(), 1);
  throw Error("unknown task '" + std::string(name) + "'" +
              (close.empty() ? "" : " (did you mean '" + close.front() + "'?)") +
              "; tasks: " + choices);
}

}  // namespace

const std::vector<std::string>& env_task_names() {
  static const std::vector<std::string> names{"reach", "shelf-pick", "pick-place", "docking"};
  return names;
}

std::vector<FieldInfo> env_task_parameters(std::string_view name) {
  return with_task(name, [](auto entry) { return entry.parameters(); });
}

std::unique_ptr<EnvTask> make_env_task(std::string_view name,
                                       const nlohmann::ordered_json& values) {
  return with_task(name, [&](auto entry) { return entry.make(name, values); });
}

}  // namespace mjarm
