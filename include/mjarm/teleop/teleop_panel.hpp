#pragma once
/// @file
/// The bimanual viewer panel's state and what it means, without a window: a section per hand
/// (position, roll/pitch/yaw, gripper), the lift, the camera (azimuth, elevation, distance,
/// look-at, presets), the mode, the task priority and the selected hand; named edits (for
/// scripts and the command line) and keyboard nudges of the selected hand.
///
/// Orientation sliders are roll, pitch, yaw [rad] with R_WT = Rz(yaw)·Ry(pitch)·Rx(roll), as the
/// single-arm panel (viewer_panel.hpp).

#include <string>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/teleop/teleop_session.hpp"

namespace mjarm {

/// One hand's section.
struct HandPanel {
  double pose[6] = {0, 0, 0, 0, 0, 0};  ///< x, y, z [m] in W, roll, pitch, yaw [rad]
  double gripper = 0.0;                 ///< 0 open … 1 closed
};

/// Camera presets.
enum class CameraPreset { front = 0, left, right, top, overview };

constexpr auto declared_names(const CameraPreset*) {
  using P = CameraPreset;
  return std::array{EnumName{P::front, "front"}, EnumName{P::left, "left"},
                    EnumName{P::right, "right"}, EnumName{P::top, "top"},
                    EnumName{P::overview, "overview"}};
}

/// The camera section: a free camera (render/camera.hpp conventions).
struct CameraPanel {
  double azimuth = 155.0;              ///< [deg]
  double elevation = -30.0;            ///< [deg]
  double distance = 2.2;               ///< [m]
  double lookat[3] = {0.4, 0.0, 1.0};  ///< [m] in W
  int preset = static_cast<int>(CameraPreset::front);
};

/// Task priorities the panel offers.
enum class TeleopPriority {
  equal = 0,            ///< every hand a pose at priority 0
  right_over_left = 1,  ///< right pose first, left position second
  left_over_right = 2   ///< left pose first, right position second
};

constexpr auto declared_names(const TeleopPriority*) {
  using P = TeleopPriority;
  return std::array{EnumName{P::equal, "equal", "every hand a pose at priority 0"},
                    EnumName{P::right_over_left, "right-over-left",
                             "right pose first, left position second"},
                    EnumName{P::left_over_right, "left-over-right",
                             "left pose first, right position second"}};
}

/// What the panel holds.
struct TeleopPanel {
  std::vector<HandPanel> hands;
  double lift = 0.0;  ///< [m]
  CameraPanel camera;
  int mode = 1;      ///< `SimulationMode` as an int
  int priority = 0;  ///< `TeleopPriority` as an int
  int selected = 0;  ///< the hand the keyboard nudges
};

/// The panel at @p session's initial targets, in its mode, the camera at the front preset looking
/// at the middle of the hands.
TeleopPanel teleop_panel(const TeleopSession& session);

/// The targets the panel asks for.
TeleopTargets panel_targets(const TeleopPanel& panel);

/// The hand tasks of a priority choice for a session's hands (the hands called "left" and
/// "right"; other hands get a pose at priority 0).
std::vector<HandTask> priority_tasks(const TeleopSession& session, TeleopPriority priority);

/// Puts the camera section at preset @p preset, looking at @p lookat [m].
void apply_camera_preset(CameraPanel& camera, CameraPreset preset, const Eigen::Vector3d& lookat);

/// Names accepted by `set_teleop_value`: "<hand>.x" … "<hand>.yaw", "<hand>.gripper" per hand,
/// "lift", "camera.azimuth", "camera.elevation", "camera.distance", "camera.lookat_x|y|z",
/// "camera.preset", "mode", "priority", "hand".
std::vector<std::string> teleop_value_names(const TeleopSession& session);

/// Sets one value by name: numbers for the hands (angles in rad, gripper in [0, 1]), the lift
/// (within its range), the camera ([deg], |elevation| < 90, distance > 0); "camera.preset"
/// front|left|right|top|overview; "mode" kinematic|position|torque; "priority"
/// equal|right-over-left|left-over-right; "hand" a hand's name.
/// @throws Error naming the value and what was expected.
void set_teleop_value(TeleopPanel& panel, const TeleopSession& session, std::string_view name,
                      std::string_view value);

/// Keyboard nudges of the selected hand (keys as GLFW and ASCII spell capital letters):
/// W/S ±x, A/D ±y, R/F ±z by `step` [m]; with shift, W/S ±pitch, A/D ±roll, R/F ±yaw by
/// `angle_step` [rad]; G toggles the gripper (open ↔ closed); TAB (258) selects the next hand.
/// @return true when the key did something
bool nudge(TeleopPanel& panel, int key, bool shift, double step = 0.01, double angle_step = 0.087);

}  // namespace mjarm
