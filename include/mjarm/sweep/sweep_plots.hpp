#pragma once
/// @file
/// A sweep's figures (gnuplot PNGs): the success rate against each varied parameter with its 95 %
/// Wilson interval, a success heat map over two axes, and the distribution of every metric.

#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/plot/rate_plots.hpp"
#include "mjarm/sweep/sweep_folder.hpp"

namespace mjarm {

struct SweepPlotOptions {
  /// The heat map's two axes (x, then y); empty: the first two axes of the grid with more than
  /// one value (no heat map when there are not two).
  std::vector<std::string> heat_map;
  plot::PlotOptions plot;
};

/// Draws the figures of @p folder's merged results into @p out_dir: `success_vs_NAME.png` per
/// varied parameter, `success_heat_map.png`, `metric_distributions.png`.
/// @throws Error when there are no results, a heat-map axis is not an axis of the sweep (with
///         the closest), or a figure cannot be drawn (see `plot_rates`)
std::vector<plot::PlotInfo> plot_sweep(const SweepFolder& folder,
                                       const std::filesystem::path& out_dir,
                                       const SweepPlotOptions& options = {});

}  // namespace mjarm
