#pragma once
/// @file
/// The live page's frame and greeting (web/src/live.js). The frame is little-endian float32: the
/// time [s]; with the viewer's panel, the tool pose (x y z [m], quaternion w x y z), the target
/// pose (the same) and the gripper command; then every body's position (3 per body, the world's
/// first) and every body's quaternion (w x y z, 4 per body) — the `pos` and `quat` of one replay
/// frame (docs/replay.md). The greeting names where each part starts.

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "mjarm/lie/pose.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

class WebFrame {
 public:
  /// A frame of @p model's bodies; with @p panel, the tool, the target and the gripper too.
  WebFrame(const mjModel& model, bool panel);

  /// Where each part starts, in floats: "floats" (the frame's size), "time", "pos", "quat" and,
  /// with the panel, "tool", "target", "gripper".
  nlohmann::json layout() const;
  /// Writes @p time and every body's pose as @p data holds it (xpos, xquat). Allocates nothing.
  void set_bodies(double time, const mjData& data) noexcept;
  /// Writes the tool and target poses and the gripper command; a frame without the panel has no
  /// room for them and is left unchanged. Allocates nothing.
  void set_panel(const Pose& tool, const Pose& target, double gripper) noexcept;
  /// The frame as the bytes a `LiveServer` publishes.
  std::string_view bytes() const noexcept {
    return {reinterpret_cast<const char*>(floats_.data()), floats_.size() * sizeof(float)};
  }

 private:
  static constexpr int kTool = 1, kTarget = 8, kGripper = 15, kPanelEnd = 16;
  int nbody_;
  bool panel_;
  int pos_;  ///< where the positions start; the quaternions follow them
  std::vector<float> floats_;
};

/// What a page builds its view from: the model as the replay page draws it (`live_scene`), the
/// model's name and @p frame's layout ("frame"); the sender adds its panel.
nlohmann::json web_greeting(const Robot& robot, const WebFrame& frame);

}  // namespace mjarm
