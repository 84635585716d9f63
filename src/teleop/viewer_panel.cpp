#include "mjarm/teleop/viewer_panel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMargin = 0.05;  // [m] added around the sampled workspace box

// the representative of `angle` + 2πk nearest to `centre`
double unwrap_near(double angle, double centre) noexcept {
  return angle + 2.0 * kPi * std::round((centre - angle) / (2.0 * kPi));
}

std::string slider_bound_text(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}

}  // namespace

const std::vector<std::string>& panel_value_names() {
  static const std::vector<std::string> names = {"x",     "y",   "z",       "roll",
                                                 "pitch", "yaw", "gripper", "mode"};
  return names;
}

PanelRanges panel_ranges(const Chain& chain, const Pose& X_WE0, std::size_t samples) {
  if (samples == 0) throw Error("panel ranges: the workspace sample count must be > 0");
  WorkspaceOptions options;
  options.samples = samples;
  options.seed = 1;
  options.compute_manipulability = false;
  options.keep_points = false;
  const WorkspaceResult workspace = sample_workspace(chain, options);
  PanelRanges ranges;
  for (int i = 0; i < 3; ++i) {
    // the box always holds the initial pose, even for a tiny sample
    ranges.lower[i] = std::min(workspace.lower[i], X_WE0.p[i]) - kMargin;
    ranges.upper[i] = std::max(workspace.upper[i], X_WE0.p[i]) + kMargin;
  }
  const Eigen::Vector3d rpy = rpy_from_rotation(X_WE0.R);
  const double half[3] = {kPi, kPi / 2.0, kPi};
  for (int i = 0; i < 3; ++i) {
    ranges.lower[3 + i] = rpy[i] - half[i];
    ranges.upper[3 + i] = rpy[i] + half[i];
  }
  return ranges;
}

Pose panel_target(const PanelState& state) noexcept {
  Pose X_WT;
  X_WT.p = Eigen::Vector3d(state.target[slider_x], state.target[slider_y], state.target[slider_z]);
  X_WT.R = rotation_from_rpy(state.target[slider_roll], state.target[slider_pitch],
                             state.target[slider_yaw]);
  return X_WT;
}

PanelState panel_state(const Pose& X_WT, const PanelRanges& ranges, double gripper,
                       SimulationMode mode) {
  PanelState state;
  for (int i = 0; i < 3; ++i) state.target[i] = X_WT.p[i];
  const Eigen::Vector3d rpy = rpy_from_rotation(X_WT.R);
  for (int i = 0; i < 3; ++i) {
    const double centre = 0.5 * (ranges.lower[3 + i] + ranges.upper[3 + i]);
    // pitch has no 2π ambiguity inside [−π/2, π/2]; roll and yaw do
    state.target[3 + i] = i == 1 ? rpy[i] : unwrap_near(rpy[i], centre);
  }
  // round-off noise (1e-33 m, −2e-16 rad) would show on the sliders as such
  for (double& v : state.target) {
    if (std::abs(v) < 1e-12) v = 0.0;
  }
  state.gripper = std::clamp(gripper, 0.0, 1.0);
  state.mode = static_cast<int>(mode);
  return state;
}

SimulationMode panel_mode(const PanelState& state) {
  switch (state.mode) {
    case 0:
      return SimulationMode::kinematic;
    case 1:
      return SimulationMode::position;
    case 2:
      return SimulationMode::torque;
    default:
      throw Error("viewer panel: mode index " + std::to_string(state.mode) +
                  " is not 0 (kinematic), 1 (position) or 2 (torque)");
  }
}

void set_panel_value(PanelState& state, const PanelRanges& ranges, std::string_view name,
                     std::string_view value) {
  const auto& names = panel_value_names();
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw Error("viewer panel: unknown value '" + std::string(name) + "'; values: " + list);
  }
  const int index = static_cast<int>(found - names.begin());
  if (name == "mode") {
    if (const auto mode = enum_from_name<SimulationMode>(value)) {
      state.mode = static_cast<int>(*mode);
      return;
    }
    std::string modes;
    for (const auto& n : enum_names<SimulationMode>()) modes += (modes.empty() ? "" : ", ") + n;
    throw Error("viewer panel: mode '" + std::string(value) + "' is not one of " + modes);
  }
  const auto parsed = number_from_text(value);
  const double number = parsed ? *parsed : std::nan("");
  if (!std::isfinite(number)) {
    throw Error("viewer panel: " + std::string(name) + " needs a finite number, got '" +
                std::string(value) + "'");
  }
  const double lower = index < 6 ? ranges.lower[index] : 0.0;
  const double upper = index < 6 ? ranges.upper[index] : 1.0;
  if (number < lower || number > upper) {
    throw Error("viewer panel: " + std::string(name) + " = " + std::string(value) +
                " is outside its slider range [" + slider_bound_text(lower) + ", " +
                slider_bound_text(upper) + "]" + (index >= 3 && index < 6 ? " rad" : ""));
  }
  if (index < 6) {
    state.target[index] = number;
  } else {
    state.gripper = number;
  }
}

}  // namespace mjarm
