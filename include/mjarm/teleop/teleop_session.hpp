#pragma once
/// @file
/// `TeleopSession`: several hands driven at once (e.g. both arms of `dual_arm`), without a window.
/// Each hand has an end-effector target pose and a gripper command; a lift joint (when the model
/// has one) has a height target. The session turns them into motion in one of three modes:
///
/// - kinematic: multi-target IK (`MultiTargetIk`, one solve for every hand, the lift held at
///   its reference) → qpos written with `Simulation::move`; a move that makes the robot touch
///   anything is rolled back (the arm stops at the contact) and counted;
/// - position: the same IK → targets of the position servos of the lift, the arms and the
///   fingers, gravity compensated by the simulation (`SimulationOptions::gravity_compensation`);
/// - motor (`SimulationMode::torque`, on the model's `_torque` variant): differential IK
///   (`DiffIk`) from the measured arm configuration every tick → joint velocity v and
///   q_d = q + v·dt → computed torque (`ComputedTorqueController`) on the lift and both arms;
///   each gripper is a `HandFingerForce` (`FingerForceController`: PD in free motion, a set
///   squeeze once its fingers touch).
///
/// Task priority: each hand's target is a pose or a position, with a priority (0 first). In
/// kinematic and position modes priorities are strict (prioritized `MultiTargetIk`: a lower
/// level moves only in the null space of the higher ones); in motor mode the differential-IK QP
/// has weights only, so a lower priority level gets a weight 100 times smaller per level.
///
/// Every target is smoothed: the poses by a `TargetFilter` each (the jerk-limited generator), the
/// gripper commands and the lift by `RampedCommand` (smootherstep ramps). `step` allocates
/// nothing in any mode.

#include <mujoco/mujoco.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/contact_query.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/teleop/detail/mode_rigs.hpp"
#include "mjarm/trajectory/target_filter.hpp"

namespace mjarm {

/// One hand: its tool frame and its finger joints.
struct TeleopHand {
  std::string name;                  ///< short name ("left", "right"): panel and file labels
  std::string frame;                 ///< site (or body) whose pose the target sets
  std::vector<std::string> fingers;  ///< gripper joints (may be empty)
};

/// The hands of @p robot: every site called "<name>_tcp" (name = the prefix) or "tcp" (name
/// "hand"), sorted by name, with the limited joints below each one's arm as fingers.
/// @throws Error when the model has no such site (listing its sites).
std::vector<TeleopHand> find_teleop_hands(const Robot& robot);

/// What one hand is asked to do.
struct HandTarget {
  Pose X_WT;             ///< target pose of the hand frame in W
  double gripper = 0.0;  ///< 0 = open … 1 = closed
};

/// Everything a person (or a script) sets.
struct TeleopTargets {
  std::vector<HandTarget> hands;  ///< one per hand, in `TeleopSession::hands()` order
  double lift = 0.0;              ///< lift joint position [m] (ignored without a lift)
};

/// How a hand's target enters the IK.
struct HandTask {
  TargetKind kind = TargetKind::pose;  ///< pose (6 rows) or position (3 rows)
  int priority = 0;                    ///< 0 first; equal priorities are stacked
};

/// Settings of a `TeleopSession`.
struct TeleopOptions {
  std::vector<TeleopHand> hands;  ///< empty: `find_teleop_hands`
  /// The lift joint ("" with no joint called "lift": none).
  std::string lift = "lift";
  /// false: the lift follows its own target (`TeleopTargets::lift`) and the IK moves the arms
  /// only, each hand on its own arm; true: the lift is an IK joint shared by the hands (its
  /// target is then ignored), so that the hands' priorities decide between them.
  bool lift_in_ik = false;
  /// Initial state: keyframe ("" = "home" when the model has it, else qpos0).
  std::string keyframe;
  SimulationMode mode = SimulationMode::position;  ///< initial mode
  /// Kinematic mode: simulated time per tick [s] (rounded to whole timesteps, ≥ 1).
  double kinematic_period = 0.01;
  /// Position and motor modes: control period [s]; 0 = one physics step.
  double control_period = 0.0;
  TargetFilterLimits reference_limits;  ///< limits of each hand's reference (`TargetFilter`)
  double gripper_travel_time = 0.5;     ///< full gripper opening/closing [s] (> 0)
  double lift_travel_time = 2.0;        ///< the lift's full stroke [s] (> 0)
  double max_joint_speed = 2.0;  ///< kinematic/position: largest IK joint speed [rad/s] (> 0)
  int ik_iterations = 8;         ///< kinematic/position: IK iterations per tick (≥ 1)
  /// Motor mode: fraction of the pose error the differential IK removes per second [1/s] (> 0).
  double motor_gain = 20.0;
  double motor_omega = 30.0;    ///< motor mode: computed-torque bandwidth [rad/s] (> 0)
  std::vector<HandTask> tasks;  ///< per hand (empty: every hand a pose at priority 0)
};

/// The plain fields of `TeleopOptions` (the hands and their tasks are checked against the model).
constexpr auto declared_fields(const TeleopOptions*) {
  using S = TeleopOptions;
  return declare<S>(
      "teleop", field("lift", &S::lift, "the lift joint (\"\": none)"),
      field("lift_in_ik", &S::lift_in_ik, "the lift is an IK joint shared by the hands"),
      field("keyframe", &S::keyframe, "initial keyframe (\"\": home, else qpos0)"),
      field("mode", &S::mode, "initial mode"),
      field("kinematic_period", &S::kinematic_period, "s", Range::non_negative(),
            "kinematic mode: simulated time per tick, rounded to whole timesteps (≥ 1)"),
      field("control_period", &S::control_period, "s", Range::non_negative(),
            "position and motor modes: control period; 0: one physics step"),
      field("reference_limits", &S::reference_limits, "limits of each hand's reference"),
      field("gripper_travel_time", &S::gripper_travel_time, "s", Range::positive(),
            "full gripper opening or closing"),
      field("lift_travel_time", &S::lift_travel_time, "s", Range::positive(),
            "the lift's full stroke"),
      field("max_joint_speed", &S::max_joint_speed, "rad/s", Range::positive(),
            "kinematic/position: largest IK joint speed"),
      field("ik_iterations", &S::ik_iterations, "", Range::at_least(1),
            "kinematic/position: IK iterations per tick"),
      field("motor_gain", &S::motor_gain, "1/s", Range::positive(),
            "motor mode: fraction of the pose error removed per second"),
      field("motor_omega", &S::motor_omega, "rad/s", Range::positive(),
            "motor mode: computed-torque bandwidth"));
}

/// What the overlays show about one hand.
struct HandStats {
  Pose X_WE;                                 ///< hand frame
  Pose X_WR;                                 ///< reference (the smoothed target)
  Pose X_WT;                                 ///< target
  double tracking_position = 0.0;            ///< ‖p_WR − p_WE‖ [m]
  double tracking_orientation = 0.0;         ///< angle from E to R [rad]
  IkStatus ik_status = IkStatus::converged;  ///< kinematic/position: this hand's IK outcome
  double ik_position = 0.0;                  ///< IK residual of this hand at the last tick [m]
  double ik_orientation = 0.0;               ///< [rad]
  int saturated = 0;         ///< its actuators (arm and fingers) clipped at the last tick
  int contacts = 0;          ///< contacts between the hand (gripper subtree) and the rest
  double grasp_force = 0.0;  ///< normal force of the fingers on other bodies [N]
  bool touching = false;     ///< a finger touches something outside the hand
  double gripper = 0.0;      ///< gripper command sent (0 open … 1 closed)
};

/// What the session reports after every `step`, `reset`, target change and mode change.
struct TeleopStats {
  SimulationMode mode = SimulationMode::position;
  double time = 0.0;             ///< simulated time [s]
  std::int64_t ticks = 0;        ///< control ticks since the start or the last reset
  double lift = 0.0;             ///< lift position [m]
  double lift_reference = 0.0;   ///< smoothed lift target [m]
  std::vector<HandStats> hands;  ///< per hand
  std::int64_t rollbacks = 0;    ///< kinematic moves undone because of a contact
  bool faulted = false;          ///< the simulation stopped on a fault; `reset` clears it
  std::string fault;
};

/// The session: a rig per mode (the model's own flavour and its `_torque` / servo variant).
class TeleopSession {
 public:
  /// @throws Error for unknown hands, frames, fingers, lift or keyframe, invalid options, or an
  ///         initial mode the model cannot run (naming why).
  explicit TeleopSession(const Robot& robot, const TeleopOptions& options = {});
  ~TeleopSession();
  TeleopSession(const TeleopSession&) = delete;
  TeleopSession& operator=(const TeleopSession&) = delete;

