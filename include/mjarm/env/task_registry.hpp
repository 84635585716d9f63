#pragma once
/// @file
/// The environment tasks by name: "reach", "shelf-pick", "pick-place", "docking", each with its
/// declared options as parameters (names as a command line writes them, like a scenario's).

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/env/env_task.hpp"
#include "mjarm/field_table.hpp"

namespace mjarm {

/// The task names, in a fixed order.
const std::vector<std::string>& env_task_names();

/// The options of the task called @p name as parameters: every declared field of its options
/// struct (`DockingEnvOptions`, …; nested ones flattened: `criteria.max-force`) with its kind,
/// unit, range, default and doc. The fields it shares with the scenario it wraps have the
/// scenario's names (`robot`, `criteria.tolerance`, `motion.start-height`).
/// @throws Error naming @p name, the closest names and the choices.
std::vector<FieldInfo> env_task_parameters(std::string_view name);

/// A new task called @p name with its default options, @p values (an object of parameter
/// names, dashes or underscores, to values) set on them, each checked.
/// @throws Error naming @p name, the closest names and the choices; "env docking: unknown
///         parameter 'criteria.max-forse'; closest: criteria.max-force"; a value of the wrong
///         kind or out of range, named; options the task refuses.
std::unique_ptr<EnvTask> make_env_task(
    std::string_view name, const nlohmann::ordered_json& values = nlohmann::ordered_json::object());

}  // namespace mjarm
