#include "mjarm/plot/trajectory_plot.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "figures.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

void check_trajectory_series(const TrajectorySeries& s) {
  const std::size_t n = s.axes.size();
  if (n == 0) throw Error("trajectory plot: no axes");
  if (s.t.empty()) throw Error("trajectory plot: no samples");
  for (std::size_t k = 0; k < 4; ++k) {
    if (s.values[k].size() != n)
      throw Error("trajectory plot: derivative " + std::to_string(k) + " has " +
                  std::to_string(s.values[k].size()) + " axes, expected " + std::to_string(n));
    for (std::size_t i = 0; i < n; ++i)
      if (s.values[k][i].size() != s.t.size())
        throw Error("trajectory plot: axis '" + s.axes[i] + "' derivative " + std::to_string(k) +
                    " has " + std::to_string(s.values[k][i].size()) + " samples, expected " +
                    std::to_string(s.t.size()));
    if (!s.limits[k].empty() && s.limits[k].size() != n)
      throw Error("trajectory plot: derivative " + std::to_string(k) + " has " +
                  std::to_string(s.limits[k].size()) + " limits, expected " + std::to_string(n));
  }
}

}  // namespace

PlotInfo plot_trajectory(const TrajectorySeries& series, const fs::path& out_dir,
                         const PlotOptions& options) {
  detail::check_single_figure(options);
  check_trajectory_series(series);
  find_gnuplot();  // fail before anything is written
  detail::PlotFiles files(out_dir);  // removed again unless the figure is drawn
  const fs::path& out = files.out();
  const fs::path& data_dir = files.data_dir();

  const std::size_t n = series.axes.size();
  // one row per sample: t, then positions, velocities, accelerations, jerks of every axis
  std::string data = "# t [s], then q, qd, qdd, qddd of each axis\n";
  for (std::size_t s = 0; s < series.t.size(); ++s) {
    data += detail::gp_number(series.t[s]);
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t i = 0; i < n; ++i) data += " " + detail::gp_number(series.values[k][i][s]);
    data += "\n";
  }
  const fs::path data_file = data_dir / "trajectory.dat";

  PlotInfo info;
  info.name = "trajectory";
  info.path = out / "trajectory.png";
  info.title = series.title;
  const std::array<const char*, 4> names{"position", "velocity", "acceleration", "jerk"};
  const std::array<std::string, 4> units{series.unit, series.unit + "/s", series.unit + "/s²",
                                         series.unit + "/s³"};
  std::string script = detail::single_figure_preamble(
      info.path, options, "drawn by `mjarm traj --plot`; run `gnuplot trajectory.gp` to redraw");
  const double t0 = series.t.front();
  const double t1 = series.t.back() > t0 ? series.t.back() : t0 + 1e-3;
  script += "set xrange [" + detail::gp_number(t0) + ":" + detail::gp_number(t1) + "]\n";
  // the same margins in every panel keep their time axes aligned; limits off the frame; the
  // legend stands in the right margin, wide enough for the longest axis name, never on a curve
  std::size_t longest = 0;
  for (const std::string& axis : series.axes) longest = std::max(longest, axis.size());
  const std::size_t right_margin = longest + 9;  // the sample line, its gaps, the border
  script += "set lmargin 12\nset rmargin " + std::to_string(right_margin) +
            "\nset offsets 0, 0, graph 0.08, graph 0.08\n";
  script += "set multiplot layout 4,1 title " + gnuplot_string(series.title) + " font ',14'\n";
  for (std::size_t k = 0; k < 4; ++k) {
    script += "set ylabel " + gnuplot_string(std::string(names[k]) + " [" + units[k] + "]") + "\n";
    script +=
        k == 0 ? "set key outside right top vertical Left reverse samplen 2\n" : "unset key\n";
    if (k < 3)
      script += "set xlabel ''\n";
    else
      script += "set xlabel 'time t [s]'\n";
    std::string plot = "plot ";
    bool limited = false;
    for (std::size_t i = 0; i < n; ++i) {
      const std::string column = std::to_string(2 + k * n + i);
      plot += (i ? ", " : "") + gnuplot_string(data_file.string()) + " using 1:" + column +
              " with lines lw 2 lc rgb " + detail::line_color(i) + " title " +
              gnuplot_string(series.axes[i]);
      const double limit = series.limits[k].empty() ? NAN : series.limits[k][i];
      if (k > 0 && std::isfinite(limit)) {
        limited = true;
        for (const double sign : {1.0, -1.0})
          plot += ", " + detail::gp_number(sign * limit) + " with lines dt 2 lw 1.5 lc rgb " +
                  detail::line_color(i) + " notitle";
      }
    }
    info.series.push_back(std::string(names[k]) + (limited ? " (dashed: ±limit)" : ""));
    script += plot + "\n";
  }
  script += "unset multiplot\nunset output\n";
  if (std::all_of(series.limits[3].begin(), series.limits[3].end(),
                  [](double v) { return !std::isfinite(v); }))
    info.notes.push_back("no jerk limit given");

  const fs::path script_file = data_dir / "trajectory.gp";
  detail::draw_single_figure(files, data_file, data, script_file, script, info.path,
                             options.timeout_s);
  return info;
}

}  // namespace mjarm::plot
