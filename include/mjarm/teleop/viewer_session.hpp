#pragma once
/// @file
/// `ViewerSession`: what the interactive viewer simulates, without the window. It turns the
/// panel's target (and gripper command) into motion in one of three modes and reports what the
/// overlays show. The GLFW shell (viewer.hpp) owns one; tests drive one directly.
///
/// Modes:
/// - kinematic: every tick, pose IK from the current configuration to the reference, the step
///   limited to `max_joint_speed`, written with `Simulation::move` (no dynamics);
/// - position: the same IK produces targets for the model's position servos (physics on);
/// - torque: operational-space impedance control of the reference on the model's `_torque`
///   variant (the file `<name>_torque.xml` beside the model; `<name>.xml` is the position
///   variant of a `_torque` model).
/// In every mode the reference follows the panel target as a jerk-limited motion (`TargetFilter`:
/// the jerk-limited generator, recalculated from the reference's current state whenever the
/// target changes).

#include <mujoco/mujoco.h>

#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/contact_query.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/teleop/detail/mode_rigs.hpp"
#include "mjarm/teleop/viewer_panel.hpp"
#include "mjarm/trajectory/ramped_command.hpp"
#include "mjarm/trajectory/target_filter.hpp"

namespace mjarm {

/// Settings of a `ViewerSession`.
struct ViewerSessionOptions {
  /// End-effector frame (site, or body). Empty: "tcp" when the model has that site, else the
  /// model's only named site.
  std::string site;
  /// Initial state. Empty: keyframe "home" when the model has it, else the reference qpos0.
  std::string keyframe;
  SimulationMode mode = SimulationMode::kinematic;  ///< initial mode
  /// Kinematic mode: simulated time per tick [s], rounded to a whole number of timesteps (≥ 1).
  double kinematic_period = 0.01;
  /// Position and torque modes: control period [s]; 0 means one physics step.
  double control_period = 0.0;
  /// Limits of the reference that follows the panel target (per world axis and per rotation
  /// vector component: velocity, acceleration, jerk; all > 0).
  TargetFilterLimits reference_limits;
  /// Duration of a full gripper opening or closing [s] (> 0): the gripper command follows its
  /// slider along a smoothstep ramp (`RampedCommand`).
  double gripper_travel_time = 0.5;
  /// Kinematic and position modes: largest joint speed of the IK output [rad/s or m/s] (> 0).
  double max_joint_speed = 2.0;
  int ik_iterations = 10;            ///< IK iterations per tick, warm-started (≥ 1)
  std::size_t range_samples = 2000;  ///< workspace samples for the slider ranges (> 0)
};

constexpr auto declared_fields(const ViewerSessionOptions*) {
  using S = ViewerSessionOptions;
  return declare<S>(
      "viewer", field("site", &S::site, "end-effector frame (\"\": tcp, else the only site)"),
      field("keyframe", &S::keyframe, "initial keyframe (\"\": home, else qpos0)"),
      field("mode", &S::mode, "initial mode"),
      field("kinematic_period", &S::kinematic_period, "s", Range::non_negative(),
            "kinematic mode: simulated time per tick, rounded to whole timesteps (≥ 1)"),
      field("control_period", &S::control_period, "s", Range::non_negative(),
            "position and torque modes: control period; 0: one physics step"),
      field("reference_limits", &S::reference_limits,
            "limits of the reference that follows the panel target"),
      field("gripper_travel_time", &S::gripper_travel_time, "s", Range::positive(),
            "full gripper opening or closing"),
      field("max_joint_speed", &S::max_joint_speed, "rad/s or m/s", Range::positive(),
            "kinematic and position modes: largest joint speed of the IK output"),
      field("ik_iterations", &S::ik_iterations, "", Range::at_least(1),
            "IK iterations per tick, warm-started"),
      field("range_samples", &S::range_samples, "", Range::at_least(1),
            "workspace samples for the slider ranges"));
}

/// What the overlays show; refreshed after every `step`, `reset`, `set_target` and mode change.
struct ViewerStats {
  SimulationMode mode = SimulationMode::kinematic;
  double time = 0.0;               ///< simulated time [s]
  Pose X_WE;                       ///< end-effector pose
  Pose X_WR;                       ///< reference pose (the filtered target the controller tracks)
  Pose X_WT;                       ///< panel target pose
  double tracking_position = 0.0;  ///< ‖p_WR − p_WE‖ [m]
  double tracking_orientation = 0.0;         ///< rotation angle from E to R [rad]
  double target_position = 0.0;              ///< ‖p_WT − p_WE‖ [m]
  double target_orientation = 0.0;           ///< rotation angle from E to T [rad]
  bool ik_used = false;                      ///< kinematic/position: an IK ran at the last tick
  IkStatus ik_status = IkStatus::converged;  ///< status of that IK
  int saturated = 0;  ///< actuators whose command was clipped at the last tick
  double gripper = 0.0;  ///< the gripper command sent (0 open … 1 closed), ramped to the slider
  /// Contacts between the robot and everything else (forces invalid in kinematic mode).
  ContactSummary contacts;
  bool faulted = false;  ///< the simulation stopped on a fault; `reset` clears it
  std::string fault;     ///< the fault, for people (empty when none)
};

/// One viewer simulation with its three mode rigs. Not copyable.
class ViewerSession {
 public:
  /// Builds the rigs of every mode the model supports (a mode whose rig fails is unavailable,
  /// with the reason kept) and puts the robot in its initial state, the target at its initial
  /// end-effector pose.
  /// @throws Error for an unknown site or keyframe, invalid options, or when the initial mode is
  ///         unavailable (naming why).
  explicit ViewerSession(const Robot& robot, const ViewerSessionOptions& options = {});
  ~ViewerSession();
  ViewerSession(const ViewerSession&) = delete;
  ViewerSession& operator=(const ViewerSession&) = delete;

