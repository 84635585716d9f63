#include "mjarm/tasks/docking/docking.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mjarm/tasks/docking/plot.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

std::shared_ptr<const DockingScene> shared_scene() {
  static const auto s = std::make_shared<const DockingScene>(build_docking_scene());
  return s;
}

/// A shorter run than the command's (start 30 mm above the socket, insertion at 20 mm/s,
/// 1.2 s hold): about 2 000 control ticks.
DockingOptions quick(double dx_mm, double dy_mm, double dyaw_deg) {
  DockingOptions o;
  o.scene = shared_scene();
  o.offset = {dx_mm * 1e-3, dy_mm * 1e-3, dyaw_deg * kDockingDeg};
  o.motion.start_height = 0.03;
  o.motion.approach_time = 0.6;
  o.motion.insertion_speed = 0.02;
  o.motion.hold_time = 1.2;
  return o;
}

std::string why(const DockingReport& r) {
  std::string out = docking_result_line(r);
  return out;
}

TEST(Docking, Se3ImpedanceSeatsThePegUnderOffsets) {
  for (const auto& [dx, dy, dyaw] :
       {std::tuple{0.0, 0.0, 0.0}, std::tuple{6.0, -6.0, 15.0}, std::tuple{-6.0, 6.0, -15.0}}) {
    const DockingReport r = run_docking(quick(dx, dy, dyaw));
    EXPECT_TRUE(r.ok()) << dx << " " << dy << " " << dyaw << ": " << why(r);
    const DockingMetrics& m = r.metrics;
    EXPECT_LE(m.peak_force, 30.0) << why(r);
    EXPECT_NEAR(m.steady_axial_force, 5.0, 0.25) << why(r);
    EXPECT_GE(m.min_depth, r.plan.full_depth - 1e-3);
    EXPECT_LE(m.max_lateral, 0.5e-3);
    EXPECT_EQ(r.run.status, RunStatus::finished);
    EXPECT_EQ(r.samples.size(), static_cast<std::size_t>(r.run.ticks));
    // at rest in the hold the filtered sensor reads the true contact force (means over 0.5 s)
    Eigen::Vector3d measured = Eigen::Vector3d::Zero(), truth = Eigen::Vector3d::Zero();
    const std::size_t window = 250;
    for (std::size_t k = r.samples.size() - window; k < r.samples.size(); ++k) {
      measured += r.samples[k].F_measured.head<3>() / window;
      truth += r.samples[k].F_peg.head<3>() / window;
    }
    EXPECT_LT((measured - truth).norm(), 0.02)
        << measured.transpose() << " | " << truth.transpose();
    const DockingSample& last = r.samples.back();
    // the lateral axes were released on contact, the others kept
    EXPECT_EQ(last.stiffness[0], 0.0);
    EXPECT_EQ(last.stiffness[2], 1000.0);
    if (dx != 0.0) {
      EXPECT_GT(m.first_contact_time, 0.6);  // on the chamfer, after the approach
    }
  }
}

TEST(Docking, TheFigureShowsTheForcesTheStiffnessAndWhereTheTipIs) {
  const DockingReport r = run_docking(quick(6.0, 0.0, 0.0));
  const plot::TimeSeriesFigure f = docking_figure(r);
  ASSERT_EQ(f.panels.size(), 3u);
  ASSERT_EQ(f.t.size(), r.samples.size());
  const std::size_t k = r.samples.size() - 1;
  EXPECT_DOUBLE_EQ(f.panels[0].series[0].values[k], r.samples[k].F_peg[2]);  // z_S = world z
  EXPECT_DOUBLE_EQ(f.panels[1].series[2].values[k], 1000.0);
  EXPECT_NEAR(f.panels[2].series[0].values[k], 50.0, 0.05);  // seated: 50 mm deep
  ASSERT_EQ(f.bands.size(), 3u);
  EXPECT_EQ(f.bands[1].label, "insert");
  EXPECT_DOUBLE_EQ(f.bands[2].start, r.plan.approach_time + r.plan.insert_time);
  const plot::PlotInfo info = plot_docking(r, test::scratch() / "docking-plot");
  EXPECT_TRUE(std::filesystem::exists(info.path));
  DockingReport empty;
  EXPECT_NE(error_of([&] { docking_figure(empty); }).find("no samples"), std::string::npos);
}

