#pragma once
/// @file
/// A figure of signals over time in stacked panels (forces in one, stiffnesses in another, …),
/// with named time bands behind them (a task's phases), drawn with gnuplot as one PNG. The
/// docking run's force and stiffness figure is one (`mjarm run docking --plot DIR`).

#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/plot/plots.hpp"

namespace mjarm::plot {

/// One curve: a value per sample instant.
struct TimeSeries {
  std::string name;            ///< legend entry
  std::vector<double> values;  ///< one per instant of the figure (NaN: a gap)
  bool dashed = false;         ///< draw dashed (a reference, a measurement beside the truth)
};

/// One panel: curves sharing a y axis.
struct TimePanel {
  std::string ylabel;              ///< y axis label with its unit ("force [N]")
  std::vector<TimeSeries> series;  ///< ≥ 1
};

/// A named stretch of time, shaded behind every panel (a phase).
struct TimeBand {
  double start = 0.0;  ///< [s]
  double end = 0.0;    ///< [s], ≥ start
  std::string label;   ///< written at the top of the first panel
};

/// The figure: panels stacked over a common time axis.
struct TimeSeriesFigure {
  std::string name = "time_series";  ///< the PNG's stem: `out_dir/NAME.png`
  std::string title;                 ///< the figure's title
  std::vector<double> t;             ///< sample instants [s], ≥ 1, non-decreasing
  std::vector<TimePanel> panels;     ///< 1 … 6
  std::vector<TimeBand> bands;       ///< optional
};

/// Draws @p figure into @p out_dir/NAME.png (the folder is created when missing; the gnuplot
/// script and its data file stay in @p out_dir/gnuplot/ for restyling): one panel per
/// `TimePanel`, one colour per curve, the bands shaded behind them.
/// @throws Error when the figure is inconsistent (a name with '/', no samples, a curve of the
///         wrong length, no or too many panels, a band ending before it starts — named), the
///         folder cannot be created or written, the size is out of range, or gnuplot is missing
///         or fails.
PlotInfo plot_time_series(const TimeSeriesFigure& figure, const std::filesystem::path& out_dir,
                          const PlotOptions& options = {});

}  // namespace mjarm::plot
