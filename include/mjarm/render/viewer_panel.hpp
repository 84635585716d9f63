#pragma once
/// @file
/// The viewer panel's state and what it means: slider values → end-effector target pose and
/// gripper command, slider ranges from the arm's workspace, named edits (for scripts and the
/// command line). The reference that follows the target is `TargetFilter`
/// (trajectory/target_filter.hpp).
///
/// None of this needs a window: the panel widgets (viewer_ui.hpp) write straight into
/// `PanelState`, and everything else reads it.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/sim/simulation_options.hpp"

namespace mjarm {

/// Index of each target slider in `PanelState::target`.
enum PanelSlider : int { slider_x = 0, slider_y, slider_z, slider_roll, slider_pitch, slider_yaw };

/// What the panel's widgets hold. Plain numbers, laid out for MuJoCo's UI (sliders write doubles,
/// the mode radio writes an int).
struct PanelState {
  /// End-effector target: position x, y, z [m] in the world frame W, then roll, pitch, yaw [rad]
  /// with R_WT = Rz(yaw)·Ry(pitch)·Rx(roll) (extrinsic X-Y-Z, as `rotation_from_rpy`).
  double target[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double gripper = 0.0;  ///< gripper command: 0 = fully open, 1 = fully closed
  int mode = 0;          ///< `SimulationMode` as an int (kinematic 0, position 1, torque 2)
};

/// Slider ranges: one [lower, upper] per target slider, plus [0, 1] for the gripper.
struct PanelRanges {
  double lower[6] = {-1.0, -1.0, 0.0, -3.14159, -1.5708, -3.14159};  ///< [m, m, m, rad, rad, rad]
  double upper[6] = {1.0, 1.0, 1.0, 3.14159, 1.5708, 3.14159};       ///< [m, m, m, rad, rad, rad]
};

/// Names accepted by `set_panel_value`, in slider order: x y z roll pitch yaw gripper mode.
const std::vector<std::string>& panel_value_names();

/// The ranges for @p chain's frame: the bounding box of a seeded workspace sample (@p samples
/// joint configurations) widened by 5 cm for x, y, z, and ±π about the initial pose's
/// roll-pitch-yaw @p X_WE0 (±π/2 for pitch), so that the initial target sits mid-slider and every
/// orientation is reachable.
/// @throws Error when @p samples is 0.
PanelRanges panel_ranges(const Chain& chain, const Pose& X_WE0, std::size_t samples = 2000);

/// The panel's target pose X_WT.
Pose panel_target(const PanelState& state) noexcept;

/// A state whose target is @p X_WT (its roll-pitch-yaw unwrapped to lie nearest the middle of
/// @p ranges), with @p gripper and @p mode.
PanelState panel_state(const Pose& X_WT, const PanelRanges& ranges, double gripper,
                       SimulationMode mode);

/// The mode the panel selects.
/// @throws Error when `state.mode` is not 0, 1 or 2.
SimulationMode panel_mode(const PanelState& state);

/// Sets one value by name: "x", "y", "z" [m], "roll", "pitch", "yaw" [rad] within @p ranges (a
/// value the slider could not show is an error), "gripper" in [0, 1], or "mode" with value
/// "kinematic", "position" or "torque".
/// @throws Error naming the value and what was expected: unknown name (listing the names), a
///         value that is not a finite number, or outside its range.
void set_panel_value(PanelState& state, const PanelRanges& ranges, std::string_view name,
                     std::string_view value);

}  // namespace mjarm
