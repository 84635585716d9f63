#pragma once
/// @file
/// Pose of a free body (an object added with `Scene::add_object`) read from and written into an
/// `mjData`: the 7 qpos of its free joint, position then unit quaternion (w, x, y, z).

#include <mujoco/mujoco.h>

#include <array>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// Pose of a free body B in world W.
struct FreePose {
  std::array<double, 3> p_WB{0.0, 0.0, 0.0};          ///< position [m]
  std::array<double, 4> quat_WB{1.0, 0.0, 0.0, 0.0};  ///< orientation (w, x, y, z), unit
};

constexpr auto declared_fields(const FreePose*) {
  using S = FreePose;
  return declare<S>("free pose", field("p_WB", &S::p_WB, "m", Range::finite(), "position"),
                    field("quat_WB", &S::quat_WB, "", Range::finite(),
                          "orientation w, x, y, z, unit"));
}

/// The qpos address of the free joint of @p body (a body name, e.g. "cube", or the name of a
/// free joint, e.g. "cube/joint").
/// @throws Error when no body or joint has that name (closest names listed) or it has no free
///         joint.
int free_qpos_address(const Robot& robot, std::string_view body);

/// Writes the pose of @p body into `data.qpos` (the quaternion is normalized); velocities and
/// derived quantities are left as they are (call `mj_forward` to update them).
/// @throws Error as `free_qpos_address`, or for a non-finite value or a zero quaternion.
void set_free_pose(const Robot& robot, mjData& data, std::string_view body, const FreePose& X_WB);

/// Reads the pose of @p body from `data.qpos`.
/// @throws Error as `free_qpos_address`.
FreePose free_pose(const Robot& robot, const mjData& data, std::string_view body);

}  // namespace mjarm
