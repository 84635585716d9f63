#include "mjarm/teleop/teleop_panel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

constexpr const char* kPoseNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
constexpr int kKeyTab = 258;

double parse_number(std::string_view name, std::string_view value) {
  const auto v = number_from_text(value);
  if (!v || !std::isfinite(*v))
    throw Error("panel value '" + std::string(name) + "' must be a finite number, got '" +
                std::string(value) + "'");
  return *v;
}

void check_range(std::string_view name, double v, double lo, double hi) {
  if (v < lo || v > hi)
    throw Error("panel value '" + std::string(name) + "' must be within [" + number_text(lo) +
                ", " + number_text(hi) + "], got " + number_text(v));
}

// the value of panel value @p name called @p value
template <DeclaredEnum E>
E panel_choice(std::string_view name, std::string_view value) {
  if (const auto found = enum_from_name<E>(value)) return *found;
  std::string list;
  for (const auto& n : names_of<E>()) list += (list.empty() ? "" : ", ") + std::string(n.name);
  throw Error("panel value '" + std::string(name) + "' must be one of " + list + ", got '" +
              std::string(value) + "'");
}

Eigen::Vector3d hands_middle(const TeleopPanel& panel) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& h : panel.hands) m += Eigen::Vector3d(h.pose[0], h.pose[1], h.pose[2]);
  return panel.hands.empty() ? m : m / static_cast<double>(panel.hands.size());
}

}  // namespace

TeleopPanel teleop_panel(const TeleopSession& session) {
  TeleopPanel panel;
  for (const auto& t : session.initial_targets().hands) {
    HandPanel h;
    const Eigen::Vector3d rpy = rpy_from_rotation(t.X_WT.R);
    for (int k = 0; k < 3; ++k) {
      h.pose[k] = t.X_WT.p[k];
      h.pose[3 + k] = rpy[k];
    }
    h.gripper = t.gripper;
    panel.hands.push_back(h);
  }
  panel.lift = session.initial_targets().lift;
  panel.mode = static_cast<int>(session.mode());
  const Eigen::Vector3d middle = hands_middle(panel) - Eigen::Vector3d(0.0, 0.0, 0.1);
  apply_camera_preset(panel.camera, CameraPreset::front, middle);
  return panel;
}

TeleopTargets panel_targets(const TeleopPanel& panel) {
  TeleopTargets t;
  t.lift = panel.lift;
  for (const auto& h : panel.hands) {
    HandTarget target;
    target.X_WT.p = Eigen::Vector3d(h.pose[0], h.pose[1], h.pose[2]);
    target.X_WT.R = rotation_from_rpy(h.pose[3], h.pose[4], h.pose[5]);
    target.gripper = h.gripper;
    t.hands.push_back(target);
  }
  return t;
}

std::vector<HandTask> priority_tasks(const TeleopSession& session, TeleopPriority priority) {
  std::vector<HandTask> tasks(session.hands().size());
  if (priority == TeleopPriority::equal) return tasks;
  const std::string first = priority == TeleopPriority::right_over_left ? "right" : "left";
  const std::string second = priority == TeleopPriority::right_over_left ? "left" : "right";
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (session.hands()[i].name == second) tasks[i] = HandTask{TargetKind::position, 1};
    if (session.hands()[i].name == first) tasks[i] = HandTask{TargetKind::pose, 0};
  }
  return tasks;
}

void apply_camera_preset(CameraPanel& camera, CameraPreset preset, const Eigen::Vector3d& lookat) {
  static constexpr double kView[5][3] = {
      // azimuth, elevation [deg], distance [m]
      {155.0, -30.0, 2.2},  // front: ahead of the robot, a little to its right
      {-90.0, -20.0, 2.2},  // left: from the robot's left (+y) side
      {90.0, -20.0, 2.2},   // right: from its right (−y) side
      {180.0, -89.0, 2.0},  // top: from above
      {135.0, -25.0, 3.5},  // overview
  };
  const int k = static_cast<int>(preset);
  camera.preset = k;
  camera.azimuth = kView[k][0];
  camera.elevation = kView[k][1];
  camera.distance = kView[k][2];
  for (int i = 0; i < 3; ++i) camera.lookat[i] = lookat[i];
}

std::vector<std::string> teleop_value_names(const TeleopSession& session) {
  std::vector<std::string> names;
  for (const auto& h : session.hands()) {
    for (const char* n : kPoseNames) names.push_back(h.name + "." + n);
    names.push_back(h.name + ".gripper");
  }
  for (const char* n :
       {"lift", "camera.azimuth", "camera.elevation", "camera.distance", "camera.lookat_x",
        "camera.lookat_y", "camera.lookat_z", "camera.preset", "mode", "priority", "hand"})
    names.emplace_back(n);
  return names;
}

