#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

#include "figures.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot::detail {

std::string gp_number(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "1e308" : "-1e308";
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof(text), value);
  return ec == std::errc() ? std::string(text, end) : "NaN";
}

std::string line_color(std::size_t k) {
  static const std::array<const char*, 10> colors{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                                  "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                                  "#bcbd22", "#17becf"};
  return std::string("'") + colors[k % colors.size()] + "'";
}

std::string band_color(std::size_t k) {
  static const std::array<const char*, 6> colors{"#dbe9f6", "#fde3c8", "#d9f0d3",
                                                 "#f6d5d5", "#e6dcef", "#f3e8c8"};
  return std::string("'") + colors[k % colors.size()] + "'";
}

std::string describe(const Recording& recording) {
  std::string text = recording.model().empty() ? "unknown model" : recording.model();
  if (!recording.controllers().empty()) text += ", " + recording.controllers().front();
  if (!recording.status().empty()) text += ", run " + recording.status();
  return text;
}

std::pair<double, double> time_range(const Recording& recording) {
  const std::vector<double> t = recording.task().numbers("t");
  double t0 = std::min(recording.start_time(), t.front());
  double t1 = std::max(recording.end_time(), t.back());
  if (!(t1 > t0)) t1 = t0 + 1e-3;  // one tick: still a visible axis
  return {t0, t1};
}

std::string phase_background(const Recording& recording) {
  const std::vector<RecordedEvent> phases = recording.events_of("phase");
  const auto [t0, t1] = time_range(recording);
  std::string s = "set xrange [" + gp_number(t0) + ":" + gp_number(t1) + "]\n";
  for (std::size_t k = 0; k < phases.size(); ++k) {
    const double a = std::max(phases[k].t, t0);
    const double b = k + 1 < phases.size() ? std::min(phases[k + 1].t, t1) : t1;
    const std::string id = std::to_string(k + 1);
    if (b > a) {
      s += "set object " + id + " rect from first " + gp_number(a) + ", graph 0 to first " +
           gp_number(b) + ", graph 1 behind fc rgb " + band_color(k) + " fs solid 1.0 noborder\n";
    }
    // the name at the band's left edge, at the top; a phase starting at the very end is named
    // leftwards of its line so that it stays inside the frame
    const bool at_end = (t1 - a) < 0.08 * (t1 - t0);
    s += "set arrow " + id + " from first " + gp_number(a) + ", graph 0 to first " + gp_number(a) +
         ", graph 1 nohead lc rgb '#9a9a9a' dt 2\n";
    s += "set label " + id + " " + gnuplot_string(phases[k].message) + " at first " + gp_number(a) +
         ", graph 0.975 " + (at_end ? "right offset -0.4,0" : "left offset 0.4,0") +
         " font ',12' tc rgb '#505050' front\n";
  }
  return s;
}

std::string common_style() {
  return "set grid lc rgb '#d0d0d0' lw 1\n"
         "set border lw 1.2\n"
         "set key opaque box lc rgb '#b0b0b0' samplen 2.5 spacing 1.1\n"
         "set tics out nomirror\n"
         "set xlabel 'time t [s]'\n";
}

std::string time_figure_preamble(const Recording& recording, const std::string& title) {
  return common_style() + phase_background(recording) + "set title " + gnuplot_string(title) +
         " font ',16'\n";
}

void check_single_figure(const PlotOptions& options, int min_height) {
  check_fields(options);
  if (options.height < min_height)
    throw Error("plot: height must be ≥ " + std::to_string(min_height) +
                " [pixels] for a single figure, got " + std::to_string(options.height));
}

std::string single_figure_preamble(const std::filesystem::path& png, const PlotOptions& options,
                                   const std::string& comment) {
  const int font = std::max(9, options.height / 70);
  return "# " + comment + "\nset terminal pngcairo noenhanced size " +
         std::to_string(options.width) + "," + std::to_string(options.height) +
         " font 'DejaVu Sans," + std::to_string(font) +
         "' linewidth 1\nset encoding utf8\nset output " + gnuplot_string(png.string()) + "\n" +
         common_style();
}

void draw_single_figure(PlotFiles& files, const std::filesystem::path& data_file,
                        const std::string& data, const std::filesystem::path& script_file,
                        const std::string& script, const std::filesystem::path& png,
                        double timeout_s) {
  files.write(data_file, data);
  files.write(script_file, script);
  files.output(png);  // no stale figure survives a failure
  run_gnuplot(script_file, timeout_s);
  if (!png_complete(png))  // a whole figure or none (PlotFiles removes it with its data)
    throw Error("gnuplot did not write " + quoted(png) +
                " completely (is the disk full?); no figure was kept, nor its data and script");
  files.keep();
}

}  // namespace mjarm::plot::detail
