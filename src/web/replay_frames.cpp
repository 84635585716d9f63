#include "replay_frames.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "mjarm/error.hpp"
#include "recorded_state.hpp"

namespace mjarm::web_detail {
namespace {

std::vector<std::size_t> kept_rows(const std::vector<double>& t, double rate) {
  std::vector<std::size_t> rows;
  if (t.empty()) return rows;
  rows.push_back(0);
  // frame k at t0 + k/rate shows the last row at or before it (a millionth of a period of slack:
  // 1/60 s is no whole number of 2 ms steps in binary)
  const double slack = 1e-6 / rate;
  std::size_t row = 0;
  for (long k = 1;; ++k) {
    const double target = t.front() + static_cast<double>(k) / rate;
    if (target > t.back() + slack) break;
    while (row + 1 < t.size() && t[row + 1] <= target + slack) ++row;
    if (row != rows.back()) rows.push_back(row);
  }
  if (rows.back() != t.size() - 1) rows.push_back(t.size() - 1);
  return rows;
}

}  // namespace

ReplayFrames replay_frames(const mjModel& m, const plot::CsvTable& state, double rate) {
  const std::vector<std::string> columns = qpos_columns(m);
  const std::size_t recorded = state.columns_with_prefix("q.").size();
  for (const std::string& column : columns) {
    if (!state.has(column)) {
      throw Error("replay-html: the model does not match the recording: '" + state.path().string() +
                  "' has no column '" + column + "' (the model has " + std::to_string(m.nq) +
                  " qpos coordinates, the recording " + std::to_string(recorded) + " q.* columns)");
    }
  }
  if (recorded != columns.size()) {
    throw Error("replay-html: the model does not match the recording: the model has " +
                std::to_string(m.nq) + " qpos coordinates, '" + state.path().string() + "' " +
                std::to_string(recorded) + " q.* columns");
  }
  const std::vector<double> t = state.numbers("t");
  const std::vector<std::size_t> rows = kept_rows(t, rate);
  std::vector<std::vector<double>> q;
  q.reserve(columns.size());
  for (const std::string& column : columns) q.push_back(state.numbers(column));

  std::unique_ptr<mjData, decltype(&mj_deleteData)> data(mj_makeData(&m), mj_deleteData);
  if (!data) throw Error("replay-html: MuJoCo could not allocate the data of the model");
  mjData& d = *data;
  ReplayFrames frames;
  frames.time.reserve(rows.size());
  frames.pos.reserve(rows.size() * static_cast<std::size_t>(m.nbody) * 3);
  frames.quat.reserve(rows.size() * static_cast<std::size_t>(m.nbody) * 4);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::size_t row = rows[k];
    for (int i = 0; i < m.nq; ++i) d.qpos[i] = q[static_cast<std::size_t>(i)][row];
    mj_kinematics(&m, &d);
    for (int b = 0; b < m.nbody; ++b) {
      for (int i = 0; i < 3; ++i) frames.pos.push_back(static_cast<float>(d.xpos[3 * b + i]));
      for (int i = 0; i < 4; ++i) frames.quat.push_back(static_cast<float>(d.xquat[4 * b + i]));
    }
    frames.time.push_back(t[row]);
    if (k > 0) frames.largest_gap = std::max(frames.largest_gap, t[row] - t[rows[k - 1]]);
  }
  return frames;
}

}  // namespace mjarm::web_detail
