// Loads a bundled arm from the installed share directory and prints its degrees of freedom, and
// the JSON of a declared options struct (mjarm/fields_json.hpp needs nlohmann/json, which the
// package's config finds for its users).
#include <iostream>

#include "mjarm/fields_json.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/simulation_options.hpp"

int main() {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  std::cout << robot.name() << " nq=" << robot.nq() << "\n";
  const auto options = mjarm::fields_to_json(mjarm::SimulationOptions{});
  std::cout << options.dump() << "\n";
  return robot.nq() >= 7 && options.contains("mode") ? 0 : 1;
}
