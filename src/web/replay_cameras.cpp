#include "replay_cameras.hpp"

#include <memory>
#include <string>

#include "base64.hpp"
#include "mjarm/error.hpp"
#include "recorded_state.hpp"

namespace mjarm::web_detail {

bool camera_moves(const mjModel& m, int c) { return m.cam_mode[c] != mjCAMLIGHT_FIXED; }

nlohmann::json replay_camera_poses(const mjModel& m, const plot::CsvTable& state,
                                   const std::vector<double>& frame_times) {
  nlohmann::json out = {{"cameras", nlohmann::json::array()}};
  std::vector<int> moving;
  for (int c = 0; c < m.ncam; ++c)
    if (camera_moves(m, c)) moving.push_back(c);
  if (moving.empty()) return out;

  std::vector<std::vector<double>> qpos;
  for (const std::string& column : qpos_columns(m)) qpos.push_back(state.numbers(column));
  const std::vector<std::size_t> rows = rows_at_or_before(state.numbers("t"), frame_times);
  std::unique_ptr<mjData, decltype(&mj_deleteData)> data(mj_makeData(&m), mj_deleteData);
  if (!data) throw Error("replay-html: MuJoCo could not allocate the data of the model");
  mjData& d = *data;
  std::vector<float> pos, quat;
  pos.reserve(rows.size() * moving.size() * 3);
  quat.reserve(rows.size() * moving.size() * 4);
  for (std::size_t row : rows) {
    for (int i = 0; i < m.nq; ++i) d.qpos[i] = qpos[static_cast<std::size_t>(i)][row];
    // what mj_fwdPosition computes before the cameras: the bodies, then the subtrees' centres of
    // mass (trackcom, targetbodycom)
    mj_kinematics(&m, &d);
    mj_comPos(&m, &d);
    mj_camlight(&m, &d);
    for (int c : moving) {
      mjtNum q[4];
      mju_mat2Quat(q, d.cam_xmat + 9 * c);
      for (int i = 0; i < 3; ++i) pos.push_back(static_cast<float>(d.cam_xpos[3 * c + i]));
      for (int i = 0; i < 4; ++i) quat.push_back(static_cast<float>(q[i]));
    }
  }
  out["cameras"] = moving;
  out["pos"] = base64_floats(pos);
  out["quat"] = base64_floats(quat);
  return out;
}

}  // namespace mjarm::web_detail
