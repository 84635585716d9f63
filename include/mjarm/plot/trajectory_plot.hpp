#pragma once
/// @file
/// The figure of a sampled trajectory: position, velocity, acceleration and jerk of every axis
/// against their limits, drawn with gnuplot as one PNG (`mjarm traj --plot DIR`).

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "mjarm/plot/plots.hpp"

namespace mjarm::plot {

/// A trajectory of n axes sampled at instants t, with the bounds its derivatives must respect.
struct TrajectorySeries {
  std::string title;              ///< the figure's title ("quintic, 7 axes, T = 1.2 s")
  std::string unit = "u";         ///< the position unit of every axis ("rad", "m")
  std::vector<std::string> axes;  ///< axis names, n ≥ 1
  std::vector<double> t;          ///< sample instants [s], ≥ 1 and non-decreasing
  /// values[k][i][s]: derivative k (0 position, 1 velocity, 2 acceleration, 3 jerk) of axis i
  /// at sample s; every list has t.size() entries
  std::array<std::vector<std::vector<double>>, 4> values;
  /// limits[k][i]: the bound on |derivative k| of axis i, drawn as dashed ±lines; empty, NaN or
  /// infinite: none (limits[0] is unused)
  std::array<std::vector<double>, 4> limits;
};

/// Draws @p series into @p out_dir/trajectory.png (the folder is created when missing; the
/// gnuplot script and data stay in @p out_dir/gnuplot/): four panels stacked over time —
/// position, velocity, acceleration, jerk — one colour per axis, its limits dashed.
/// @throws Error when the series is inconsistent (sizes named), the folder cannot be created or
///         written, the size is out of range, or gnuplot is missing or fails.
PlotInfo plot_trajectory(const TrajectorySeries& series, const std::filesystem::path& out_dir,
                         const PlotOptions& options = {});

}  // namespace mjarm::plot
