#include "figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mjarm/error.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot::detail {
namespace {

namespace fs = std::filesystem;

std::string fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}

double peak(const std::vector<double>& v, std::size_t* at = nullptr) {
  double best = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (std::isfinite(v[i]) && std::abs(v[i]) >= best) {
      best = std::abs(v[i]);
      if (at != nullptr) *at = i;
    }
  }
  return best;
}

// Maps an actuator force into [-1, 1] of its range: lower → −1, upper → +1, and 0 → 0 when the
// range straddles zero (so that an asymmetric range still shows the sign of the torque).
double normalized(double f, double lower, double upper) {
  if (lower < 0.0 && upper > 0.0) return f >= 0.0 ? f / upper : -f / lower;
  return 2.0 * (f - lower) / (upper - lower) - 1.0;
}

}  // namespace

Figure tracking_error_figure(const Recording& recording, const fs::path& data_dir) {
  const CsvTable& task = recording.task();
  const std::vector<double> t = task.numbers("t");
  std::vector<std::vector<double>> e;
  for (const char* c : {"err.vx", "err.vy", "err.vz", "err.wx", "err.wy", "err.wz"})
    e.push_back(task.numbers(c));
  Figure f;
  f.info.name = "tracking_error";
  const std::string frame = recording.frame().empty() ? "end effector" : recording.frame();
  f.info.title = "End-effector tracking error of " + frame + " (" + describe(recording) + ")";
  std::vector<double> position(t.size()), orientation(t.size());
  std::string data = "# t [s]  position error [mm]  orientation error [mrad]\n";
  for (std::size_t i = 0; i < t.size(); ++i) {
    position[i] = 1e3 * std::sqrt(e[0][i] * e[0][i] + e[1][i] * e[1][i] + e[2][i] * e[2][i]);
    orientation[i] = 1e3 * std::sqrt(e[3][i] * e[3][i] + e[4][i] * e[4][i] + e[5][i] * e[5][i]);
    data += gp_number(t[i]) + " " + gp_number(position[i]) + " " + gp_number(orientation[i]) + "\n";
  }
  const fs::path file = data_dir / "tracking_error.dat";
  f.data.emplace_back(file, data);
  f.info.series = {"position error |p_ref - p| [mm]", "orientation error |log(R_ref R^T)| [mrad]"};
  std::size_t at = 0;
  const double p_peak = peak(position, &at);
  f.info.notes.push_back("peak position error " + fixed(p_peak, 3) +
                         " mm at t = " + fixed(t[at], 3) + " s");
  f.info.notes.push_back("final position error " + fixed(position.back(), 4) +
                         " mm, orientation error " + fixed(orientation.back(), 4) + " mrad");
  f.script = time_figure_preamble(recording, f.info.title) +
             "set ylabel 'position error [mm]'\n"
             "set y2label 'orientation error [mrad]'\n"
             "set y2tics\n"
             "set yrange [0:*]\nset y2range [0:*]\n"
             "set key outside below center horizontal width -2\nset bmargin 5.5\n"
             "plot " +
             gnuplot_string(file.string()) + " using 1:2 with lines lw 2.5 lc rgb " +
             line_color(0) + " title " + gnuplot_string(f.info.series[0]) +
             ", \\\n     '' using 1:3 axes x1y2 with lines lw 2 dt 2 lc rgb " + line_color(3) +
             " title " + gnuplot_string(f.info.series[1]) + "\n";
  return f;
}

