#pragma once
/// @file
/// A heat map over rings and equal sectors around a centre (a capture region: radial offset ×
/// direction), drawn as coloured annular cells on Cartesian axes.

#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/plot/plots.hpp"

namespace mjarm::plot {

/// `values[ring][sector]`: ring k spans [ring_edges[k], ring_edges[k+1]]; sector j is centred
/// on the angle 2π·j/sectors from the x axis (counter-clockwise). NaN: not drawn.
struct PolarHeatMapFigure {
  std::string name = "polar_heat_map";  ///< the PNG's stem
  std::string title;
  std::string axis_label;  ///< both axes ("offset [mm]")
  std::string value_label = "success rate";
  std::vector<double> ring_edges;  ///< ≥ 2, increasing, ≥ 0, in the axes' unit
  int sectors = 8;                 ///< ≥ 1
  std::vector<std::vector<double>> values;
  double low = 0.0, high = 1.0;  ///< the colour range (red at low, green at high)
};

/// Draws @p figure into @p out_dir/NAME.png (the script and data stay in @p out_dir/gnuplot/).
/// @throws Error for an inconsistent figure (edges not increasing, a grid that does not match
///         them, low ≥ high, a name with '/'), a folder that cannot be written, or gnuplot
///         missing or failing.
PlotInfo plot_polar_heat_map(const PolarHeatMapFigure& figure, const std::filesystem::path& out_dir,
                             const PlotOptions& options = {});

}  // namespace mjarm::plot
