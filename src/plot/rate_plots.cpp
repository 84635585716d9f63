#include "mjarm/plot/rate_plots.hpp"

#include <algorithm>
#include <cmath>

#include "figures.hpp"
#include "mjarm/error.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

void check_name(const std::string& kind, const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    throw Error(kind + ": the name '" + name + "' is not a plain file stem");
}

/// `set xtics ('a' 0, 'b' 1, …)` for categories at 0, 1, …
std::string category_tics(const char* axis, const std::vector<std::string>& labels) {
  std::string tics = std::string("set ") + axis + "tics (";
  for (std::size_t k = 0; k < labels.size(); ++k)
    tics += (k ? ", " : "") + gnuplot_string(labels[k]) + " " + std::to_string(k);
  return tics + ")\n";
}

}  // namespace

PlotInfo plot_rates(const RateFigure& f, const fs::path& out_dir, const PlotOptions& options) {
  detail::check_single_figure(options);
  check_name("rate plot", f.name);
  if (f.points.empty()) throw Error("rate plot '" + f.name + "': no points");
  for (const RatePoint& p : f.points)
    if (!(p.low >= 0.0 && p.low <= p.rate && p.rate <= p.high && p.high <= 1.0))
      throw Error("rate plot '" + f.name + "': point '" + p.label +
                  "' is not 0 ≤ low ≤ rate ≤ high ≤ 1");
  find_gnuplot();
  detail::PlotFiles files(out_dir);
  std::string data = "# index, rate, low, high, trials\n";
  std::vector<std::string> labels;
  for (std::size_t k = 0; k < f.points.size(); ++k) {
    const RatePoint& p = f.points[k];
    data += std::to_string(k) + " " + detail::gp_number(p.rate) + " " + detail::gp_number(p.low) +
            " " + detail::gp_number(p.high) + " " + std::to_string(p.trials) + "\n";
    labels.push_back(p.label);
  }
  const fs::path data_file = files.data_dir() / (f.name + ".dat");
  PlotInfo info{f.name, files.out() / (f.name + ".png"), f.title, {f.ylabel}, {}};
  std::string script = detail::single_figure_preamble(
      info.path, options, "drawn by mjarm (plot_rates); run `gnuplot " + f.name + ".gp` to redraw");
  script += "set title " + gnuplot_string(f.title) + "\nset xlabel " + gnuplot_string(f.xlabel) +
            "\nset ylabel " + gnuplot_string(f.ylabel) + "\nset yrange [0:1.08]\n";
  script += "set xrange [-0.5:" + std::to_string(f.points.size() - 1) + ".5]\n" +
            category_tics("x", labels) + "set key off\n";
  const std::string file = gnuplot_string(data_file.string());
  script += "plot " + file + " using 1:2:3:4 with yerrorlines lw 2 pt 7 ps 1.2 lc rgb " +
            detail::line_color(0) + ", " + file +
            " using 1:4:(sprintf('n = %d', $5)) with labels offset 0,0.8 font ',10'\n"
            "unset output\n";
  detail::draw_single_figure(files, data_file, data, files.data_dir() / (f.name + ".gp"), script,
                             info.path, options.timeout_s);
  return info;
}

