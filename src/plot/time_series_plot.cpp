#include "mjarm/plot/time_series_plot.hpp"

#include <algorithm>
#include <cmath>

#include "figures.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

void check_time_series(const TimeSeriesFigure& f) {
  if (f.name.empty() || f.name.find('/') != std::string::npos || f.name == "." || f.name == "..")
    throw Error("time-series plot: the name '" + f.name + "' is not a plain file stem");
  if (f.t.empty()) throw Error("time-series plot '" + f.name + "': no samples");
  if (!std::is_sorted(f.t.begin(), f.t.end()))
    throw Error("time-series plot '" + f.name + "': the instants are not in order");
  if (f.panels.empty() || f.panels.size() > 6)
    throw Error("time-series plot '" + f.name + "': 1 … 6 panels, got " +
                std::to_string(f.panels.size()));
  for (const TimePanel& panel : f.panels) {
    if (panel.series.empty())
      throw Error("time-series plot '" + f.name + "': panel '" + panel.ylabel + "' has no curve");
    for (const TimeSeries& s : panel.series)
      if (s.values.size() != f.t.size())
        throw Error("time-series plot '" + f.name + "': curve '" + s.name + "' has " +
                    std::to_string(s.values.size()) + " values, expected " +
                    std::to_string(f.t.size()));
  }
  for (const TimeBand& b : f.bands)
    if (!(b.end >= b.start))
      throw Error("time-series plot '" + f.name + "': band '" + b.label +
                  "' ends before it starts");
}

}  // namespace

PlotInfo plot_time_series(const TimeSeriesFigure& figure, const fs::path& out_dir,
                          const PlotOptions& options) {
  detail::check_single_figure(options);
  check_time_series(figure);
  find_gnuplot();  // fail before anything is written
  detail::PlotFiles files(out_dir);  // removed again unless the figure is drawn
  const fs::path& out = files.out();
  const fs::path& data_dir = files.data_dir();

  // one row per instant: t, then every curve of every panel in order
  std::string data = "# t [s]";
  for (const TimePanel& panel : figure.panels)
    for (const TimeSeries& s : panel.series) data += ", " + s.name;
  data += "\n";
  for (std::size_t k = 0; k < figure.t.size(); ++k) {
    data += detail::gp_number(figure.t[k]);
    for (const TimePanel& panel : figure.panels)
      for (const TimeSeries& s : panel.series) data += " " + detail::gp_number(s.values[k]);
    data += "\n";
  }
  const fs::path data_file = data_dir / (figure.name + ".dat");

  PlotInfo info;
  info.name = figure.name;
  info.path = out / (figure.name + ".png");
  info.title = figure.title;
  std::string script = detail::single_figure_preamble(
      info.path, options,
      "drawn by mjarm (plot_time_series); run `gnuplot " + figure.name + ".gp` to redraw");
  const double t0 = figure.t.front();
  const double t1 = figure.t.back() > t0 ? figure.t.back() : t0 + 1e-3;
  script += "set xrange [" + detail::gp_number(t0) + ":" + detail::gp_number(t1) + "]\n";
  for (std::size_t k = 0; k < figure.bands.size(); ++k) {
    const TimeBand& b = figure.bands[k];
    const double a = std::max(b.start, t0), e = std::min(b.end, t1);
    if (e > a)
      script += "set object " + std::to_string(k + 1) + " rect from first " + detail::gp_number(a) +
                ", graph 0 to first " + detail::gp_number(e) + ", graph 1 behind fc rgb " +
                detail::band_color(k) + " fs solid 1.0 noborder\n";
  }
  script += "set lmargin 12\nset rmargin 4\nset offsets 0, 0, graph 0.08, graph 0.08\n";
  script += "set multiplot layout " + std::to_string(figure.panels.size()) + ",1 title " +
            gnuplot_string(figure.title) + " font ',14'\n";
  std::size_t column = 2;
  for (std::size_t p = 0; p < figure.panels.size(); ++p) {
    const TimePanel& panel = figure.panels[p];
    script += "set ylabel " + gnuplot_string(panel.ylabel) + "\nset key inside right top\n";
    script += p + 1 < figure.panels.size() ? "set xlabel ''\n" : "set xlabel 'time t [s]'\n";
    // the band names on the first panel only
    for (std::size_t k = 0; k < figure.bands.size(); ++k) {
      const std::string id = std::to_string(k + 1);
      if (p == 0 && figure.bands[k].start >= t0 && figure.bands[k].start < t1)
        script += "set label " + id + " " + gnuplot_string(figure.bands[k].label) + " at first " +
                  detail::gp_number(figure.bands[k].start) +
                  ", graph 0.95 left offset 0.4,0 font ',11' tc rgb '#505050' front\n";
      else
        script += "unset label " + id + "\n";
    }
    std::string plot = "plot ";
    for (std::size_t i = 0; i < panel.series.size(); ++i, ++column) {
      const TimeSeries& s = panel.series[i];
      plot += (i ? ", " : "") + gnuplot_string(data_file.string()) +
              " using 1:" + std::to_string(column) + " with lines lw 2" +
              (s.dashed ? " dt 2" : "") + " lc rgb " + detail::line_color(i) + " title " +
              gnuplot_string(s.name);
      info.series.push_back(panel.ylabel + ": " + s.name);
    }
    script += plot + "\n";
  }
  script += "unset multiplot\nunset output\n";

  detail::draw_single_figure(files, data_file, data, data_dir / (figure.name + ".gp"), script,
                             info.path, options.timeout_s);
  return info;
}

}  // namespace mjarm::plot
