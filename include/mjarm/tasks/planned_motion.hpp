#pragma once
/// @file
/// A planned motion tracked in simulation: a timed joint trajectory (the waypoint planner's) on
/// a shelf-pick robot's torque model, followed under one of its controllers, with the tool's
/// tracking error (`mjarm run plan`, the `plan` scenario; docs/planning.md).

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "mjarm/model/chain.hpp"
#include "mjarm/planning/joint_spline.hpp"
#include "mjarm/planning/planned_reference.hpp"
#include "mjarm/planning/waypoint_path_plan.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/shelf_pick/plan.hpp"

namespace mjarm {

/// How the plan is tracked.
struct TrackingOptions {
  std::string controller = "osc";  ///< ct | osc | task-pd | accel (the shelf pick's)
  double settle_time = 1.0;        ///< the final target held after the plan ends [s]
  double control_period = 0.0;     ///< [s]; 0: one physics step
  double max_acceleration = 1e6;   ///< divergence bound on |q̈| [rad/s²]
};

/// What the tracking did.
struct PlannedMotionRun {
  RunResult run;
  TrackingError tracking;
  double control_period = 0.0;  ///< [s]
};

/// Simulates @p trajectory on @p chain (the torque model of @p robot) from @p start_qpos, at
/// rest, under the controller named in @p options, until the plan and the settle time are over.
/// @throws Error for an unknown controller, a negative settle time, or as `Simulation`
PlannedMotionRun track_planned_motion(const Chain& chain, const ShelfPickRobot& robot,
                                      const Eigen::VectorXd& start_qpos,
                                      const JointSpline& trajectory,
                                      const TrackingOptions& options);

/// A whole planned motion, from a waypoint file to the tracking.
struct PlannedMotionOptions {
  std::string robot = "panda";      ///< planar2 | panda (the shelf pick's robots)
  std::filesystem::path waypoints;  ///< JSON or CSV waypoint file (docs/planning.md)
  std::uint64_t seed = 1;           ///< IK branches and detours
  double min_sigma = PlanOptions{}.checks.min_singular_value;  ///< accepted σmin of the Jacobian
  TrackingOptions tracking;
};

struct PlannedMotionReport {
  std::string robot;
  WaypointPathPlan plan;
  PlannedMotionRun tracked;  ///< empty when there was no plan
  bool planned() const noexcept { return plan.result.ok(); }
};

/// Plans @p options' waypoints on the robot's torque model from its "home" keyframe (qpos0 when
/// it has none), and tracks the plan when there is one.
/// @throws Error for an unknown robot or controller, a waypoint file that cannot be read, or as
///         `track_planned_motion`
PlannedMotionReport run_planned_motion(const PlannedMotionOptions& options);

}  // namespace mjarm