PlotInfo plot_heat_map(const HeatMapFigure& f, const fs::path& out_dir,
                       const PlotOptions& options) {
  detail::check_single_figure(options);
  check_name("heat map", f.name);
  if (f.columns.empty() || f.rows.empty() || f.rates.size() != f.rows.size())
    throw Error("heat map '" + f.name + "': the grid does not match its categories");
  for (const auto& row : f.rates) {
    if (row.size() != f.columns.size())
      throw Error("heat map '" + f.name + "': the grid does not match its categories");
    for (const double r : row)
      if (!std::isnan(r) && !(r >= 0.0 && r <= 1.0))
        throw Error("heat map '" + f.name + "': a rate outside [0, 1]");
  }
  find_gnuplot();
  detail::PlotFiles files(out_dir);
  std::string data = "# column, row, rate (NaN: no trials)\n";
  for (std::size_t r = 0; r < f.rows.size(); ++r)
    for (std::size_t c = 0; c < f.columns.size(); ++c)
      data += std::to_string(c) + " " + std::to_string(r) + " " + detail::gp_number(f.rates[r][c]) +
              "\n";
  const fs::path data_file = files.data_dir() / (f.name + ".dat");
  PlotInfo info{f.name, files.out() / (f.name + ".png"), f.title, {"success rate"}, {}};
  std::string script = detail::single_figure_preamble(
      info.path, options,
      "drawn by mjarm (plot_heat_map); run `gnuplot " + f.name + ".gp` to redraw");
  script += "set title " + gnuplot_string(f.title) + "\nset xlabel " + gnuplot_string(f.xlabel) +
            "\nset ylabel " + gnuplot_string(f.ylabel) + "\n";
  script += "set xrange [-0.5:" + std::to_string(f.columns.size() - 1) +
            ".5]\nset yrange [-0.5:" + std::to_string(f.rows.size() - 1) + ".5]\n" +
            category_tics("x", f.columns) + category_tics("y", f.rows) +
            "set cbrange [0:1]\nset cblabel 'success rate'\nset palette defined (0 '#d73027', "
            "0.5 '#fee08b', 1 '#1a9850')\nunset grid\nset key off\n";
  const std::string file = gnuplot_string(data_file.string());
  script += "plot " + file + " using 1:2:3 with image, " + file +
            " using 1:2:($3 == $3 ? sprintf('%.2f', $3) : '') with labels font ',11'\n"
            "unset output\n";
  detail::draw_single_figure(files, data_file, data, files.data_dir() / (f.name + ".gp"), script,
                             info.path, options.timeout_s);
  return info;
}

PlotInfo plot_histograms(const HistogramFigure& f, const fs::path& out_dir,
                         const PlotOptions& options) {
  detail::check_single_figure(options);
  check_name("histograms", f.name);
  if (f.histograms.empty() || f.histograms.size() > 12)
    throw Error("histograms '" + f.name + "': 1 … 12 panels, got " +
                std::to_string(f.histograms.size()));
  if (f.bins < 1 || f.bins > 1000)
    throw Error("histograms '" + f.name + "': 1 … 1000 bins, got " + std::to_string(f.bins));
  find_gnuplot();
  detail::PlotFiles files(out_dir);
  // one block per panel (gnuplot's `index`): bin centre, count, bin width
  std::string data;
  PlotInfo info{f.name, files.out() / (f.name + ".png"), f.title, {}, {}};
  std::vector<std::size_t> counts;
  for (const Histogram& h : f.histograms) {
    std::vector<double> v;
    for (const double x : h.values)
      if (std::isfinite(x)) v.push_back(x);
    counts.push_back(v.size());
    data += "# " + h.label + "\n";
    if (v.empty()) {
      data += "0 0 1\n\n\n";
      continue;
    }
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const double width = *hi > *lo ? (*hi - *lo) / f.bins : 1.0;
    std::vector<long long> bins(static_cast<std::size_t>(f.bins), 0);
    for (const double x : v)
      ++bins[std::min<std::size_t>(static_cast<std::size_t>((x - *lo) / width), bins.size() - 1)];
    for (std::size_t b = 0; b < bins.size(); ++b)
      data += detail::gp_number(*lo + (static_cast<double>(b) + 0.5) * width) + " " +
              std::to_string(bins[b]) + " " + detail::gp_number(width) + "\n";
    data += "\n\n";
    info.series.push_back(h.label);
  }
  const fs::path data_file = files.data_dir() / (f.name + ".dat");
  std::string script = detail::single_figure_preamble(
      info.path, options,
      "drawn by mjarm (plot_histograms); run `gnuplot " + f.name + ".gp` to redraw");
  const std::size_t n = f.histograms.size();
  const std::size_t columns = n <= 2 ? n : n <= 4 ? 2 : 3;
  const std::size_t rows = (n + columns - 1) / columns;
  script += "set style fill solid 0.6 border -1\nset key off\nset ylabel 'trials'\n";
  script += "set multiplot layout " + std::to_string(rows) + "," + std::to_string(columns) +
            " title " + gnuplot_string(f.title) + " font ',14'\n";
  for (std::size_t k = 0; k < n; ++k)
    script += "set title " +
              gnuplot_string(f.histograms[k].label + " (" + std::to_string(counts[k]) + ")") +
              "\nplot " + gnuplot_string(data_file.string()) + " index " + std::to_string(k) +
              " using 1:2:3 with boxes lc rgb " + detail::line_color(k) + "\n";
  script += "unset multiplot\nunset output\n";
  detail::draw_single_figure(files, data_file, data, files.data_dir() / (f.name + ".gp"), script,
                             info.path, options.timeout_s);
  return info;
}

}  // namespace mjarm::plot
