#pragma once
/// @file
/// The planned motion as a scenario (`run_planned_motion`, docs/planning.md): its parameters,
/// declared. It draws nothing but the planner's branches and detours (its seed).

#include <cstdint>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/scenarios/declared_scenario.hpp"
#include "mjarm/tasks/planned_motion.hpp"

namespace mjarm {

/// What a planned motion can be run with; the defaults are `PlannedMotionOptions`'.
struct PlanParameters {
  std::string robot = PlannedMotionOptions{}.robot;
  std::string waypoints;  ///< the waypoint file (JSON or CSV)
  std::string scene;      ///< a scene file of obstacles (empty: none)
  std::string controller = TrackingOptions{}.controller;
  std::int64_t seed = 1;
  double min_sigma = PlannedMotionOptions{}.min_sigma;
  double settle_time = TrackingOptions{}.settle_time;
  double control_period = TrackingOptions{}.control_period;
  double max_acceleration = TrackingOptions{}.max_acceleration;
};

constexpr auto declared_fields(const PlanParameters*) {
  using S = PlanParameters;
  return declare<S>(
      "plan", field("robot", &S::robot, "planar2 | panda"),
      field("waypoints", &S::waypoints, "the waypoint file, JSON or CSV (docs/planning.md)"),
      field("scene", &S::scene,
            "a scene file whose fixtures and objects are obstacles (empty: the robot alone)"),
      field("controller", &S::controller, "ct | osc | task-pd | accel"),
      field("seed", &S::seed, "", Range::non_negative(), "the IK branches and detours"),
      field("min_sigma", &S::min_sigma, "", Range::non_negative(),
            "smallest accepted singular value of the Jacobian"),
      field("settle_time", &S::settle_time, "s", Range::closed(0.0, 60.0),
            "the final target held after the plan ends"),
      field("control_period", &S::control_period, "s", Range::closed(0.0, 1.0),
            "a whole multiple of the timestep; 0: one physics step"),
      field("max_acceleration", &S::max_acceleration, "rad/s²", Range::positive(),
            "divergence bound on |joint acceleration|"));
}

/// The planned motion's options for @p p.
PlannedMotionOptions planned_motion_options(const PlanParameters& p);

/// The planned motion of the registry.
const DeclaredScenario<PlanParameters>& plan_scenario();

}  // namespace mjarm
