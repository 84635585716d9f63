#pragma once
/// @file
/// The viewer's text overlays: a rate meter for frames per second and simulation speed, and the
/// two columns (labels, values) that `mjr_overlay` draws.

#include <mujoco/mujoco.h>

#include <cstdint>
#include <span>
#include <string>

#include "mjarm/teleop/teleop_panel.hpp"
#include "mjarm/teleop/viewer_session.hpp"

namespace mjarm {

/// Measures a rate (events or amounts per second) over windows of @p window seconds of a clock
/// the caller passes in. Allocation-free.
class RateMeter {
 public:
  /// @param window length of a measuring window [s] (> 0; non-positive values become 0.5 s)
  explicit RateMeter(double window = 0.5) noexcept;
  /// Adds @p amount at time @p now [s] (the amount accrued since the previous call); closes the
  /// window when @p now is @p window past its start. The first call only opens the first window.
  void add(double now, double amount = 1.0) noexcept;
  /// The rate over the last closed window [1/s]; 0 before the first window closes.
  double rate() const noexcept { return rate_; }

 private:
  double window_;
  double start_ = 0.0;
  double sum_ = 0.0;
  double rate_ = 0.0;
  bool started_ = false;
};

/// What the overlay shows besides the session's statistics.
struct OverlayInfo {
  double fps = 0.0;    ///< frames drawn per wall-clock second
  double speed = 0.0;  ///< simulated seconds per wall-clock second
  bool paused = false;
  std::string note;  ///< one line for people (a mode that could not be selected, …)
};

/// The two columns `mjr_overlay` draws, one line each: labels and values.
struct OverlayText {
  std::string labels;
  std::string values;
};

/// Formats the overlay: mode (and "paused"), simulated time and speed, frame rate, tracking error
/// (end effector vs reference) and distance to the panel target, IK status, actuator saturation
/// (the names of the actuators clipped at the last tick, from @p saturated, one flag per actuator
/// of @p m), contacts between the robot and the rest with their total normal force, the fault,
/// and @p info's note. Reuses @p out's storage.
void format_overlay(const ViewerStats& stats, const OverlayInfo& info, const mjModel& m,
                    std::span<const std::uint8_t> saturated, OverlayText& out);

/// Formats the bimanual overlays. @p common: mode (and "paused"), simulated time and speed,
/// frame rate, lift (position and reference), task priority, kinematic rollbacks, the fault and
/// @p info's note. @p hands_text: per hand of @p hands (the one the keys move marked), from
/// `TeleopStats::hands`: tracking error (hand vs reference, mm and degrees), IK status and
/// residual, saturated actuators, contacts of the gripper with the rest, grasp force (the
/// fingers' normal force on other bodies; n/a in kinematic mode) and whether the fingers touch,
/// the gripper command sent and the one asked for. Reuses the outputs' storage.
void format_teleop_overlay(const TeleopStats& stats, const std::vector<TeleopHand>& hands,
                           const TeleopPanel& panel, const OverlayInfo& info, OverlayText& common,
                           OverlayText& hands_text);

}  // namespace mjarm