  /// The model simulated in the current mode (the `_torque` variant in torque mode).
  const Robot& robot() const noexcept;
  /// The current simulation (its data is what the viewer draws).
  Simulation& simulation() noexcept;
  const Simulation& simulation() const noexcept;
  /// The arm chain of the current mode.
  const Chain& arm() const noexcept;
  /// Name of the end-effector frame.
  const std::string& site() const noexcept { return site_; }

  SimulationMode mode() const noexcept { return rigs_.mode(); }
  /// True when @p mode can run on this model.
  bool available(SimulationMode mode) const noexcept { return rigs_.available(mode); }
  /// Why @p mode cannot run (empty when it can).
  const std::string& unavailable_reason(SimulationMode mode) const noexcept {
    return rigs_.unavailable_reason(mode);
  }
  /// Switches mode, carrying the configuration (and velocity) over; the reference restarts at
  /// the current end-effector pose. Nothing happens when @p mode is the current one.
  /// @throws Error when @p mode is unavailable (with the reason).
  void set_mode(SimulationMode mode);

  /// Simulated time per control tick of the current mode [s].
  double control_period() const noexcept;
  /// Slider ranges (from the arm's workspace and initial pose).
  const PanelRanges& ranges() const noexcept { return ranges_; }
  /// The panel state at start: target at the initial end-effector pose, gripper open, the
  /// initial mode.
  const PanelState& initial_panel() const noexcept { return initial_panel_; }
  /// True when the model has gripper joints (limited joints below the end-effector frame's
  /// last arm joint that are not on the arm chain).
  bool has_gripper() const noexcept;

  /// Takes the target pose and gripper command of @p panel (its mode is not read: see
  /// `set_mode`).
  void set_target(const PanelState& panel) noexcept;

  /// Simulates @p ticks control ticks (fewer when a fault stops the simulation). Allocates
  /// nothing (a fault's message is built once, when it happens).
  /// @return the ticks simulated
  int step(int ticks) noexcept;

  /// Back to the initial state in the current mode; clears a fault. The target is kept (the
  /// caller resets the panel if it wants to).
  void reset();

  const ViewerStats& stats() const noexcept { return stats_; }

 private:
  struct Rig;
  bool tick(Rig& rig) noexcept;
  void refresh_stats() noexcept;
  void restart_reference();

  std::string site_;
  ViewerSessionOptions options_;
  detail::ModeRigs<Rig> rigs_;
  PanelRanges ranges_;
  PanelState initial_panel_;
  Pose X_WT_;
  double gripper_ = 0.0;
  TargetFilter filter_;
  RampedCommand gripper_ramp_;
  ViewerStats stats_;
};

/// The end-effector frame the viewer uses for @p robot when none is given: "tcp" when the model
/// has that site, else its only named site.
/// @throws Error listing the sites when the model has several (and no "tcp") or none.
std::string default_viewer_site(const Robot& robot);

}  // namespace mjarm
