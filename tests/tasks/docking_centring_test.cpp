#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/tasks/docking/centring.hpp"
#include "mjarm/tasks/docking/docking.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::kDockingDeg;

constexpr double kClearance = 0.5e-3;
constexpr double kTick = 0.002;

/// A peg that follows its lateral reference exactly, but only inside the bore: its centre stays
/// within the clearance of @p axis (all relative to the uncentred reference, lateral).
Eigen::Vector3d peg_in_bore(const Eigen::Vector3d& reference, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d e = reference - axis;
  return e.norm() <= kClearance ? reference : Eigen::Vector3d(axis + kClearance * e.normalized());
}

struct Probe {
  bool found = false;
  Eigen::Vector3d end = Eigen::Vector3d::Zero();  // the shift at the end
  double largest_step = 0.0;                      // of the shift between ticks
};

/// Runs the centring on `peg_in_bore` from the peg at @p tip (the reference at the origin,
/// u = −z), as the task does: decide every tick until it starts, then update.
Probe run_probe(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                const DockingCentringOptions& options = {}) {
  BoreCentring centring(options, kClearance);
  const Eigen::Vector3d u(0.0, 0.0, -1.0), ref = Eigen::Vector3d::Zero();
  const double depth = options.start_depth + 1e-3;
  EXPECT_FALSE(centring.decide(depth, tip, ref, u, 1.0));  // no previous tick: not known at rest
  EXPECT_TRUE(centring.decide(depth, tip, ref, u, 1.0 + kTick));
  Probe probe;
  // it starts on the tip: nothing jumps when the stiffness comes back
  EXPECT_NEAR((centring.shift(1.0 + kTick) - tip).norm(), 0.0, 1e-15);
  Eigen::Vector3d last = centring.shift(1.0 + kTick);
  for (double t = 1.0 + 2 * kTick; t < 4.0; t += kTick) {
    const Eigen::Vector3d peg = peg_in_bore(centring.shift(t - kTick), axis);
    centring.update(peg, ref, t);
    const Eigen::Vector3d now = centring.shift(t);
    probe.largest_step = std::max(probe.largest_step, (now - last).norm());
    last = now;
  }
  probe.found = centring.found_wall();
  probe.end = last;
  return probe;
}

TEST(DockingCentring, TheProbeFindsTheWallAheadOrBehindAndEndsOnTheAxis) {
  const Eigen::Vector3d axis(-1.0e-3, 0.4e-3, 0.0);  // the true axis, off the believed one
  const Eigen::Vector3d toward = axis.normalized();
  // at the wall it slid from (between the believed axis and the true one) ...
  const Probe near = run_probe(axis - kClearance * toward, axis);
  EXPECT_TRUE(near.found);
  // ... and carried across to the far wall: the same line, the axis behind the peg
  const Probe far = run_probe(axis + kClearance * toward, axis);
  EXPECT_TRUE(far.found);
  for (const Probe& p : {near, far}) {
    // the peg here stops at the wall itself: the axis to within the ticks' resolution
    EXPECT_LT((p.end - axis).norm(), 2e-6) << p.end.transpose();
    EXPECT_LT(p.largest_step, 1e-5);  // smooth: a jump would be the lag, 0.25 mm, or more
  }
}

TEST(DockingCentring, AProbeThatMeetsNoWallGoesBackToWhereItStarted) {
  const Eigen::Vector3d tip(0.3e-3, -0.4e-3, 0.0);
  DockingCentringOptions short_probe;
  short_probe.probe_travel = 0.3e-3;  // the wall ahead is 0.95 mm away
  const Probe free = run_probe(tip, tip + 0.45e-3 * tip.normalized(), short_probe);
  EXPECT_FALSE(free.found);
  EXPECT_LT((free.end - tip).norm(), 1e-15);
}

