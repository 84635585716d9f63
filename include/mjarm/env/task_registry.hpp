#pragma once
/// @file
/// The environment tasks by name: "reach", "shelf-pick", "pick-place", "docking".

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/env/env_task.hpp"

namespace mjarm {

/// The task names, in a fixed order.
const std::vector<std::string>& env_task_names();

/// A new task called @p name with its default options.
/// @throws Error naming @p name, the closest names and the choices.
std::unique_ptr<EnvTask> make_env_task(std::string_view name);

}  // namespace mjarm
