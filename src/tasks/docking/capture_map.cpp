#include "mjarm/tasks/docking/capture_map.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/plot/polar_heat_map.hpp"

namespace mjarm {

DockingMapAxes default_docking_map_axes() {
  DockingMapAxes a;
  for (int r = 0; r <= 15; ++r) a.radii.push_back(1e-3 * r);
  for (int y = 0; y <= 25; y += 5) a.yaws.push_back(y * std::numbers::pi / 180.0);
  return a;
}

std::vector<DockingOffset> docking_map_offsets(const DockingMapAxes& a) {
  if (a.radii.empty() || a.yaws.empty() || a.directions < 1)
    throw Error("docking map: needs a radius, a yaw and at least one direction");
  for (std::size_t k = 0; k < a.radii.size(); ++k)
    if (!std::isfinite(a.radii[k]) || a.radii[k] < 0.0 || (k > 0 && !(a.radii[k] > a.radii[k - 1])))
      throw Error("docking map: radii must be finite, ≥ 0 and increasing");
  std::vector<DockingOffset> offsets;
  for (double r : a.radii)
    for (int j = 0; j < a.directions; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / a.directions;
      for (double yaw : a.yaws) offsets.push_back({r * std::cos(phi), r * std::sin(phi), yaw});
    }
  return offsets;
}

std::vector<DockingMapCell> docking_map_cells(const DockingMapAxes& a,
                                              const DockingGridResult& result) {
  std::vector<DockingMapCell> cells;
  const std::vector<DockingOffset> offsets = docking_map_offsets(a);
  const std::size_t per_cell = a.yaws.size();
  std::size_t next_run = 0;  // runs come in the offsets' order, some may be missing
  for (std::size_t c = 0; c * per_cell < offsets.size(); ++c) {
    DockingMapCell cell;
    cell.radius = a.radii[c / static_cast<std::size_t>(a.directions)];
    cell.direction = 2.0 * std::numbers::pi * static_cast<double>(c % a.directions) / a.directions;
    cell.max_seat_time = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < per_cell; ++k) {
      const DockingOffset& o = offsets[c * per_cell + k];
      if (next_run >= result.runs.size()) break;
      const DockingGridRun& run = result.runs[next_run];
      if (run.offset.dx != o.dx || run.offset.dy != o.dy || run.offset.dyaw != o.dyaw) continue;
      ++next_run;
      ++cell.trials;
      cell.max_peak_force = std::max(cell.max_peak_force, run.metrics.peak_force);
      if (run.searches > 0) ++cell.searched;
      if (run.outcome != DockingOutcome::seated) continue;
      ++cell.seated;
      if (std::isnan(cell.max_seat_time) || run.seat_time > cell.max_seat_time)
        cell.max_seat_time = run.seat_time;
    }
    cells.push_back(cell);
  }
  return cells;
}

plot::PlotInfo plot_docking_map(const DockingMapAxes& a, const DockingGridResult& result,
                                const std::filesystem::path& out_dir, const std::string& name) {
  const std::vector<DockingMapCell> cells = docking_map_cells(a, result);
  plot::PolarHeatMapFigure f;
  f.name = name;
  int seated = 0, trials = 0;
  for (const DockingMapCell& c : cells) {
    seated += c.seated;
    trials += c.trials;
  }
  f.title = "docking capture region: " + result.controller + ", " + to_string(result.source) +
            " (" + std::to_string(seated) + "/" + std::to_string(trials) +
            " seated; colour: fraction over the yaws)";
  f.axis_label = "believed-socket offset [mm]";
  f.value_label = "seated fraction";
  f.sectors = a.directions;
  // ring k around radius k: edges halfway between the radii (the first from 0)
  f.ring_edges.push_back(0.0);
  for (std::size_t k = 0; k < a.radii.size(); ++k) {
    const double next = k + 1 < a.radii.size()
                            ? 0.5 * (a.radii[k] + a.radii[k + 1])
                            : a.radii[k] + 0.5 * (k > 0 ? a.radii[k] - a.radii[k - 1] : 1e-3);
    f.ring_edges.push_back(1e3 * next);
  }
  f.values.assign(a.radii.size(), std::vector<double>(static_cast<std::size_t>(a.directions),
                                                      std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t c = 0; c < cells.size(); ++c)
    if (cells[c].trials > 0)
      f.values[c / static_cast<std::size_t>(a.directions)]
              [c % static_cast<std::size_t>(a.directions)] =
          static_cast<double>(cells[c].seated) / cells[c].trials;
  return plot::plot_polar_heat_map(f, out_dir);
}

}  // namespace mjarm
