#include "replay_plots.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base64.hpp"

namespace mjarm::web_detail {
namespace {

// for each frame time, the index of the last row at or before it (0 before the first row)
std::vector<std::size_t> rows_at(const std::vector<double>& t, const std::vector<double>& times) {
  std::vector<std::size_t> rows;
  rows.reserve(times.size());
  for (double time : times) {
    const auto after = std::upper_bound(t.begin(), t.end(), time + 1e-12);
    rows.push_back(after == t.begin() ? 0 : static_cast<std::size_t>(after - t.begin() - 1));
  }
  return rows;
}

struct Series {
  std::string label;
  std::vector<float> values;
};

nlohmann::json plot_json(const std::string& title, const std::string& unit,
                         const std::vector<Series>& series) {
  nlohmann::json list = nlohmann::json::array();
  for (const Series& s : series)
    list.push_back({{"label", s.label}, {"values", base64_floats(s.values)}});
  return {{"title", title}, {"unit", unit}, {"series", list}};
}

}  // namespace

ReplayPlots replay_plots(const plot::Recording& recording, const std::vector<double>& frame_times) {
  const plot::CsvTable& state = recording.state();
  const plot::CsvTable& task = recording.task();
  const std::vector<std::size_t> state_rows = rows_at(state.numbers("t"), frame_times);
  const std::vector<std::size_t> task_rows = rows_at(task.numbers("t"), frame_times);
  auto sample = [](const std::vector<double>& column, const std::vector<std::size_t>& rows,
                   double scale) {
    std::vector<float> values;
    values.reserve(rows.size());
    for (std::size_t row : rows) values.push_back(static_cast<float>(column[row] * scale));
    return values;
  };
  ReplayPlots plots;
  nlohmann::json& list = plots.json["plots"] = nlohmann::json::array();

  if (task.has("err.vx") && task.has("err.wz")) {
    std::vector<Series> error{{"position [mm]", {}}, {"orientation [mrad]", {}}};
    std::vector<std::vector<double>> e;
    for (const char* axis : {"err.vx", "err.vy", "err.vz", "err.wx", "err.wy", "err.wz"})
      e.push_back(task.numbers(axis));
    for (std::size_t row : task_rows) {
      const double linear = std::hypot(e[0][row], e[1][row], e[2][row]);
      const double angular = std::hypot(e[3][row], e[4][row], e[5][row]);
      error[0].values.push_back(static_cast<float>(1e3 * linear));
      error[1].values.push_back(static_cast<float>(1e3 * angular));
    }
    list.push_back(plot_json("tracking error", "", error));
  }

  // joint torque (gear · actuator force) as a fraction of its limit: ±1 is the limit
  std::vector<Series> torques;
  for (const plot::RecordedActuator& a : recording.actuators()) {
    const std::string column = "force." + a.name;
    if (!a.force_range || !state.has(column)) continue;
    const double limit = std::max(std::abs(a.force_range->first), std::abs(a.force_range->second));
    if (!(limit > 0.0)) continue;
    torques.push_back({a.name, sample(state.numbers(column), state_rows, 1.0 / limit)});
  }
  if (!torques.empty()) list.push_back(plot_json("actuator force / its limit", "", torques));

  if (state.has("contact.normal_force")) {
    list.push_back(plot_json(
        "contact force (all contacts)", "N",
        {{"normal force", sample(state.numbers("contact.normal_force"), state_rows, 1.0)}}));
  }
  if (task.has("grasp.force")) {
    list.push_back(
        plot_json("gripper force", "N",
                  {{"grasp force", sample(task.numbers("grasp.force"), task_rows, 1.0)}}));
  }

  std::vector<float> time(frame_times.begin(), frame_times.end());
  plots.json["plot_time"] = base64_floats(time);
  plots.count = static_cast<int>(list.size());
  return plots;
}

}  // namespace mjarm::web_detail
