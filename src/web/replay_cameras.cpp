#include "replay_cameras.hpp"

#include "base64.hpp"
#include "replay_frames.hpp"

namespace mjarm::web_detail {

bool camera_moves(const mjModel& m, int c) { return m.cam_mode[c] != mjCAMLIGHT_FIXED; }

nlohmann::json replay_camera_poses(const ReplayFrames& frames) {
  nlohmann::json out = {{"cameras", frames.cameras}};
  if (frames.cameras.empty()) return out;
  out["pos"] = base64_floats(frames.camera_pos);
  out["quat"] = base64_floats(frames.camera_quat);
  return out;
}

}  // namespace mjarm::web_detail
