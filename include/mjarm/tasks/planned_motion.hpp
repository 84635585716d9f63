#pragma once
/// @file
/// A planned motion tracked in simulation: a timed joint trajectory (the waypoint planner's) on
/// a shelf-pick robot's torque model, alone or in a scene file's world of obstacles, followed
/// under one of its controllers, with the tool's tracking error and every contact the robot made
/// (`mjarm run plan`, the `plan` scenario; docs/planning.md).

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>

#include "mjarm/model/chain.hpp"
#include "mjarm/planning/joint_spline.hpp"
#include "mjarm/planning/planned_reference.hpp"
#include "mjarm/planning/robot_contacts.hpp"
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

/// The contacts the robot made while it was tracked, as `RobotContacts` counts them (a geom the
/// chain moves touching anything but an adjacent link).
struct TrackingContacts {
  std::int64_t ticks = 0;  ///< control ticks that began with a counted contact
  double first_time = std::numeric_limits<double>::quiet_NaN();  ///< [s] of the first
  RobotContact first;      ///< the deepest contact of that first tick
  RobotContact deepest;    ///< the deepest of the run
  std::string first_pair;  ///< "geom 'panda/link5_c' and geom 'wall'" (empty: none)
  bool any() const noexcept { return ticks > 0; }
};

/// What the tracking did.
struct PlannedMotionRun {
  RunResult run;
  TrackingError tracking;
  TrackingContacts contacts;
  double control_period = 0.0;  ///< [s]
};

/// Simulates @p trajectory on @p chain (the torque model of @p robot) from @p start_qpos, at
/// rest, under the controller named in @p options, until the plan and the settle time are over,
/// and records the contacts the robot makes on the way.
/// @throws Error for an unknown controller, a negative settle time, or as `Simulation`
PlannedMotionRun track_planned_motion(const Chain& chain, const ShelfPickRobot& robot,
                                      const Eigen::VectorXd& start_qpos,
                                      const JointSpline& trajectory,
                                      const TrackingOptions& options);

/// The model a planned motion runs on: the robot's torque model alone, or placed at the origin
/// (named by the robot, so its names get the prefix "panda/") in a scene file's world, whose
/// fixtures, objects and other robots are obstacles to the plan and to the tracking.
struct PlannedMotionWorld {
  Robot model;
  std::string frame;  ///< the tool's site in that model
};

/// @p robot's world with the scene file @p scene (empty: none).
/// @throws Error for a scene file that cannot be read or already holds a robot of that name
PlannedMotionWorld planned_motion_world(const ShelfPickRobot& robot,
                                        const std::filesystem::path& scene);

/// A whole planned motion, from a waypoint file to the tracking.
struct PlannedMotionOptions {
  std::string robot = "panda";      ///< planar2 | panda (the shelf pick's robots)
  std::filesystem::path waypoints;  ///< JSON or CSV waypoint file (docs/planning.md)
  std::filesystem::path scene;      ///< a scene file of obstacles (empty: none)
  std::uint64_t seed = 1;           ///< IK branches and detours
  double min_sigma = PlanOptions{}.checks.min_singular_value;  ///< accepted σmin of the Jacobian
  TrackingOptions tracking;
};

struct PlannedMotionReport {
  std::string robot;
  WaypointPathPlan plan;
  PlannedMotionRun tracked;  ///< empty when there was no plan
  bool planned() const noexcept { return plan.result.ok(); }
  /// Planned, tracked to the end and without touching anything.
  bool ok() const noexcept { return planned() && tracked.run.ok() && !tracked.contacts.any(); }
};

/// Plans @p options' waypoints on the robot's world (`planned_motion_world`) from its "home"
/// keyframe (qpos0 when it has none), and tracks the plan when there is one.
/// @throws Error for an unknown robot or controller, a waypoint or scene file that cannot be
///         read, or as `track_planned_motion`
PlannedMotionReport run_planned_motion(const PlannedMotionOptions& options);

}  // namespace mjarm