  const std::vector<TeleopHand>& hands() const noexcept { return hands_; }
  bool has_lift() const noexcept { return has_lift_; }
  /// The lift's range [m] (0, 0 without a lift).
  std::array<double, 2> lift_range() const noexcept { return lift_range_; }
  const TeleopOptions& options() const noexcept { return options_; }

  /// The model simulated in the current mode.
  const Robot& robot() const noexcept;
  Simulation& simulation() noexcept;
  const Simulation& simulation() const noexcept;

  SimulationMode mode() const noexcept { return rigs_.mode(); }
  bool available(SimulationMode mode) const noexcept { return rigs_.available(mode); }
  const std::string& unavailable_reason(SimulationMode mode) const noexcept {
    return rigs_.unavailable_reason(mode);
  }
  /// Switches mode carrying the state over; references restart where the hands are.
  /// @throws Error when @p mode is unavailable.
  void set_mode(SimulationMode mode);
  double control_period() const noexcept;

  /// Task kind and priority of hand @p hand (rebuilds the IK of every rig: not for a tick).
  /// @throws Error for a bad index or a negative priority.
  void set_task(int hand, const HandTask& task);
  const std::vector<HandTask>& tasks() const noexcept { return tasks_; }

  /// The targets at the start: each hand where it is, gripper open, the lift where it is.
  const TeleopTargets& initial_targets() const noexcept { return initial_; }
  /// The targets in force.
  const TeleopTargets& targets() const noexcept { return targets_; }
  /// Takes new targets (invalid poses and NaN commands are ignored, the lift clamped).
  /// @throws Error when the number of hands differs.
  void set_targets(const TeleopTargets& targets);

  /// Simulates @p ticks control ticks (fewer after a fault). Allocates nothing.
  int step(int ticks) noexcept;
  /// Back to the initial state in the current mode (the targets are kept).
  void reset();

  const TeleopStats& stats() const noexcept { return stats_; }

 private:
  struct Rig;
  bool tick(Rig& rig) noexcept;
  void refresh_stats() noexcept;
  void restart_references();
  void build_ik();

  std::vector<TeleopHand> hands_;
  TeleopOptions options_;
  bool has_lift_ = false;
  int lift_qpos_ = -1;
  std::array<double, 2> lift_range_{0.0, 0.0};
  detail::ModeRigs<Rig> rigs_;
  std::vector<HandTask> tasks_;
  TeleopTargets initial_;
  TeleopTargets targets_;
  struct Smoothing;
  std::unique_ptr<Smoothing> smooth_;
  TeleopStats stats_;
};

}  // namespace mjarm
