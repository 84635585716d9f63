#pragma once
/// @file
/// Wiping a straight stroke at a constant normal force as a scenario (`run_wiping`,
/// docs/scenarios.md): its parameters, declared. The seed draws the table height the robot
/// believes and the force sensor's noise.

#include <cstdint>

#include "mjarm/fields.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"
#include "mjarm/tasks/wiping/wiping.hpp"

namespace mjarm {

/// What a wipe can be run with; the defaults are `WipingOptions`'.
struct WipingParameters {
  WipingControl control;
  WipingMotion motion;
  WipingPath path;
  WipingForceLoop force_loop;
  WipingSurface surface;
  WipingCriteria criteria;
  std::int64_t seed = 1;
  double max_acceleration = WipingOptions{}.max_acceleration;
};

constexpr auto declared_fields(const WipingParameters*) {
  using S = WipingParameters;
  return declare<S>(
      "wiping", field("control", &S::control, "the force controller and its gains"),
      field("motion", &S::motion, "timing, speed and normal force"),
      field("path", &S::path, "the stroke, and how well the table's height is known"),
      field("force_loop", &S::force_loop, "the explicit loop on the sensor's normal force"),
      field("surface", &S::surface, "table, pad and joint friction"),
      field("criteria", &S::criteria, "when a stroke counts as wiped"),
      field("seed", &S::seed, "", Range::non_negative(),
            "draws the believed table height and the sensor's noise"),
      field("max_acceleration", &S::max_acceleration, "rad/s²", Range::positive(),
            "divergence bound on |joint acceleration|"));
}

/// The wipe's options for @p p (no recording, no video).
WipingOptions wiping_options(const WipingParameters& p);

/// The wipe of the registry.
const DeclaredScenario<WipingParameters>& wiping_scenario();

}  // namespace mjarm
