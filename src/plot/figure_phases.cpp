// The phases figure: one band per task phase on a time line, other events as markers below.

#include <algorithm>
#include <cstdio>

#include "figures.hpp"

namespace mjarm::plot::detail {

Figure phases_figure(const Recording& recording, const std::filesystem::path& data_dir) {
  const std::vector<RecordedEvent> phases = recording.events_of("phase");
  const auto [t0, t1] = time_range(recording);
  const double span = t1 - t0;
  Figure f;
  f.info.name = "phases";
  f.info.title = "Task phases and events over time (" + describe(recording) + ")";
  std::string s =
      "set title " + gnuplot_string(f.info.title) + " font ',16'\n" + common_style() +
      "unset grid\nset grid xtics lc rgb '#d0d0d0'\n"
      // a margin on the right: a phase or event at the very end stays visible
      "set xrange [" +
      gp_number(t0) + ":" + gp_number(t1 + 0.03 * span) +
      "]\n"
      "set yrange [0:2]\nset ytics ('events' 0.5, 'phases' 1.5) font ',14'\nunset y2tics\n"
      "set key outside below center horizontal width -2\nset bmargin 5.5\n";
  std::string plot = "plot ";
  auto label_side = [&, end = t1](double x) {  // clang 14 captures no structured binding
    return (end - x) < 0.12 * span ? std::string("right offset -0.5,0")
                                  : std::string("left offset 0.5,0");
  };
  for (std::size_t k = 0; k < phases.size(); ++k) {
    const double a = std::max(phases[k].t, t0);
    const double b = k + 1 < phases.size() ? std::min(phases[k + 1].t, t1) : t1;
    const std::string id = std::to_string(k + 1);
    char times[96];
    std::snprintf(times, sizeof(times), " %.3f-%.3f s", a, b);
    if (b - a > 0.004 * span) {
      s += "set object " + id + " rect from " + gp_number(a) + ", 1.1 to " + gp_number(b) +
           ", 1.9 fc rgb " + band_color(k) + " fs solid 1.0 border lc rgb '#808080'\n";
    }
    // wide bands are named inside, narrow ones (a phase at the very end) beside their line
    if (b - a > 0.15 * span) {
      s += "set label " + id + " " + gnuplot_string(phases[k].message) + " at " +
           gp_number(0.5 * (a + b)) + ", 1.55 center font ',15' front\n";
      s += "set label " + std::to_string(100 + k) + " " + gnuplot_string(times) + " at " +
           gp_number(0.5 * (a + b)) + ", 1.35 center font ',11' tc rgb '#505050' front\n";
    } else {
      s += "set arrow " + id + " from " + gp_number(a) + ", 1.1 to " + gp_number(a) +
           ", 1.9 nohead lw 3 lc rgb " + line_color(k) + " front\n";
      s += "set label " + id + " " + gnuplot_string(phases[k].message) + " at " + gp_number(a) +
           ", " + gp_number(1.7 - 0.2 * static_cast<double>(k % 3)) + " " + label_side(a) +
           " font ',15' front\n";
    }
    char from[64];
    std::snprintf(from, sizeof(from), " (from %.3f s)", a);
    const std::string legend = phases[k].message + from;
    plot += std::string(k ? ", " : "") + "NaN with boxes fs solid 1.0 fc rgb " + band_color(k) +
            " title " + gnuplot_string(legend);
    f.info.series.push_back(phases[k].message);
  }
  if (phases.empty()) {
    s += "set label 1 'no phase events recorded' at graph 0.5, 0.75 center font ',18' tc rgb "
         "'#707070'\n";
    f.info.notes.push_back("no phase events recorded");
  } else {
    f.info.notes.push_back(std::to_string(phases.size()) + " phases");
  }
  // the other events (result, warning, divergence, …): a stem each, named by kind
  std::string events;
  int others = 0;
  for (const RecordedEvent& e : recording.events()) {
    if (e.kind == "phase") continue;
    ++others;
    if (others > 24) continue;  // a crowded run: the first ones, the rest counted in the notes
    events += gp_number(e.t) + " 0.85\n";
    s += "set label " + std::to_string(200 + others) + " " + gnuplot_string(e.kind) + " at " +
         gp_number(e.t) + ", " + gp_number(0.75 - 0.2 * static_cast<double>(others % 3)) + " " +
         label_side(e.t) + " font ',13' front\n";
  }
  if (others > 0) {
    const std::filesystem::path file = data_dir / "phases_events.dat";
    f.data.emplace_back(file, "# t [s]  stem height\n" + events);
    plot += std::string(phases.empty() ? "" : ", ") + gnuplot_string(file.string()) +
            " using 1:2 with impulses lw 2 lc rgb '#404040' title 'other events'";
    f.info.series.push_back("other events");
    f.info.notes.push_back(std::to_string(others) + " other events" +
                           (others > 24 ? " (first 24 drawn)" : ""));
  }
  if (phases.empty() && others == 0) plot += "NaN notitle";
  f.script = s + plot + "\n";
  return f;
}

}  // namespace mjarm::plot::detail