TEST(Docking, SensorlessSe3SeatsAndHoldsThePreload) {
  DockingOptions o = quick(6.0, 6.0, 15.0);
  o.controller.source = ForceSource::observer;
  const DockingReport r = run_docking(o);
  EXPECT_TRUE(r.ok()) << why(r);
  EXPECT_NEAR(r.metrics.steady_axial_force, o.motion.preload, 0.05 * o.motion.preload);
  EXPECT_EQ(r.bad_wrench_ticks, 0);
}

TEST(Docking, HqpAcSeatsThePegWithTheSensorAndSensorless) {
  for (const auto& [dx, dy, dyaw, source] : {std::tuple{6.0, -6.0, 15.0, ForceSource::sensor},
                                             std::tuple{0.0, 0.0, 0.0, ForceSource::sensor},
                                             std::tuple{-6.0, 6.0, -15.0, ForceSource::observer}}) {
    DockingOptions o = quick(dx, dy, dyaw);
    o.controller.law = DockingLaw::hqp_ac;
    o.controller.source = source;
    const DockingReport r = run_docking(o);
    EXPECT_TRUE(r.ok()) << dx << " " << dy << " " << dyaw << ": " << why(r);
    const DockingMetrics& m = r.metrics;
    EXPECT_LE(m.peak_force, 30.0) << why(r);
    // the task's preload, fed forward at the hold, is the steady force (also with no offset,
    // where nothing touches the peg before the bottom)
    EXPECT_NEAR(m.steady_axial_force, o.motion.preload, 0.05 * o.motion.preload) << why(r);
    // the arm starts held: the first reading is of the peg at rest (it was its whole weight,
    // 2.1 N, read from an arm falling under zero torque), and the free motion tracks
    EXPECT_LT(r.samples.front().F_measured.norm(), 0.05) << r.samples.front().F_measured;
    EXPECT_LT(m.position_rms, 0.02e-3);
    EXPECT_EQ(r.qp_least_squares, 0);  // counted, and none here: every QP solved
    EXPECT_EQ(r.qp_null_space_dropped, 0);
    const DockingSample& last = r.samples.back();
    const HqpAcOptions defaults;
    // K_r at its floor (E's x, y tilt by thousandths of a degree from the world's: 1e-6 N/m)
    EXPECT_NEAR(last.stiffness[2], 0.3 * defaults.compliance.stiffness(2, 2), 1e-3);
    if (dx != 0.0) {
      EXPECT_LT(last.stiffness.head<2>().norm(), 1e-3);  // released: E's x, y are world x, y here
    } else {
      EXPECT_GT(last.stiffness[0], 0.0);  // nothing touched the peg before the bottom
    }
  }
}

TEST(Docking, ASensorControllerOnASceneWithoutTheSensorStopsBeforeTheRun) {
  DockingSceneOptions scene_options;
  scene_options.ft_sensor = false;
  DockingOptions o = quick(0.0, 0.0, 0.0);
  o.scene = std::make_shared<const DockingScene>(build_docking_scene(scene_options));
  const std::string message = error_of([&] { run_docking(o); });
  EXPECT_NE(message.find("site 'iiwa/peg/ft'"), std::string::npos) << message;
  o.joint_friction = true;  // the scene given is the plain one
  EXPECT_NE(error_of([&] { run_docking(o); }).find("joint friction"), std::string::npos);
  o = quick(0.0, 0.0, 0.0);
  o.criteria.max_force = 0.0;
  EXPECT_NE(error_of([&] { run_docking(o); }).find("max_force"), std::string::npos);
  o = quick(0.0, 0.0, 0.0);
  o.offset.dx = std::nan("");
  EXPECT_NE(error_of([&] { run_docking(o); }).find("dx and dy"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
