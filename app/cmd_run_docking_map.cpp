// `mjarm run docking --map`: the capture region of the docking (docs/docking.md "The capture
// region") — the runs over polar offsets per law, a table per (radius, direction) cell, a polar
// heat map per law and the table as JSON.

#include <cmath>
#include <iostream>
#include <numbers>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/tasks/docking/capture_map.hpp"

namespace mjarm::cli {

namespace {

Json map_number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace

void run_docking_map(const DockingCliOptions& cli, const std::vector<DockingLaw>& laws,
                     const DockingOptions& base, bool json) {
  DockingMapAxes axes;
  for (double r = 0.0; r <= 15.0 + 1e-9; r += cli.map_step) axes.radii.push_back(1e-3 * r);
  for (double y = 0.0; y <= 25.0 + 1e-9; y += cli.map_yaw_step)
    axes.yaws.push_back(y * std::numbers::pi / 180.0);
  DockingGridOptions grid;
  grid.base = base;
  grid.jobs = cli.jobs;
  grid.offsets = docking_map_offsets(axes);
  DockingSceneOptions scene_options;
  scene_options.joint_friction = base.joint_friction;
  scene_options.geometry = base.geometry;
  grid.base.scene = std::make_shared<const DockingScene>(build_docking_scene(scene_options));
  const int planned = static_cast<int>(grid.offsets.size() * laws.size());
  Progress progress("docking map runs", planned);
  int done_before = 0;
  Json tables = Json::array();
  std::vector<std::string> pngs;
  bool interrupted = false;
  if (!json)
    std::cout << "docking capture region: radial offset 0–15 mm by " << compact(cli.map_step)
              << " mm × " << axes.directions << " directions × yaw 0–25° by "
              << compact(cli.map_yaw_step) << "°, "
              << (base.controller.source == ForceSource::observer ? "sensorless" : "F/T sensor")
              << "\n";
  for (const DockingLaw law : laws) {
    grid.base.controller.law = law;
    const DockingGridResult result =
        run_docking_grid(grid, [&](int done, int) { progress.update(done_before + done); });
    done_before += static_cast<int>(result.runs.size());
    const std::vector<DockingMapCell> cells = docking_map_cells(axes, result);
    Json rows = Json::array();
    for (const DockingMapCell& c : cells)
      rows.push_back({{"radius", c.radius},
                      {"direction", c.direction},
                      {"trials", c.trials},
                      {"seated", c.seated},
                      {"max_seat_time", map_number(c.max_seat_time)},
                      {"max_peak_force", c.max_peak_force},
                      {"searched", c.searched}});
    Json runs = Json::array();
    for (const DockingGridRun& run : result.runs)
      runs.push_back({{"offset", fields_to_json(run.offset)},
                      {"outcome", to_string(run.outcome)},
                      {"seat_time", map_number(run.seat_time)},
                      {"peak_force", run.metrics.peak_force},
                      {"searches", run.searches},
                      {"search_time", run.search_time},
                      {"failures", run.metrics.failures}});
    std::string png;
    if (!cli.plot.empty() && !result.runs.empty()) {
      const std::string name =
          "docking_map_" + result.controller + "_" + std::string(to_string(result.source));
      png = plot_docking_map(axes, result, cli.plot, name).path.string();
      pngs.push_back(png);
    }
    tables.push_back({{"controller", result.controller},
                      {"source", to_string(result.source)},
                      {"planned", result.planned},
                      {"runs", static_cast<int>(result.runs.size())},
                      {"seated", result.seated},
                      {"max_peak_force", result.max_peak_force},
                      {"png", png.empty() ? Json(nullptr) : Json(png)},
                      {"cells", rows},
                      {"offsets", runs}});
    if (!json) {
      // per ring: seated of its trials, worst time to seat and peak force
      std::cout << result.controller << ": " << result.seated << "/" << result.runs.size()
                << " seated, peak force " << fixed(result.max_peak_force, 2) << " N\n";
      Table table(
          {{"radius [mm]"}, {"seated"}, {"worst seat time [s]"}, {"peak force [N]"}, {"searched"}});
      for (std::size_t r = 0; r < axes.radii.size(); ++r) {
        int seated = 0, trials = 0, searched = 0;
        double seat = 0.0, peak = 0.0;
        for (int j = 0; j < axes.directions; ++j) {
          const DockingMapCell& c =
              cells[r * static_cast<std::size_t>(axes.directions) + static_cast<std::size_t>(j)];
          seated += c.seated;
          trials += c.trials;
          searched += c.searched;
          if (std::isfinite(c.max_seat_time)) seat = std::max(seat, c.max_seat_time);
          peak = std::max(peak, c.max_peak_force);
        }
        table.add_row({fixed(axes.radii[r] * 1e3, 1),
                       std::to_string(seated) + "/" + std::to_string(trials), fixed(seat, 2),
                       fixed(peak, 2), std::to_string(searched)});
      }
      table.print(std::cout, 0);
      if (!png.empty()) std::cout << "  heat map " << png << '\n';
    }
    if (result.interrupted) {
      interrupted = true;
      break;
    }
  }
  progress.finish();
  const Json doc{{"scenario", "docking"},
                 {"map", true},
                 {"interrupted", interrupted},
                 {"controllers", tables}};
  if (!cli.plot.empty()) {
    FileWriter out(std::filesystem::path(cli.plot) / "docking_map.json", FileWriter::Mode::replace,
                   "docking map JSON");
    out.write(doc.dump(1) + "\n");
    out.commit();
  }
  if (json) print_json(doc);
  if (interrupted)
    throw InterruptedError("interrupted after " + std::to_string(done_before) + " of " +
                               std::to_string(planned) + " docking map runs",
                           interrupt_signal());
}

}  // namespace mjarm::cli
