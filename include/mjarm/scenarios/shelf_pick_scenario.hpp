#pragma once
/// @file
/// The shelf pick as a scenario (`run_shelf_pick`, docs/tasks.md): its parameters, declared.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"
#include "mjarm/tasks/pick_monitor.hpp"
#include "mjarm/tasks/shelf_pick/shelf_pick.hpp"

namespace mjarm {

/// What a shelf pick can be run with; the defaults are `ShelfPickOptions`'.
struct ShelfPickParameters {
  std::string robot = ShelfPickRequest{}.robot;
  std::string controller = ShelfPickRequest{}.controller;
  std::int64_t seed = 1;
  std::optional<Eigen::Vector3d> pick;
  PickCriteria criteria = ShelfPickRequest{}.criteria;
  double control_period = ShelfPickOptions{}.control_period;
  double max_acceleration = ShelfPickOptions{}.max_acceleration;
  double settle_time = ShelfPickOptions{}.settle_time;
  double gain_scale = ShelfPickOptions{}.gain_scale;
};

constexpr auto declared_fields(const ShelfPickParameters*) {
  using S = ShelfPickParameters;
  return declare<S>(
      "shelf-pick", field("robot", &S::robot, "planar2 | panda"),
      field("controller", &S::controller, "ct | osc | task-pd | accel"),
      field("seed", &S::seed, "", Range::non_negative(),
            "draws the pick point when none is given and perturbs the start"),
      field("pick", &S::pick, "m", Range::finite(), "pick point x y z in the world; none: drawn"),
      field("criteria", &S::criteria, "when the pick holds"),
      field("control_period", &S::control_period, "s", Range::closed(0.0, 1.0),
            "a whole multiple of the timestep; 0: one physics step"),
      field("max_acceleration", &S::max_acceleration, "rad/s²", Range::positive(),
            "divergence bound on |joint acceleration|"),
      field("settle_time", &S::settle_time, "s", Range::open_closed(0.0, 60.0),
            "time allowed after the approach to enter the tolerance and hold"),
      field("gain_scale", &S::gain_scale, "", Range::closed(0.01, 100.0),
            "the tuned gains scaled: stiffness × s, damping × √s"));
}

/// The shelf pick's options for @p p (no recording, no video).
ShelfPickOptions shelf_pick_options(const ShelfPickParameters& p);
/// Sets the fields of @p options that @p p covers; the others (recording, video) are kept.
void apply(const ShelfPickParameters& p, ShelfPickOptions& options);
/// The parameters @p options stand for.
ShelfPickParameters shelf_pick_parameters(const ShelfPickOptions& options);

/// The shelf pick of the registry.
const DeclaredScenario<ShelfPickParameters>& shelf_pick_scenario();

}  // namespace mjarm
