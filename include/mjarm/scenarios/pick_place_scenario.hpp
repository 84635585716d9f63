#pragma once
/// @file
/// The pick and place as a scenario (`run_pick_place`, docs/pick_place.md): its parameters,
/// declared.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"
#include "mjarm/tasks/pick_place/pick_place.hpp"

namespace mjarm {

/// What a pick and place can be run with; the defaults are `PickPlaceOptions`'.
struct PickPlaceParameters {
  std::string robot = PickPlaceOptions{}.robot;
  GraspKind grasp = PickPlaceOptions{}.grasp;
  SimulationMode mode = PickPlaceOptions{}.mode;
  std::int64_t seed = 1;
  std::optional<std::array<double, 2>> object;  ///< object centre x y [m]; none: drawn
  std::optional<std::array<double, 2>> target;  ///< target x y [m]; none: drawn
  std::optional<double> object_size;            ///< cube half extent [m]; none: drawn
  bool classic = PickPlaceOptions{}.classic;
  PickPlaceRanges ranges = PickPlaceOptions{}.ranges;
  PickPlaceMotion motion = PickPlaceOptions{}.motion;
  PickPlaceCriteria criteria = PickPlaceOptions{}.criteria;
  WeldGraspOptions weld = PickPlaceOptions{}.weld;
  double grasp_force = PickPlaceOptions{}.grasp_force;
  int noslip = PickPlaceOptions{}.noslip_iterations;
  double impratio = PickPlaceOptions{}.impratio;
  double control_period = PickPlaceOptions{}.control_period;
  double max_acceleration = PickPlaceOptions{}.max_acceleration;
};

constexpr auto declared_fields(const PickPlaceParameters*) {
  using S = PickPlaceParameters;
  return declare<S>(
      "pick-place", field("robot", &S::robot, "arm6 | panda_hand"),
      field("grasp", &S::grasp, "how the object is held"),
      field("mode", &S::mode, "how the arm is driven: position servos or torques"),
      field("seed", &S::seed, "", Range::non_negative(),
            "draws the object, its size, mass, friction and the target"),
      field("object", &S::object, "m", Range::finite(), "object centre x y; none: drawn"),
      field("target", &S::target, "m", Range::finite(), "target x y; none: drawn"),
      field("object_size", &S::object_size, "m", Range::closed(0.005, 0.05),
            "cube half extent; none: drawn"),
      field("classic", &S::classic, "the classic scene edits (7.5 mm cube, short fingers)"),
      field("ranges", &S::ranges, "what the seed draws the object and target from"),
      field("motion", &S::motion, "heights, dwell and grip times, speed limits"),
      field("criteria", &S::criteria, "what the trial is judged by"),
      field("weld", &S::weld, "the weld of the weld grasp"),
      field("grasp_force", &S::grasp_force, "N", Range::positive(),
            "the fingers' squeeze once touching"),
      field("noslip", &S::noslip, "", Range::non_negative(),
            "MuJoCo's noslip solver iterations (0: off)"),
      field("impratio", &S::impratio, "", Range::at_least(1.0), "MuJoCo's impratio"),
      field("control_period", &S::control_period, "s", Range::closed(0.0, 1.0),
            "a whole multiple of the timestep; 0: one physics step"),
      field("max_acceleration", &S::max_acceleration, "rad/s²", Range::positive(),
            "divergence bound on |joint acceleration|"));
}

/// The pick and place's options for @p p (no recording, no video).
PickPlaceOptions pick_place_options(const PickPlaceParameters& p);
/// Sets the fields of @p options that @p p covers; the others (recording, video) are kept.
void apply(const PickPlaceParameters& p, PickPlaceOptions& options);
/// The parameters @p options stand for.
PickPlaceParameters pick_place_parameters(const PickPlaceOptions& options);

/// The pick and place of the registry.
const DeclaredScenario<PickPlaceParameters>& pick_place_scenario();

}  // namespace mjarm
