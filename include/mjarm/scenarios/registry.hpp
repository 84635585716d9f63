#pragma once
/// @file
/// Every scenario mjarm runs, by name: what `mjarm run`, Python's `mjarm.scenarios()` and the
/// sweeps list and look up.

#include <span>
#include <string_view>

#include "mjarm/scenarios/scenario.hpp"

namespace mjarm {

/// Every scenario, in the order the CLI lists them.
std::span<const Scenario* const> scenarios();

/// The scenario called @p name.
/// @throws Error "unknown scenario 'pick-plce'; closest: pick-place; scenarios: …"
const Scenario& find_scenario(std::string_view name);

}  // namespace mjarm
