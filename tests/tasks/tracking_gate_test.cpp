#include "mjarm/tasks/docking/tracking_gate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mjarm/lie/so3.hpp"
#include "support/error_message.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

Pose start() {
  Pose X;
  X.R = Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal();
  X.p = Eigen::Vector3d(0.6, 0.0, 0.4);
  return X;
}

TEST(TrackingGate, TheReferenceIsACircleThenAFigureEightWithExactDerivatives) {
  const TrackingGateOptions o;
  const Pose X = start();
  const double loop = 1.0 / o.frequency + o.ramp_time;
  EXPECT_DOUBLE_EQ(tracking_gate_duration(o), 2.0 * loop + o.settle_time);
  const double h = 1e-5;
  for (double t = 0.0; t < tracking_gate_duration(o); t += 0.0937) {
    const auto s = tracking_gate_reference(o, X, t);
    const auto a = tracking_gate_reference(o, X, t - h);
    const auto b = tracking_gate_reference(o, X, t + h);
    EXPECT_LT((s.V_WE.head<3>() - (b.X_WE.p - a.X_WE.p) / (2 * h)).norm(), 1e-8) << t;
    EXPECT_LT((s.A_WE.head<3>() - (b.V_WE.head<3>() - a.V_WE.head<3>()) / (2 * h)).norm(), 1e-5)
        << t;
    EXPECT_EQ(s.X_WE.R, X.R);                 // orientation held
    EXPECT_DOUBLE_EQ(s.X_WE.p.x(), X.p.x());  // in the y-z plane
    const Eigen::Vector3d d = s.X_WE.p - X.p;
    if (t < loop) {
      // on the circle of radius r about c + r·z
      EXPECT_NEAR((d - Eigen::Vector3d(0, 0, o.radius)).norm(), o.radius, 1e-12) << t;
    } else {
      // on the eight: z = ½·r·sin 2φ with y = r·sin φ  ⇒  z² = y²·(1 − y²/r²)
      const double y = d.y() / o.radius, z = d.z() / o.radius;
      EXPECT_NEAR(z * z, y * y * (1.0 - y * y), 1e-12) << t;
    }
  }
  // each loop starts and ends at rest at c; the cruise runs at ω = 2πf
  for (const double t : {0.0, loop, 2.0 * loop}) {
    const auto s = tracking_gate_reference(o, X, t);
    EXPECT_LT((s.X_WE.p - X.p).norm(), 1e-12) << t;
    EXPECT_LT(s.V_WE.norm(), 1e-12) << t;
  }
  const auto cruise = tracking_gate_reference(o, X, 0.5 * loop);
  EXPECT_NEAR(cruise.V_WE.head<3>().norm(), 2.0 * std::numbers::pi * o.frequency * o.radius, 1e-12);
}

TEST(TrackingGate, Se3ImpedanceTracksAShortGateWithinTheTargets) {
  TrackingGateOptions o;
  o.radius = 0.05;  // a shorter, faster gate than the command's
  o.frequency = 0.5;
  o.ramp_time = 0.5;
  o.settle_time = 0.1;
  const TrackingGateReport r = run_tracking_gate(o);
  EXPECT_EQ(r.run.status, RunStatus::finished);
  EXPECT_EQ(r.contact_ticks, 0);
  EXPECT_TRUE(passes(r)) << r.total.position_rms << " m, " << r.total.orientation_rms << " rad";
  EXPECT_GT(r.loops[0].samples, 0);
  EXPECT_GT(r.loops[1].samples, 0);
  EXPECT_EQ(r.loops[0].samples + r.loops[1].samples, r.total.samples);
  EXPECT_GT(r.total.position_rms, 0.0);
  EXPECT_LE(r.total.position_rms, std::max(r.loops[0].max_position, r.loops[1].max_position));
}

TEST(TrackingGate, BadOptionsAreNamed) {
  auto message = [](auto edit) {
    TrackingGateOptions o;
    edit(o);
    return error_of([&] { run_tracking_gate(o); });
  };
  EXPECT_TRUE(contains(message([](auto& o) { o.ramp_time = 6.0; }), "shorter than a loop"));
  EXPECT_TRUE(contains(message([](auto& o) { o.radius = 0.3; }), "dip into the socket"));
  EXPECT_TRUE(contains(message([](auto& o) { o.frequency = 0.0; }), "frequency"));
  EXPECT_TRUE(contains(message([](auto& o) { o.settle_time = -1.0; }), "settle_time"));
  EXPECT_TRUE(contains(message([](auto& o) { o.controller.cic_damping_ratio = 0.0; }),
                       "cic_damping_ratio"));
}

}  // namespace
}  // namespace mjarm
