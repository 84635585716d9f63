#pragma once
/// @file
/// The force and stiffness figure of a docking run, through the plot room
/// (`plot::plot_time_series`).

#include <filesystem>

#include "mjarm/plot/time_series_plot.hpp"
#include "mjarm/tasks/docking/docking.hpp"

namespace mjarm {

/// The figure of @p report (its samples must be kept): three panels over the run's time —
/// the contact force on the peg (true axial and lateral, from MuJoCo's contacts; the controller's
/// measured axial force dashed) [N], the stiffness the controller applies on x, y, z [N/m], and
/// the tip's depth below the socket's top and its distance to the bore axis [mm] — with the
/// phases approach, insert, hold shaded.
/// @throws Error when the report holds no samples.
plot::TimeSeriesFigure docking_figure(const DockingReport& report);

/// Draws `docking_figure(report)` as @p out_dir/docking.png.
/// @throws Error as `docking_figure` and `plot::plot_time_series`.
plot::PlotInfo plot_docking(const DockingReport& report, const std::filesystem::path& out_dir,
                            const plot::PlotOptions& options = {});

}  // namespace mjarm
