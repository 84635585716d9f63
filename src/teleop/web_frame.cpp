#include "teleop/web_frame.hpp"

#include <Eigen/Core>

#include "mjarm/lie/rotation.hpp"
#include "mjarm/web/live_page.hpp"

namespace mjarm {

namespace {

void write_pose(const Pose& pose, float* out) noexcept {
  const Eigen::Vector4d q = quaternion_from_rotation(pose.R);
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(pose.p[k]);
  for (int k = 0; k < 4; ++k) out[3 + k] = static_cast<float>(q[k]);
}

}  // namespace

WebFrame::WebFrame(const mjModel& model, bool panel)
    : nbody_(model.nbody),
      panel_(panel),
      pos_(panel ? kPanelEnd : 1),
      floats_(static_cast<std::size_t>(pos_ + 7 * model.nbody), 0.0f) {}

nlohmann::json WebFrame::layout() const {
  nlohmann::json layout = {{"floats", floats_.size()},
                           {"time", 0},
                           {"pos", pos_},
                           {"quat", pos_ + 3 * nbody_},
                           {"bodies", nbody_}};
  if (panel_) {
    layout["tool"] = kTool;
    layout["target"] = kTarget;
    layout["gripper"] = kGripper;
  }
  return layout;
}

void WebFrame::set_bodies(double time, const mjData& data) noexcept {
  floats_[0] = static_cast<float>(time);
  float* pos = floats_.data() + pos_;
  float* quat = pos + 3 * nbody_;
  for (int i = 0; i < 3 * nbody_; ++i) pos[i] = static_cast<float>(data.xpos[i]);
  for (int i = 0; i < 4 * nbody_; ++i) quat[i] = static_cast<float>(data.xquat[i]);
}

void WebFrame::set_panel(const Pose& tool, const Pose& target, double gripper) noexcept {
  if (!panel_) return;
  write_pose(tool, floats_.data() + kTool);
  write_pose(target, floats_.data() + kTarget);
  floats_[kGripper] = static_cast<float>(gripper);
}

nlohmann::json web_greeting(const Robot& robot, const WebFrame& frame) {
  nlohmann::json greeting = live_scene(robot.model());
  greeting["model"] = robot.name();
  greeting["frame"] = frame.layout();
  return greeting;
}

}  // namespace mjarm
