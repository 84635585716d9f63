#include "replay_plots.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base64.hpp"

namespace mjarm::web_detail {
namespace {

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

std::vector<float> scaled(const std::vector<double>& values, double scale) {
  std::vector<float> out;
  out.reserve(values.size());
  for (double v : values) out.push_back(static_cast<float>(v * scale));
  return out;
}

constexpr const char* kErrorColumns[] = {"err.vx", "err.vy", "err.vz",
                                         "err.wx", "err.wy", "err.wz"};

}  // namespace

std::vector<std::string> plot_state_columns(const plot::Recording& recording) {
  std::vector<std::string> columns;
  for (const plot::RecordedActuator& a : recording.actuators()) {
    const std::string column = "force." + a.name;
    if (a.force_range && recording.state().has(column)) columns.push_back(column);
  }
  if (recording.state().has("contact.normal_force")) columns.emplace_back("contact.normal_force");
  return columns;
}

std::vector<std::string> plot_task_columns() {
  std::vector<std::string> columns(std::begin(kErrorColumns), std::end(kErrorColumns));
  columns.emplace_back("grasp.force");
  return columns;
}

ReplayPlots replay_plots(const plot::Recording& recording, const std::vector<double>& frame_times,
                         const std::map<std::string, std::vector<double>>& state,
                         const std::map<std::string, std::vector<double>>& task) {
  ReplayPlots plots;
  nlohmann::json& list = plots.json["plots"] = nlohmann::json::array();

  if (std::all_of(std::begin(kErrorColumns), std::end(kErrorColumns),
                  [&](const char* c) { return task.count(c) != 0; })) {
    std::vector<Series> error{{"position [mm]", {}}, {"orientation [mrad]", {}}};
    std::vector<const std::vector<double>*> e;
    for (const char* axis : kErrorColumns) e.push_back(&task.at(axis));
    for (std::size_t f = 0; f < frame_times.size(); ++f) {
      const double linear = std::hypot((*e[0])[f], (*e[1])[f], (*e[2])[f]);
      const double angular = std::hypot((*e[3])[f], (*e[4])[f], (*e[5])[f]);
      error[0].values.push_back(static_cast<float>(1e3 * linear));
      error[1].values.push_back(static_cast<float>(1e3 * angular));
    }
    list.push_back(plot_json("tracking error", "", error));
  }

  // joint torque (gear · actuator force) as a fraction of its limit: ±1 is the limit
  std::vector<Series> torques;
  for (const plot::RecordedActuator& a : recording.actuators()) {
    const auto column = state.find("force." + a.name);
    if (!a.force_range || column == state.end()) continue;
    const double limit = std::max(std::abs(a.force_range->first), std::abs(a.force_range->second));
    if (!(limit > 0.0)) continue;
    torques.push_back({a.name, scaled(column->second, 1.0 / limit)});
  }
  if (!torques.empty()) list.push_back(plot_json("actuator force / its limit", "", torques));

  if (const auto force = state.find("contact.normal_force"); force != state.end()) {
    list.push_back(plot_json("contact force (all contacts)", "N",
                             {{"normal force", scaled(force->second, 1.0)}}));
  }
  if (const auto grasp = task.find("grasp.force"); grasp != task.end()) {
    list.push_back(plot_json("gripper force", "N", {{"grasp force", scaled(grasp->second, 1.0)}}));
  }

  std::vector<float> time(frame_times.begin(), frame_times.end());
  plots.json["plot_time"] = base64_floats(time);
  plots.count = static_cast<int>(list.size());
  return plots;
}

}  // namespace mjarm::web_detail
