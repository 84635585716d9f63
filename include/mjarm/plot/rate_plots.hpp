#pragma once
/// @file
/// Figures of success rates and of distributions, one PNG each, drawn with gnuplot: a rate per
/// category with its confidence interval (a sweep's success against one axis), a grid of rates
/// over two categories (a heat map), and histograms of several quantities side by side.

#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/plot/plots.hpp"

namespace mjarm::plot {

/// One category's rate and its interval, all in [0, 1].
struct RatePoint {
  std::string label;  ///< the category ("weld", "0.015")
  double rate = 0.0;
  double low = 0.0;
  double high = 1.0;
  long long trials = 0;  ///< written above the point (n = …)
};

/// A rate against one categorical axis.
struct RateFigure {
  std::string name = "rates";  ///< the PNG's stem
  std::string title;
  std::string xlabel;  ///< the axis ("object-size [m]")
  std::string ylabel = "success rate";
  std::vector<RatePoint> points;  ///< ≥ 1, in the axis's order
};

/// Rates over two categorical axes: `rates[row][column]`, NaN for a cell without trials.
struct HeatMapFigure {
  std::string name = "heat_map";
  std::string title;
  std::string xlabel, ylabel;
  std::vector<std::string> columns;  ///< x categories, ≥ 1
  std::vector<std::string> rows;     ///< y categories, ≥ 1
  std::vector<std::vector<double>> rates;
};

/// One quantity's values, drawn as a histogram in a panel of its own.
struct Histogram {
  std::string label;           ///< "placement_error [m]"
  std::vector<double> values;  ///< NaN and infinite values are left out
};

struct HistogramFigure {
  std::string name = "distributions";
  std::string title;
  std::vector<Histogram> histograms;  ///< 1 … 12 panels
  int bins = 20;                      ///< 1 … 1000
};

/// Draws @p figure into @p out_dir/NAME.png (the script and data stay in @p out_dir/gnuplot/):
/// the rates joined by a line, each with its interval as an error bar and its trial count.
/// @throws Error for an inconsistent figure (no point, a rate outside [0, 1] or its interval, a
///         name with '/'), a folder that cannot be written, or gnuplot missing or failing.
PlotInfo plot_rates(const RateFigure& figure, const std::filesystem::path& out_dir,
                    const PlotOptions& options = {});

/// Draws @p figure as coloured cells from red (0) to green (1), each labelled with its rate.
/// @throws Error as `plot_rates`, or for a grid whose size does not match its categories
PlotInfo plot_heat_map(const HeatMapFigure& figure, const std::filesystem::path& out_dir,
                       const PlotOptions& options = {});

/// Draws @p figure: one panel per histogram, in a grid, each with its count of values.
/// @throws Error as `plot_rates`, or for no or too many panels
PlotInfo plot_histograms(const HistogramFigure& figure, const std::filesystem::path& out_dir,
                         const PlotOptions& options = {});

}  // namespace mjarm::plot