TEST(DockingCentring, ItStartsOnlyOnAPegAtRestThatAContactMoved) {
  DockingCentringOptions o;
  BoreCentring centring(o, kClearance);
  const Eigen::Vector3d u(0.0, 0.0, -1.0), ref(0.6, 0.0, 0.18);
  const Eigen::Vector3d tip = ref + Eigen::Vector3d(0.3e-3, -0.4e-3, 2e-3);
  // not deep enough yet
  EXPECT_FALSE(centring.decide(o.start_depth - 1e-4, tip, ref, u, 1.0));
  // moving sideways at 10 mm/s (crossing the bore): not yet
  const Eigen::Vector3d step(0.02e-3, 0.0, 0.0);
  EXPECT_FALSE(centring.decide(o.start_depth, tip + step, ref, u, 1.0 + kTick));
  EXPECT_FALSE(centring.active());
  // at rest: it starts, once; the probe's speed ramps in, its travel against its speed
  EXPECT_TRUE(centring.decide(o.start_depth, tip + step, ref, u, 1.0 + 2 * kTick));
  EXPECT_FALSE(centring.decide(o.start_depth, tip + step, ref, u, 1.0 + 3 * kTick));
  EXPECT_TRUE(centring.active());
  const double t0 = 1.0 + 2 * kTick;
  EXPECT_EQ(centring.probe_speed(t0), 0.0);
  EXPECT_DOUBLE_EQ(centring.probe_speed(t0 + o.probe_ramp + 0.1), o.probe_speed);
  for (const double t : {t0 + 0.05, t0 + 0.2, t0 + o.probe_ramp, t0 + 0.4}) {
    const double h = 1e-6;
    const double fd = (centring.probe_travel(t + h) - centring.probe_travel(t - h)) / (2 * h);
    EXPECT_NEAR(centring.probe_speed(t), fd, 1e-9) << t;
    const Eigen::Vector3d rate_fd = (centring.shift(t + h) - centring.shift(t - h)) / (2 * h);
    EXPECT_NEAR((centring.shift_rate(t) - rate_fd).norm(), 0.0, 1e-9) << t;
    EXPECT_DOUBLE_EQ(centring.shift(t).dot(u), 0.0);  // lateral only
  }
  centring.reset();
  EXPECT_FALSE(centring.active());
  EXPECT_EQ(centring.shift(2.0).norm(), 0.0);

  // a peg that met nothing (tracking error only) is not moved, nor with the centring off
  BoreCentring untouched(o, kClearance);
  const Eigen::Vector3d tracking = ref + Eigen::Vector3d(5e-6, 0.0, -3e-3);
  for (int k = 0; k < 3; ++k)
    EXPECT_FALSE(untouched.decide(0.02, tracking, ref, u, 1.0 + k * kTick));
  EXPECT_FALSE(untouched.active());
  o.enabled = false;
  BoreCentring off(o, kClearance);
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(off.decide(0.02, tip, ref, u, 1.0 + k * kTick));
}

std::shared_ptr<const DockingScene> centring_scene() {
  static const auto s = std::make_shared<const DockingScene>(build_docking_scene());
  return s;
}

TEST(DockingCentring, HqpAcSensorlessSeatsAOneMillimetreOffsetWithLateralRoom) {
  // the capture map's failure (the command's own run): HQP-AC with the observer at (0, 1 mm, 0)
  // ended 0.501 mm off the axis, against the wall it slid from
  DockingOptions o;
  o.scene = centring_scene();
  o.offset = {0.0, 1e-3, 0.0};
  o.controller.law = DockingLaw::hqp_ac;
  o.controller.source = ForceSource::observer;
  DockingOptions before = o;
  before.motion.centring.enabled = false;
  const DockingReport a = run_docking(before);
  EXPECT_FALSE(a.ok()) << docking_result_line(a);
  EXPECT_GT(a.metrics.max_lateral, 0.5e-3) << docking_result_line(a);

  const DockingReport r = run_docking(o);
  EXPECT_TRUE(r.ok()) << docking_result_line(r);
  EXPECT_LE(r.metrics.max_lateral, 0.2e-3) << docking_result_line(r);
  EXPECT_LE(r.metrics.peak_force, a.metrics.peak_force + 1e-9);
  EXPECT_NEAR(r.metrics.steady_axial_force, o.motion.preload, 0.05 * o.motion.preload);
  // HQP-AC's hard limits hold through the probe: joints in range and under their speed limits,
  // no motor clipped, every QP solved, and nothing but the socket touched
  for (const DockingSample& s : r.samples) {
    EXPECT_TRUE(s.within_limits) << s.t;
    EXPECT_LE(s.joint_velocity_ratio, 1.0) << s.t;
    EXPECT_FALSE(s.saturated) << s.t;
    EXPECT_FALSE(s.other_contact) << s.t;
  }
  EXPECT_EQ(r.qp_least_squares, 0);
  EXPECT_EQ(r.qp_null_space_dropped, 0);
  // released again at the bottom, as before the centring
  EXPECT_LT(r.samples.back().stiffness.head<2>().norm(), 1e-3);
}

TEST(DockingCentring, Se3SensorlessSeatsTheMapsOneMillimetreFailure) {
  DockingOptions o;
  o.scene = centring_scene();
  o.offset = {-std::sqrt(0.5) * 1e-3, std::sqrt(0.5) * 1e-3, 10.0 * kDockingDeg};
  o.controller.source = ForceSource::observer;
  const DockingReport r = run_docking(o);
  EXPECT_TRUE(r.ok()) << docking_result_line(r);
  EXPECT_LE(r.metrics.max_lateral, 0.2e-3) << docking_result_line(r);
  EXPECT_EQ(r.samples.back().stiffness[0], 0.0);  // released at the bottom
}

}  // namespace
}  // namespace mjarm
