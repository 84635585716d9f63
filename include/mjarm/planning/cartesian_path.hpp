#pragma once
/// @file
/// Cartesian straight-line paths in the MoveIt sense (docs/planning.md, "Cartesian paths"): the
/// chain's frame E follows straight lines (position lerp, orientation slerp) from its start pose
/// through waypoints, in steps no longer than a Cartesian bound; each step is solved by the local
/// pose IK seeded at the previous knot and judged (IK, jump in joint space, joint limits, σmin,
/// contacts); the path stops at the first step that fails and reports the share it followed.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/planning/configuration_check.hpp"

namespace mjarm {

/// How a Cartesian path ended.
enum class CartesianPathStatus {
  complete,            ///< every step followed: fraction 1
  partial_ik_failure,  ///< a step's pose has no IK solution near the previous knot
  partial_collision,   ///< a step (or a state between two knots) touches the scene
  partial_jump,        ///< a step's joint motion is a jump (branch switch), not a small step
  partial_limits,      ///< a step leaves the joint ranges or comes too close to a singularity
  invalid_input        ///< the IK met a NaN mid-solve (a bad model): nothing after it is trusted
};

constexpr auto declared_names(const CartesianPathStatus*) {
  using S = CartesianPathStatus;
  return std::array{
      EnumName{S::complete, "complete", "every step followed"},
      EnumName{S::partial_ik_failure, "partial_ik_failure", "a step's pose has no IK solution"},
      EnumName{S::partial_collision, "partial_collision", "a step touches the scene"},
      EnumName{S::partial_jump, "partial_jump", "a step's joint motion is a jump"},
      EnumName{S::partial_limits, "partial_limits",
               "a step leaves the joint ranges or comes too close to a singularity"},
      EnumName{S::invalid_input, "invalid_input", "the IK met a NaN mid-solve"}};
}

/// Every setting of a Cartesian path.
struct CartesianPathOptions {
  /// Largest position change of E between two consecutive step targets [m] (> 0).
  double max_step = 0.005;
  /// Largest rotation of E between two consecutive step targets [rad] (> 0).
  double max_rotation_step = 0.02;
  /// Relative jump test: a step whose joint distance ‖Δq‖ per unit of Cartesian step is more than
  /// this × the mean of the steps before it is a jump (0 disables; else ≥ 1).
  double jump_factor = 10.0;
  /// Absolute jump test: a revolute joint moving more than this in one step is a jump [rad]
  /// (0 disables).
  double jump_revolute = 0.5;
  /// … a prismatic joint moving more than this in one step [m] (0 disables).
  double jump_prismatic = 0.05;
  /// Between two knots the joint-space segment is checked at states at most this far apart
  /// (largest joint motion) [rad or m] (> 0).
  double check_step = 0.02;
  /// Judge contacts between the robot and the scene (off: joint ranges and σmin only).
  bool check_collisions = true;
  /// Steps one path may have (≥ 1); a longer path is refused before any IK is solved.
  int max_steps = 100000;
  /// σmin threshold, contact margin and joint-range tolerance of every state.
  CheckOptions checks;
  /// The local IK of each step; its position and orientation tolerances are the path's.
  PoseIkOptions ik;
};

/// The plain fields of `CartesianPathOptions` (`checks` nested; `ik` is checked on its own).
constexpr auto declared_fields(const CartesianPathOptions*) {
  using S = CartesianPathOptions;
  return declare<S>(
      "cartesian path",
      field("max_step", &S::max_step, "m", Range::positive(),
            "largest position change of E between two step targets"),
      field("max_rotation_step", &S::max_rotation_step, "rad", Range::positive(),
            "largest rotation of E between two step targets"),
      field("jump_factor", &S::jump_factor, "", Range::non_negative(),
            "a step's ‖Δq‖ beyond this × the mean so far is a jump (0: off)"),
      field("jump_revolute", &S::jump_revolute, "rad", Range::non_negative(),
            "a revolute joint moving more in one step is a jump (0: off)"),
      field("jump_prismatic", &S::jump_prismatic, "m", Range::non_negative(),
            "a prismatic joint moving more in one step is a jump (0: off)"),
      field("check_step", &S::check_step, "rad or m", Range::positive(),
            "largest joint motion between two checked states"),
      field("check_collisions", &S::check_collisions, "judge contacts with the scene"),
      field("max_steps", &S::max_steps, "", Range::at_least(1), "steps one path may have"),
      field("checks", &S::checks, "σmin, contact margin and joint-range tolerance"));
}

/// @throws Error naming the option out of range ("cartesian path: max_step must be positive and
///         finite [m], got 0"), or a jump_factor in (0, 1).
void check(const CartesianPathOptions& options);

/// What a Cartesian path reached. Knot 0 is the start; knot k (k ≥ 1) solves step k.
struct CartesianPathResult {
  CartesianPathStatus status = CartesianPathStatus::complete;
  /// Share of the path's steps followed, in [0, 1] (steps are equal within a segment, so on one
  /// straight line it is the share of the line's length).
  double fraction = 0.0;
  int steps = 0;             ///< steps of the whole path
  int stopped_at_step = -1;  ///< the step that failed (1…steps; 0: the start); −1 when complete
  int stopped_at_waypoint = -1;  ///< the waypoint its segment leads to (−1 when complete)
  std::string message;           ///< one line for people
  /// The knots followed, one column each (n × (steps followed + 1); n × 0 when the start fails).
  Eigen::MatrixXd knots;
  std::vector<Pose> poses;             ///< FK of E at each knot
  double max_position_error = 0.0;     ///< largest ‖p_target − p‖ over the knots [m]
  double max_orientation_error = 0.0;  ///< largest rotation angle to the target [rad]
  double max_joint_step = 0.0;         ///< largest |Δq_i| between two knots [rad or m]
  ConfigurationCheck check;            ///< the failing state's checks (failure none otherwise)
  bool complete() const noexcept { return status == CartesianPathStatus::complete; }
  int knot_count() const noexcept { return static_cast<int>(knots.cols()); }
};

/// Follows Cartesian paths for one chain: construct once (the IK, the checker and their scratch
/// data), follow many times. Never touches a caller's `mjData`.
class CartesianPathPlanner {
 public:
  /// @throws Error for invalid options.
  explicit CartesianPathPlanner(const Chain& chain, const CartesianPathOptions& options = {});
  ~CartesianPathPlanner();
  CartesianPathPlanner(CartesianPathPlanner&&) noexcept;
  CartesianPathPlanner& operator=(CartesianPathPlanner&&) noexcept;

  const CartesianPathOptions& options() const noexcept;

  /// Sets the joints outside the chain (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Follows straight lines from E's pose at @p q_start (n) through @p waypoints (poses of E in
  /// the world), in order.
  /// @throws Error naming the input when @p q_start has the wrong size or holds NaN/inf,
  ///         @p waypoints is empty, a waypoint is not finite or not a rotation, or the path
  ///         would need more than `max_steps` steps.
  CartesianPathResult follow(const Eigen::VectorXd& q_start, const std::vector<Pose>& waypoints);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One path, one call: `CartesianPathPlanner(chain, options).follow(q_start, waypoints)`.
CartesianPathResult cartesian_path(const Chain& chain, const Eigen::VectorXd& q_start,
                                   const std::vector<Pose>& waypoints,
                                   const CartesianPathOptions& options = {});
/// A single straight line to @p target.
CartesianPathResult cartesian_path(const Chain& chain, const Eigen::VectorXd& q_start,
                                   const Pose& target, const CartesianPathOptions& options = {});

}  // namespace mjarm
