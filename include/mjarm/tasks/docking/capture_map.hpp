#pragma once
/// @file
/// The capture region of the docking: the run over believed-socket offsets on a polar grid
/// (radial offset × direction × yaw), run as a grid of listed offsets (`run_docking_grid`), per
/// (radius, direction) cell the seated fraction over the yaws, the worst time to seat and peak
/// force, and its polar heat map. docs/docking.md "The capture region".

#include <filesystem>
#include <vector>

#include "mjarm/plot/plots.hpp"
#include "mjarm/tasks/docking/grid.hpp"

namespace mjarm {

/// The polar grid: the is radii 0–15 mm by 1 mm × 8 directions × yaw 0–25° by 5°.
struct DockingMapAxes {
  std::vector<double> radii;  ///< [m], ≥ 0, increasing
  int directions = 8;         ///< equal, the first along the socket's x
  std::vector<double> yaws;   ///< [rad]
};

/// The axes.
DockingMapAxes default_docking_map_axes();

/// The offsets of @p axes: radius slowest, then direction, then yaw (a zero radius repeated in
/// each direction, so every cell has its trials).
/// @throws Error for an empty axis, a radius < 0 or not increasing, directions < 1.
std::vector<DockingOffset> docking_map_offsets(const DockingMapAxes& axes);

/// One (radius, direction) cell over the yaws.
struct DockingMapCell {
  double radius = 0.0;     ///< [m]
  double direction = 0.0;  ///< [rad]
  int trials = 0;
  int seated = 0;
  double max_seat_time = 0.0;   ///< worst time to the bottom of the seated runs [s] (NaN: none)
  double max_peak_force = 0.0;  ///< [N]
  int searched = 0;             ///< runs that detected a miss
};

/// The cells of a grid run over `docking_map_offsets(axes)`, ring by ring (the runs matched by
/// offset: an interrupted grid gives cells with fewer trials).
std::vector<DockingMapCell> docking_map_cells(const DockingMapAxes& axes,
                                              const DockingGridResult& result);

/// The polar heat map of the seated fraction per cell as @p out_dir/@p name.png.
/// @throws Error as `plot::plot_polar_heat_map`.
plot::PlotInfo plot_docking_map(const DockingMapAxes& axes, const DockingGridResult& result,
                                const std::filesystem::path& out_dir, const std::string& name);

}  // namespace mjarm
