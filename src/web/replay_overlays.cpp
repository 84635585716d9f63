#include "replay_overlays.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "base64.hpp"
#include "mjarm/error.hpp"
#include "recorded_state.hpp"

namespace mjarm::web_detail {
namespace {

// "ee." or "ref." pose columns at @p rows, as frame-major floats; empty when a column is missing
std::vector<float> poses(const plot::CsvTable& task, const std::string& prefix,
                         const std::vector<std::size_t>& rows) {
  std::vector<std::vector<double>> columns;
  for (const char* c : {"x", "y", "z", "qw", "qx", "qy", "qz"}) {
    if (!task.has(prefix + c)) return {};
    columns.push_back(task.numbers(prefix + c));
  }
  std::vector<float> out;
  out.reserve(rows.size() * 7);
  for (std::size_t row : rows)
    for (const std::vector<double>& column : columns)
      out.push_back(static_cast<float>(column[row]));
  return out;
}

}  // namespace

nlohmann::json replay_overlays(const mjModel& m, const plot::Recording& recording,
                               const std::vector<double>& frame_times) {
  nlohmann::json out;
  const plot::CsvTable& task = recording.task();
  const plot::CsvTable& state = recording.state();
  const std::vector<std::size_t> task_rows = rows_at_or_before(task.numbers("t"), frame_times);
  const std::vector<float> tool = poses(task, "ee.", task_rows);
  const std::vector<float> target = poses(task, "ref.", task_rows);
  if (!tool.empty()) out["tool"] = base64_floats(tool);
  if (!target.empty()) out["target"] = base64_floats(target);

  // the state at each frame, as recorded: qpos, qvel (free/ball joints: 7/4 and 6/3 columns),
  // ctrl; contacts and their forces by mj_forward
  const std::vector<std::size_t> state_rows = rows_at_or_before(state.numbers("t"), frame_times);
  std::vector<std::vector<double>> qpos, qvel, ctrl;
  for (const std::string& column : qpos_columns(m)) qpos.push_back(state.numbers(column));
  for (const std::string& column : qvel_columns(m))
    qvel.push_back(state.has(column) ? state.numbers(column) : std::vector<double>());
  for (int a = 0; a < m.nu; ++a) {
    const char* name = mj_id2name(&m, mjOBJ_ACTUATOR, a);
    const std::string column = std::string("ctrl.") + (name != nullptr ? name : "");
    ctrl.push_back(state.has(column) ? state.numbers(column) : std::vector<double>());
  }
  std::unique_ptr<mjData, decltype(&mj_deleteData)> data(mj_makeData(&m), mj_deleteData);
  if (!data) throw Error("replay-html: MuJoCo could not allocate the data of the model");
  mjData& d = *data;
  std::vector<unsigned> offsets{0};
  std::vector<float> points;
  for (std::size_t row : state_rows) {
    mj_resetData(&m, &d);
    for (int i = 0; i < m.nq; ++i) d.qpos[i] = qpos[static_cast<std::size_t>(i)][row];
    for (int i = 0; i < m.nv; ++i) {
      const std::vector<double>& v = qvel[static_cast<std::size_t>(i)];
      d.qvel[i] = v.empty() ? 0.0 : v[row];
    }
    for (int a = 0; a < m.nu; ++a) {
      const std::vector<double>& c = ctrl[static_cast<std::size_t>(a)];
      d.ctrl[a] = c.empty() ? 0.0 : c[row];
    }
    mj_forward(&m, &d);
    for (int c = 0; c < d.ncon; ++c) {
      const mjContact& contact = d.contact[c];
      if (contact.exclude != 0) continue;
      mjtNum local[6], world[3];
      mj_contactForce(&m, &d, c, local);
      // the contact frame's rows are its axes in world coordinates (normal first)
      mju_mulMatTVec(world, contact.frame, local, 3, 3);
      for (int i = 0; i < 3; ++i) points.push_back(static_cast<float>(contact.pos[i]));
      for (int i = 0; i < 3; ++i) points.push_back(static_cast<float>(world[i]));
    }
    offsets.push_back(static_cast<unsigned>(points.size() / 6));
  }
  out["contacts"] = {{"offsets", base64_uints(offsets)}, {"points", base64_floats(points)}};
  return out;
}

}  // namespace mjarm::web_detail