void set_teleop_value(TeleopPanel& panel, const TeleopSession& session, std::string_view name,
                      std::string_view value) {
  const auto dot = name.find('.');
  const std::string_view head = name.substr(0, dot);
  const std::string_view tail = dot == std::string_view::npos ? "" : name.substr(dot + 1);
  for (std::size_t i = 0; i < session.hands().size() && i < panel.hands.size(); ++i) {
    if (head != session.hands()[i].name || tail.empty()) continue;
    for (int k = 0; k < 6; ++k) {
      if (tail != kPoseNames[k]) continue;
      const double v = parse_number(name, value);
      if (k >= 3) check_range(name, v, -2.0 * std::numbers::pi, 2.0 * std::numbers::pi);
      if (k < 3) check_range(name, v, -3.0, 3.0);
      panel.hands[i].pose[k] = v;
      return;
    }
    if (tail == "gripper") {
      const double v = parse_number(name, value);
      check_range(name, v, 0.0, 1.0);
      panel.hands[i].gripper = v;
      return;
    }
  }
  if (name == "lift") {
    const double v = parse_number(name, value);
    check_range(name, v, session.lift_range()[0], session.lift_range()[1]);
    panel.lift = v;
    return;
  }
  if (head == "camera") {
    if (tail == "preset") {
      apply_camera_preset(
          panel.camera, panel_choice<CameraPreset>(name, value),
          Eigen::Vector3d(panel.camera.lookat[0], panel.camera.lookat[1], panel.camera.lookat[2]));
      return;
    }
    const double v = parse_number(name, value);
    if (tail == "azimuth") {
      check_range(name, v, -360.0, 360.0);
      panel.camera.azimuth = v;
    } else if (tail == "elevation") {
      check_range(name, v, -89.9, 89.9);
      panel.camera.elevation = v;
    } else if (tail == "distance") {
      check_range(name, v, 0.05, 20.0);
      panel.camera.distance = v;
    } else if (tail == "lookat_x" || tail == "lookat_y" || tail == "lookat_z") {
      check_range(name, v, -10.0, 10.0);
      panel.camera.lookat[tail.back() - 'x'] = v;
    } else {
      throw Error("unknown panel value '" + std::string(name) + "'");
    }
    return;
  }
  if (name == "mode") {
    panel.mode = static_cast<int>(panel_choice<SimulationMode>(name, value));
    return;
  }
  if (name == "priority") {
    panel.priority = static_cast<int>(panel_choice<TeleopPriority>(name, value));
    return;
  }
  if (name == "hand") {
    for (std::size_t i = 0; i < session.hands().size(); ++i) {
      if (value == session.hands()[i].name) {
        panel.selected = static_cast<int>(i);
        return;
      }
    }
    throw Error("panel value 'hand': no hand called '" + std::string(value) + "'");
  }
  std::string list;
  for (const auto& n : teleop_value_names(session)) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown panel value '" + std::string(name) + "'; values: " + list);
}

bool nudge(TeleopPanel& panel, int key, bool shift, double step, double angle_step) {
  if (panel.hands.empty()) return false;
  if (key == kKeyTab) {
    panel.selected = (panel.selected + 1) % static_cast<int>(panel.hands.size());
    return true;
  }
  HandPanel& h = panel.hands[static_cast<std::size_t>(
      std::clamp(panel.selected, 0, static_cast<int>(panel.hands.size()) - 1))];
  if (key == 'G') {
    h.gripper = h.gripper < 0.5 ? 1.0 : 0.0;
    return true;
  }
  // (key, coordinate, sign): position coordinates without shift, angles with it
  struct Binding {
    int key, coordinate, angle_coordinate;
    double sign;
  };
  static constexpr Binding kBindings[6] = {{'W', 0, 4, 1.0},  {'S', 0, 4, -1.0}, {'A', 1, 3, 1.0},
                                           {'D', 1, 3, -1.0}, {'R', 2, 5, 1.0},  {'F', 2, 5, -1.0}};
  for (const Binding& b : kBindings) {
    if (b.key != key) continue;
    if (shift) {
      h.pose[b.angle_coordinate] += b.sign * angle_step;
    } else {
      h.pose[b.coordinate] += b.sign * step;
    }
    return true;
  }
  return false;
}

}  // namespace mjarm
