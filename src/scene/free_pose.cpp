#include "mjarm/scene/free_pose.hpp"

#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {

int free_qpos_address(const Robot& robot, std::string_view body) {
  const mjModel& m = robot.model();
  int joint = -1;
  const int b = try_find_object(m, mjOBJ_BODY, body);
  if (b >= 0) {
    for (int j = m.body_jntadr[b]; j >= 0 && j < m.body_jntadr[b] + m.body_jntnum[b]; ++j)
      if (m.jnt_type[j] == mjJNT_FREE) joint = j;
    if (joint < 0)
      throw Error("body '" + std::string(body) + "' in model '" + robot.name() +
                  "' has no free joint (expected an object added with add_object)");
  } else {
    joint = try_find_object(m, mjOBJ_JOINT, body);
    if (joint < 0) find_object(m, mjOBJ_BODY, body);  // throws, naming the closest bodies
    if (m.jnt_type[joint] != mjJNT_FREE)
      throw Error("joint '" + std::string(body) + "' in model '" + robot.name() +
                  "' is not a free joint");
  }
  return m.jnt_qposadr[joint];
}

void set_free_pose(const Robot& robot, mjData& data, std::string_view body, const FreePose& X_WB) {
  const int adr = free_qpos_address(robot, body);
  double norm = 0.0;
  for (double v : X_WB.p_WB)
    if (!std::isfinite(v)) throw Error("pose of '" + std::string(body) + "' is not finite");
  for (double v : X_WB.quat_WB) {
    if (!std::isfinite(v)) throw Error("pose of '" + std::string(body) + "' is not finite");
    norm += v * v;
  }
  norm = std::sqrt(norm);
  if (norm < 1e-9)
    throw Error("pose of '" + std::string(body) + "': zero quaternion, expected (w, x, y, z)");
  for (int i = 0; i < 3; ++i) data.qpos[adr + i] = X_WB.p_WB[static_cast<std::size_t>(i)];
  for (int i = 0; i < 4; ++i)
    data.qpos[adr + 3 + i] = X_WB.quat_WB[static_cast<std::size_t>(i)] / norm;
}

FreePose free_pose(const Robot& robot, const mjData& data, std::string_view body) {
  const int adr = free_qpos_address(robot, body);
  FreePose pose;
  for (int i = 0; i < 3; ++i) pose.p_WB[static_cast<std::size_t>(i)] = data.qpos[adr + i];
  for (int i = 0; i < 4; ++i) pose.quat_WB[static_cast<std::size_t>(i)] = data.qpos[adr + 3 + i];
  return pose;
}

}  // namespace mjarm
