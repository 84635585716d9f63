#include "mjarm/tasks/docking/plot.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "mjarm/error.hpp"

namespace mjarm {

plot::TimeSeriesFigure docking_figure(const DockingReport& r) {
  if (r.samples.empty())
    throw Error("docking plot: the report holds no samples (run with keep_samples)");
  const DockingPlan& plan = r.plan;
  const Eigen::Vector3d z_S = plan.X_WS.R.col(2);
  plot::TimeSeriesFigure f;
  f.name = "docking";
  char title[256];
  std::snprintf(title, sizeof title,
                "docking, %s (%s%s), offset (%.3g mm, %.3g mm, %.3g°): %s, peak force %.1f N",
                r.controller.c_str(), to_string(r.source),
                r.joint_friction ? ", joint friction" : "", plan.offset.dx * 1e3,
                plan.offset.dy * 1e3, plan.offset.dyaw * 180.0 / std::numbers::pi,
                to_string(r.outcome), r.metrics.peak_force);
  f.title = title;
  plot::TimePanel force{
      "contact force on the peg [N]",
      {{"axial (true)", {}, false}, {"lateral (true)", {}, false}, {"axial (measured)", {}, true}}};
  plot::TimePanel stiffness{"stiffness [N/m]",
                            {{"x", {}, false}, {"y", {}, false}, {"z", {}, false}}};
  plot::TimePanel place{
      "tip [mm]", {{"depth below the top", {}, false}, {"distance to the bore axis", {}, false}}};
  for (const DockingSample& s : r.samples) {
    f.t.push_back(s.t);
    const Eigen::Vector3d force_true = s.F_peg.head<3>();
    const double axial = force_true.dot(z_S);
    force.series[0].values.push_back(axial);
    force.series[1].values.push_back((force_true - axial * z_S).norm());
    force.series[2].values.push_back(s.F_measured.head<3>().dot(z_S));
    for (int i = 0; i < 3; ++i)
      stiffness.series[static_cast<std::size_t>(i)].values.push_back(s.stiffness[i]);
    const Eigen::Vector3d d = s.X_WE.p - plan.X_WS.p;
    const double depth = -d.dot(z_S);
    place.series[0].values.push_back(depth * 1e3);
    place.series[1].values.push_back((d + depth * z_S).norm() * 1e3);
  }
  f.panels = {force, stiffness, place};
  const double t_insert = plan.approach_time;
  const double t_hold = plan.approach_time + plan.insert_time;
  f.bands.push_back({0.0, t_insert, "approach"});
  const double t_end = r.samples.back().t;
  if (r.searches > 0 && std::isfinite(r.miss_time)) {
    // approach, insert, search (first miss to last drop, or the end), insert again, hold
    f.bands.push_back({t_insert, r.miss_time, "insert"});
    const double t_drop = std::isfinite(r.drop_time) ? r.drop_time : t_end;
    f.bands.push_back({r.miss_time, t_drop, "search"});
    if (t_drop < t_end) {
      f.bands.push_back({t_drop, r.hold_start, "insert"});
      f.bands.push_back({r.hold_start, t_end, "hold"});
    }
    return f;
  }
  if (plan.insert_time > 0.0) f.bands.push_back({t_insert, t_hold, "insert"});
  f.bands.push_back({t_hold, plan.duration(), "hold"});
  return f;
}

plot::PlotInfo plot_docking(const DockingReport& report, const std::filesystem::path& out_dir,
                            const plot::PlotOptions& options) {
  return plot::plot_time_series(docking_figure(report), out_dir, options);
}

}  // namespace mjarm
