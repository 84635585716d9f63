#pragma once
/// @file
/// The scripted bimanual lift as a scenario (`run_bimanual_lift` on a `TeleopSession`,
/// docs/teleop.md): its parameters, declared. It draws nothing: the same parameters give the same
/// run.

#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"
#include "mjarm/sim/simulation_options.hpp"
#include "mjarm/teleop/bimanual_lift.hpp"

namespace mjarm {

/// What a bimanual lift can be run with.
struct BimanualLiftParameters {
  std::string model = "dual_arm_box";  ///< a bundled scene with two hands and the free body
  SimulationMode mode = SimulationMode::position;
  BimanualLiftOptions lift;  ///< geometry, timing, tolerance
};

constexpr auto declared_fields(const BimanualLiftParameters*) {
  using S = BimanualLiftParameters;
  return declare<S>("bimanual-lift",
                    field("model", &S::model, "bundled scene with two hands and the bar"),
                    field("mode", &S::mode, "how the arms are driven"),
                    field("lift", &S::lift, "the script: grasp points, heights, times, tolerance"));
}

/// The bimanual lift of the registry.
const DeclaredScenario<BimanualLiftParameters>& bimanual_lift_scenario();

}  // namespace mjarm
