#include "mjarm/scenarios/registry.hpp"

#include <array>
#include <string>
#include <vector>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/scenarios/bimanual_lift_scenario.hpp"
#include "mjarm/scenarios/docking_scenario.hpp"
#include "mjarm/scenarios/pick_place_scenario.hpp"
#include "mjarm/scenarios/plan_scenario.hpp"
#include "mjarm/scenarios/shelf_pick_scenario.hpp"
#include "mjarm/scenarios/wiping_scenario.hpp"

namespace mjarm {

std::span<const Scenario* const> scenarios() {
  // a new scenario: its files and one line here
  static const std::array<const Scenario*, 6> all{&shelf_pick_scenario(),    &pick_place_scenario(),
                                                  &docking_scenario(),       &plan_scenario(),
                                                  &bimanual_lift_scenario(), &wiping_scenario()};
  return all;
}

const Scenario& find_scenario(std::string_view name) {
  std::vector<std::string> names;
  for (const Scenario* s : scenarios()) {
    if (s->name() == name) return *s;
    names.emplace_back(s->name());
  }
  throw Error(unknown_name_message("scenario", name, names));
}

}  // namespace mjarm