Figure joint_torques_figure(const Recording& recording, const fs::path& data_dir) {
  const CsvTable& state = recording.state();
  const std::vector<double> t = state.numbers("t");
  // the actuators of the summary; an older summary without them: every force.* column, no limits
  std::vector<RecordedActuator> actuators = recording.actuators();
  if (actuators.empty()) {
    for (const std::string& column : state.columns_with_prefix("force."))
      actuators.push_back({column.substr(6), "", 1.0, std::nullopt});
  }
  if (actuators.empty())
    throw Error(quoted(recording.directory() / "state.csv") +
                " has no force.<actuator> column: no torques to plot");
  const bool all_limited =
      std::all_of(actuators.begin(), actuators.end(),
                  [](const RecordedActuator& a) { return a.force_range.has_value(); });
  Figure f;
  f.info.name = "joint_torques";
  f.info.title =
      std::string(all_limited ? "Joint torques relative to their limits" : "Joint torques") + " (" +
      describe(recording) + ")";
  std::vector<std::vector<double>> y;
  for (const RecordedActuator& a : actuators) {
    std::vector<double> force = state.numbers("force." + a.name);
    for (double& v : force)
      v = all_limited ? normalized(v, a.force_range->first, a.force_range->second) : a.gear * v;
    y.push_back(std::move(force));
  }
  std::string data = "# t [s]" + std::string(all_limited ? "  tau/tau_max per actuator\n"
                                                         : "  tau [N m] per actuator\n");
  for (std::size_t i = 0; i < t.size(); ++i) {
    data += gp_number(t[i]);
    for (const auto& column : y) data += " " + gp_number(column[i]);
    data += "\n";
  }
  const fs::path file = data_dir / "joint_torques.dat";
  f.data.emplace_back(file, data);

  // saturated ticks (task.csv sat.<actuator>), drawn at the torque of the nearest state row
  std::string saturation;
  std::size_t saturated = 0;
  const CsvTable& task = recording.task();
  const std::vector<double> task_t = task.numbers("t");
  for (std::size_t k = 0; k < actuators.size(); ++k) {
    const std::string column = "sat." + actuators[k].name;
    if (!task.has(column)) continue;
    const std::vector<double> sat = task.numbers(column);
    for (std::size_t i = 0; i < sat.size(); ++i) {
      if (!(sat[i] > 0.5)) continue;
      const auto it = std::lower_bound(t.begin(), t.end(), task_t[i] - 1e-12);
      const std::size_t row =
          std::min<std::size_t>(static_cast<std::size_t>(it - t.begin()), t.size() - 1);
      saturation += gp_number(task_t[i]) + " " + gp_number(y[k][row]) + "\n";
      ++saturated;
    }
  }
  const fs::path sat_file = data_dir / "joint_torques_saturated.dat";
  if (saturated > 0)
    f.data.emplace_back(sat_file, "# t [s]  value at a saturated tick\n" + saturation);

  std::string plot = "plot ";
  for (std::size_t k = 0; k < actuators.size(); ++k) {
    const double p = peak(y[k]);
    const std::string name = actuators[k].joint.empty() ? actuators[k].name : actuators[k].joint;
    const std::string title = all_limited ? name + " (peak " + fixed(100.0 * p, 0) + " %)"
                                          : name + " (peak " + fixed(p, 1) + " N m)";
    f.info.series.push_back(title);
    plot += std::string(k ? ", \\\n     " : "") + gnuplot_string(file.string()) +
            " using 1:" + std::to_string(k + 2) + " with lines lw 2 lc rgb " + line_color(k) +
            " title " + gnuplot_string(title);
  }
  if (all_limited) {
    plot +=
        ", \\\n     1 with lines lw 2 dt 2 lc rgb '#c00000' title 'limit (+/-1)', -1 with lines lw "
        "2 dt 2 lc rgb '#c00000' notitle";
    f.info.series.push_back("limit (+/-1)");
  } else {
    f.info.notes.push_back(
        "not every actuator has a force range in summary.json: torques are drawn in N m");
    for (std::size_t k = 0; k < actuators.size(); ++k) {
      if (!actuators[k].force_range) continue;
      for (double limit : {actuators[k].force_range->first, actuators[k].force_range->second})
        plot += ", \\\n     " + gp_number(actuators[k].gear * limit) +
                " with lines lw 1.5 dt 2 lc rgb " + line_color(k) + " notitle";
    }
  }
  if (saturated > 0) {
    // first, so that the curves stay visible through a run of saturated ticks
    plot = "plot " + gnuplot_string(sat_file.string()) +
           " using 1:2 with points pt 6 ps 1.2 lw 1.5 lc rgb 'black' title 'saturated tick "
           "(clipped)', \\\n     " +
           plot.substr(5);
    f.info.series.insert(f.info.series.begin(), "saturated tick (clipped)");
  }
  f.info.notes.push_back(saturated > 0
                             ? std::to_string(saturated) + " saturated actuator ticks marked"
                             : "no saturated ticks");
  f.script = time_figure_preamble(recording, f.info.title) +
             (all_limited ? "set ylabel 'torque / limit  tau / tau_max [-]'\nset yrange "
                            "[-1.15:1.15]\nset ytics 0.25\n"
                          : "set ylabel 'joint torque tau [N m]'\n") +
             "set key outside right top\n" + plot + "\n";
  return f;
}

Figure contact_force_figure(const Recording& recording, const fs::path& data_dir) {
  const CsvTable& state = recording.state();
  const std::vector<double> t = state.numbers("t");
  const std::vector<double> force = state.numbers("contact.normal_force");
  const std::vector<double> count = state.numbers("contact.count");
  Figure f;
  f.info.name = "contact_force";
  f.info.title = "Contact force, all contacts of the model (" + describe(recording) + ")";
  std::string data = "# t [s]  normal force sum [N]  contacts\n";
  for (std::size_t i = 0; i < t.size(); ++i)
    data += gp_number(t[i]) + " " + gp_number(force[i]) + " " + gp_number(count[i]) + "\n";
  const fs::path file = data_dir / "contact_force.dat";
  f.data.emplace_back(file, data);
  const bool forces =
      std::any_of(force.begin(), force.end(), [](double v) { return std::isfinite(v); });
  const double peak_force = peak(force), peak_count = peak(count);
  std::string extra;
  if (!forces) {
    f.info.notes.push_back(
        "kinematic run: no contact forces were computed, only contacts are counted");
    extra +=
        "set label 100 'kinematic run: no contact forces' at graph 0.5, 0.55 center font ',18' tc "
        "rgb '#707070' front\n";
  }
  if (peak_count == 0.0) {
    f.info.notes.push_back("no contact during the run");
    extra +=
        "set label 101 'no contact during the run' at graph 0.5, 0.5 center font ',20' tc rgb "
        "'#707070' front\n"
        "set yrange [0:1]\nset y2range [0:1]\n";
  } else {
    f.info.notes.push_back("peak normal force " + fixed(peak_force, 2) + " N, up to " +
                           fixed(peak_count, 0) + " contacts at once");
    extra += "set yrange [0:*]\nset y2range [0:" +
             gp_number(std::max(1.0, std::ceil(1.15 * peak_count))) + "]\n";
  }
  f.info.series = {"sum of normal forces [N]", "active contacts"};
  f.script = time_figure_preamble(recording, f.info.title) +
             "set ylabel 'normal force [N]'\nset y2label 'contacts [count]'\nset y2tics\nset key "
             "outside below center horizontal width -2\nset bmargin 5.5\n" +
             extra + "plot " + gnuplot_string(file.string()) +
             " using 1:2 with lines lw 2.5 lc rgb " + line_color(0) + " title " +
             gnuplot_string(f.info.series[0]) +
             ", \\\n     '' using 1:3 axes x1y2 with steps lw 1.5 lc rgb " + line_color(7) +
             " title " + gnuplot_string(f.info.series[1]) + "\n";
  return f;
}

}  // namespace mjarm::plot::detail
