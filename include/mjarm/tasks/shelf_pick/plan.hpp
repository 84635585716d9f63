#pragma once
/// @file
/// The set-up of a shelf pick before anything runs: which robots and controllers exist, what a
/// seed draws (the pick point when none is given, and a small perturbation of the start), the
/// reachability check with a message that gives the arm's reach, and the IK joint target.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/ik/result.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/random.hpp"
#include "mjarm/tasks/arm_reach.hpp"
#include "mjarm/tasks/shelf_pick/task.hpp"

namespace mjarm {

/// A robot the shelf pick knows: its torque-motor model, tool frame and the constants of the
/// scenario on it. Positions are world coordinates [m].
struct ShelfPickRobot {
  std::string name;   ///< what the user types ("planar2")
  std::string model;  ///< bundled torque-motor model ("planar2_torque")
  std::string frame;  ///< the tool tip (site)
  /// Position-only task (planar2): the tool orientation is free. Otherwise the tool keeps its
  /// orientation at the home keyframe (pointing down on the panda).
  bool position_only = false;
  /// When set, the arm moves in the plane through the shoulder with this normal (planar2: y).
  std::optional<Eigen::Vector3d> plane_normal;
  Eigen::Vector3d pick_center;      ///< centre of the box a seed draws pick points from
  Eigen::Vector3d pick_half_width;  ///< half-sizes of that box (0 along a plane normal)
  double start_perturbation = 0.0;  ///< each start joint is home ± this, uniform [rad]
  double max_speed = 1.0;           ///< peak tip speed of the approach reference [m/s]
  double max_acceleration = 10.0;   ///< peak tip acceleration of the approach reference [m/s²]
  double min_approach_time = 0.1;   ///< shortest approach [s]
  /// The approach is stretched until the joint move needs at most this fraction of each motor's
  /// torque limit (`torque_feasible_duration`), leaving the rest for the feedback.
  double torque_fraction = 0.7;
};

/// The robots, in a fixed order: planar2, panda.
const std::vector<ShelfPickRobot>& shelf_pick_robots();
/// The robot called @p name.
/// @throws Error "unknown robot 'x'; choices: planar2, panda".
const ShelfPickRobot& shelf_pick_robot(std::string_view name);
/// The controllers, in a fixed order: ct, osc, task-pd, accel.
const std::vector<std::string>& shelf_pick_controllers();
/// @throws Error "unknown controller 'x'; choices: ct, osc, task-pd, accel".
void check_shelf_pick_controller(std::string_view name);

/// What the user asks for.
struct ShelfPickRequest {
  std::string robot = "panda";
  std::string controller = "osc";
  std::optional<Eigen::Vector3d> pick;  ///< world [m]; drawn from the seed when absent
  std::uint64_t seed = 1;
  PickCriteria criteria;  ///< 1 mm, 200 ms
};

/// A checked request, ready to run.
struct ShelfPickPlan {
  const ShelfPickRobot* robot = nullptr;
  Robot model;             ///< the torque-motor model
  Chain chain;             ///< every arm joint, frame = the tool tip
  std::string controller;  ///< checked name
  std::uint64_t seed = 1;
  Eigen::Vector3d pick;            ///< the pick point (world, m)
  bool pick_drawn = false;         ///< true when the seed chose it
  std::vector<double> qpos_start;  ///< full start qpos (home + the seeded perturbation)
  ShelfPickGoal goal;              ///< start/target poses and joints, approach time, criteria
  IkResult ik;                     ///< the IK solve that gave goal.q_target
};

/// What a seed's generator draws for a shelf pick, in this order: three numbers for the pick
/// point (uniform in the robot's box), then one per chain joint for the start (the joint moved
/// by a uniform offset in ±start_perturbation, clipped into its limits). Allocation-free.
/// @param qpos in: a full configuration (nq), the `home` keyframe; out: the start
/// @return the pick point drawn (world, m)
Eigen::Vector3d draw_shelf_pick(const ShelfPickRobot& robot, const Chain& chain, Random& rng,
                                std::span<double> qpos) noexcept;

/// Checks @p request and builds the plan. The seed's generator (`Random`) draws as
/// `draw_shelf_pick` (the pick point is drawn even when one is given, so that a seed perturbs
/// the start the same way with or without --pick).
/// @throws Error for an unknown robot or controller (listing the choices), a pick point that
///         is not finite, off the arm's plane, below the floor or out of reach (the message
///         gives its distance from the shoulder and the arm's reach), or criteria that are not
///         positive.
ShelfPickPlan plan_shelf_pick(const ShelfPickRequest& request);

}  // namespace mjarm
