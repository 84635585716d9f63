#include "mjarm/plot/polar_heat_map.hpp"

#include <cmath>
#include <numbers>

#include "figures.hpp"
#include "mjarm/error.hpp"

namespace mjarm::plot {

namespace {

namespace fs = std::filesystem;

void check_polar(const PolarHeatMapFigure& f) {
  const std::string what = "polar heat map '" + f.name + "': ";
  if (f.name.empty() || f.name.find('/') != std::string::npos || f.name == "." || f.name == "..")
    throw Error(what + "the name is not a plain file stem");
  if (f.ring_edges.size() < 2 || f.sectors < 1)
    throw Error(what + "needs at least one ring and one sector");
  for (std::size_t k = 0; k < f.ring_edges.size(); ++k)
    if (!std::isfinite(f.ring_edges[k]) || f.ring_edges[k] < 0.0 ||
        (k > 0 && !(f.ring_edges[k] > f.ring_edges[k - 1])))
      throw Error(what + "ring edges must be finite, ≥ 0 and increasing");
  if (f.values.size() != f.ring_edges.size() - 1)
    throw Error(what + "the grid does not match its rings");
  for (const auto& ring : f.values)
    if (ring.size() != static_cast<std::size_t>(f.sectors))
      throw Error(what + "the grid does not match its sectors");
  if (!std::isfinite(f.low) || !std::isfinite(f.high) || !(f.low < f.high))
    throw Error(what + "the colour range must be finite with low < high");
}

}  // namespace

PlotInfo plot_polar_heat_map(const PolarHeatMapFigure& f, const fs::path& out_dir,
                             const PlotOptions& options) {
  detail::check_single_figure(options);
  check_polar(f);
  find_gnuplot();
  detail::PlotFiles files(out_dir);
  // each cell an annular sector, drawn as a polygon coloured from the palette at its value;
  // the data file holds the cell centres (it makes gnuplot draw the colour box)
  std::string objects, data = "# x y value (cell centres)\n";
  const double width = 2.0 * std::numbers::pi / f.sectors;
  const int arc = 8;  // points per arc
  int id = 1;
  for (std::size_t k = 0; k + 1 < f.ring_edges.size(); ++k) {
    const double r0 = f.ring_edges[k], r1 = f.ring_edges[k + 1];
    for (int j = 0; j < f.sectors; ++j) {
      const double v = f.values[k][static_cast<std::size_t>(j)];
      if (std::isnan(v)) continue;
      const double a0 = (j - 0.5) * width;
      std::string poly;
      for (int i = 0; i <= arc; ++i) {  // outer arc forwards, inner arc backwards
        const double a = a0 + width * i / arc;
        poly += (poly.empty() ? " from " : " to ") + detail::gp_number(r1 * std::cos(a)) + "," +
                detail::gp_number(r1 * std::sin(a));
      }
      for (int i = arc; i >= 0; --i) {
        const double a = a0 + width * i / arc;
        poly += " to " + detail::gp_number(r0 * std::cos(a)) + "," +
                detail::gp_number(r0 * std::sin(a));
      }
      objects += "set object " + std::to_string(id++) + " polygon" + poly + " back fc palette cb " +
                 detail::gp_number(v) + " fs solid 1.0 border lc rgb '#606060' lw 0.5\n";
      const double rc = 0.5 * (r0 + r1), ac = j * width;
      data += detail::gp_number(rc * std::cos(ac)) + " " + detail::gp_number(rc * std::sin(ac)) +
              " " + detail::gp_number(v) + "\n";
    }
  }
  const fs::path data_file = files.data_dir() / (f.name + ".dat");
  PlotInfo info{f.name, files.out() / (f.name + ".png"), f.title, {f.value_label}, {}};
  std::string script = detail::single_figure_preamble(
      info.path, options,
      "drawn by mjarm (plot_polar_heat_map); run `gnuplot " + f.name + ".gp` to redraw");
  const std::string R = detail::gp_number(f.ring_edges.back() * 1.05);
  script += "set title " + gnuplot_string(f.title) + "\nset xlabel " +
            gnuplot_string(f.axis_label) + "\nset ylabel " + gnuplot_string(f.axis_label) +
            "\nset size ratio -1\nset xrange [-" + R + ":" + R + "]\nset yrange [-" + R + ":" + R +
            "]\nset cbrange [" + detail::gp_number(f.low) + ":" + detail::gp_number(f.high) +
            "]\nset cblabel " + gnuplot_string(f.value_label) +
            "\nset palette defined (0 '#d73027', 0.5 '#fee08b', 1 '#1a9850')\nunset grid\n"
            "set key off\n" +
            objects;
  script += "plot " + gnuplot_string(data_file.string()) +
            " using 1:2:3 with points pt 7 ps 0.01 lc palette\nunset output\n";
  detail::draw_single_figure(files, data_file, data, files.data_dir() / (f.name + ".gp"), script,
                             info.path, options.timeout_s);
  return info;
}

}  // namespace mjarm::plot
