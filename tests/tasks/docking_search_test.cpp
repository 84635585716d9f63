#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "mjarm/tasks/docking/docking.hpp"
#include "mjarm/tasks/docking/search.hpp"
#include "support/error_message.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

std::shared_ptr<const DockingScene> search_scene() {
  static const auto s = std::make_shared<const DockingScene>(build_docking_scene());
  return s;
}

/// A short run (start 30 mm above, 1.2 s hold) with the search on (its defaults) and the
/// command's insertion speed, 10 mm/s: at the docking test's 20 mm/s the first touch on the flat
/// top face alone peaks at 36–37 N (the arm's inertia meets the face before any law acts).
DockingOptions quick_search(double dx_mm, double dy_mm, double dyaw_deg, DockingLaw law,
                            ForceSource source = ForceSource::sensor) {
  DockingOptions o;
  o.scene = search_scene();
  o.offset = {dx_mm * 1e-3, dy_mm * 1e-3, dyaw_deg * kDockingDeg};
  o.motion.start_height = 0.03;
  o.motion.approach_time = 0.6;
  o.motion.hold_time = 1.2;
  o.controller.law = law;
  o.controller.source = source;
  return o;
}

std::string search_why(const DockingReport& r) {
  return docking_result_line(r) + " searches=" + std::to_string(r.searches) +
         " search_time=" + std::to_string(r.search_time);
}

TEST(DockingSearchPath, TheSpiralMovesAtItsSpeedAndGrowsByThePitchPerTurn) {
  DockingSearchOptions o;
  o.pitch = 0.004;
  o.speed = 0.01;
  o.max_radius = 0.008;
  SearchPath path(o);
  const double h = 1e-6;
  double angle_before = 0.0;
  double turns = 0.0;
  for (double t = 0.01; t < 3.0; t += 0.01) {
    SearchPath::Sample a = path.at(t - h);
    SearchPath::Sample b = path.at(t + h);
    const SearchPath::Sample s = path.at(t);
    const Eigen::Vector2d fd = (b.offset - a.offset) / (2.0 * h);
    EXPECT_NEAR((fd - s.velocity).norm(), 0.0, 1e-6) << t;
    EXPECT_NEAR(s.velocity.norm(), o.speed, 1e-9) << t;
    // r = pitch·θ/2π with θ the unwrapped polar angle
    double angle = std::atan2(s.offset.y(), s.offset.x());
    if (angle < angle_before - std::numbers::pi) turns += 1.0;
    angle_before = angle;
    const double theta = angle + 2.0 * std::numbers::pi * turns;
    EXPECT_NEAR(
        s.radius,
        o.pitch * (theta < 0 ? theta + 2 * std::numbers::pi : theta) / (2.0 * std::numbers::pi),
        1e-9)
        << t;
  }
  // reaches its radius when it says so
  SearchPath again(o);
  const double T = again.time_to_max_radius();
  EXPECT_NEAR(again.at(T).radius, o.max_radius, 1e-9);
}

TEST(DockingSearchPath, TheLissajousFigureStaysInItsSquareAtItsSpeed) {
  DockingSearchOptions o;
  o.pattern = SearchPattern::lissajous;
  o.max_radius = 0.006;
  SearchPath path(o);
  EXPECT_TRUE(std::isinf(path.time_to_max_radius()));
  const double h = 1e-6;
  for (double t = 0.0; t < 10.0; t += 0.013) {
    const SearchPath::Sample s = path.at(t);
    EXPECT_LE(s.radius, o.max_radius + 1e-12);  // the square inside the circle
    if (t >= h) {
      const Eigen::Vector2d fd = (path.at(t + h).offset - path.at(t - h).offset) / (2.0 * h);
      EXPECT_NEAR((fd - s.velocity).norm(), 0.0, 1e-6) << t;
    }
    EXPECT_LE(std::abs(s.velocity.x()), o.speed + 1e-12);        // x's peak speed
    EXPECT_LE(std::abs(s.velocity.y()), 2.0 * o.speed + 1e-12);  // κ = (N+1)/N ≤ 2 times it
  }
}

TEST(DockingSearch, BadOptionsAreRefusedBeforeTheRun) {
  const DockingGeometry g;
  auto with = [&](auto edit) {
    DockingOptions o = quick_search(8.0, 8.0, 20.0, DockingLaw::se3);
    edit(o.motion.search);
    return error_of([&] { run_docking(o); });
  };
  EXPECT_TRUE(contains(with([](DockingSearchOptions& s) { s.pitch = 0.0; }), "pitch"));
  EXPECT_TRUE(contains(with([](DockingSearchOptions& s) { s.pitch = -1e-3; }), "pitch"));
  EXPECT_TRUE(contains(
      with([](DockingSearchOptions& s) { s.speed = std::numeric_limits<double>::quiet_NaN(); }),
      "speed"));
  EXPECT_TRUE(contains(with([](DockingSearchOptions& s) { s.speed = 0.0; }), "speed"));
  EXPECT_TRUE(contains(with([](DockingSearchOptions& s) { s.contact_force = 31.0; }),
                       "contact_force must not exceed force_limit"));
  const std::string radius = with([](DockingSearchOptions& s) { s.max_radius = 0.03; });
  EXPECT_TRUE(contains(radius, "max_radius")) << radius;
  EXPECT_TRUE(contains(radius, "top face")) << radius;
  // the largest radius the socket allows is accepted
  DockingSearchOptions edge;
  edge.max_radius = g.bore_radius + g.chamfer + g.wall - g.peg_radius;
  EXPECT_NO_THROW(check(edge, g));
  EXPECT_EQ(search_pattern("lissajous"), SearchPattern::lissajous);
  EXPECT_TRUE(contains(error_of([] { search_pattern("spiraal"); }), "spiral"));
}

/// Peak of the true contact force while the task searched (the samples between the miss and
/// the drop or the end).
double peak_while_searching(const DockingReport& r) {
  double peak = 0.0;
  const double end = std::isnan(r.drop_time) ? 1e9 : r.drop_time;
  for (const DockingSample& s : r.samples)
    if (s.t >= r.miss_time && s.t <= end) peak = std::max(peak, s.F_peg.head<3>().norm());
  return peak;
}

TEST(DockingSearch, AMissOnTheTopFaceIsFoundAndSeatedWithBothLaws) {
  for (const DockingLaw law : {DockingLaw::se3, DockingLaw::hqp_ac}) {
    for (const auto& [dx, dy, dyaw] : {std::tuple{8.0, 8.0, 20.0}, std::tuple{9.0, 0.0, 0.0}}) {
      const DockingReport r = run_docking(quick_search(dx, dy, dyaw, law));
      SCOPED_TRACE(std::string(to_string(law)) + " " + std::to_string(dx) + " " +
                   std::to_string(dy) + " " + std::to_string(dyaw) + ": " + search_why(r));
      EXPECT_TRUE(r.ok());
      EXPECT_LE(r.metrics.peak_force, 30.0);
      EXPECT_LE(r.search_time, 5.0);
      if (dx == 8.0) {  // 11.3 mm off: the peg lands on the top face
        EXPECT_GE(r.searches, 1);
        EXPECT_LE(peak_while_searching(r), 30.0);
      }
    }
  }
}

TEST(DockingSearch, TheLissajousPatternFindsTheHoleToo) {
  DockingOptions o = quick_search(8.0, -8.0, 0.0, DockingLaw::hqp_ac);
  o.motion.search.pattern = search_pattern("lissajous");
  const DockingReport r = run_docking(o);
  EXPECT_TRUE(r.ok()) << search_why(r);
  EXPECT_GE(r.searches, 1);
  EXPECT_LE(peak_while_searching(r), 30.0) << search_why(r);
}

TEST(DockingSearch, AFarOffsetEndsSearchExhaustedWithinTheForceLimit) {
  DockingOptions o = quick_search(25.0, 0.0, 0.0, DockingLaw::se3);
  const DockingReport r = run_docking(o);
  EXPECT_EQ(r.outcome, DockingOutcome::search_exhausted) << search_why(r);
  EXPECT_GE(r.searches, 1);
  EXPECT_LE(r.metrics.peak_force, o.motion.search.force_limit) << search_why(r);
  EXPECT_LE(peak_while_searching(r), o.motion.search.force_limit) << search_why(r);
  EXPECT_NEAR(r.search_time, o.motion.search.timeout, 0.01);
  EXPECT_TRUE(contains(docking_result_line(r), "search_exhausted"));
}

TEST(DockingSearch, SensorlessTheObserverFindsTheHoleAndHqpAcKeepsItsHardLimits) {
  for (const DockingLaw law : {DockingLaw::se3, DockingLaw::hqp_ac}) {
    const DockingReport r = run_docking(quick_search(8.0, -8.0, 0.0, law, ForceSource::observer));
    SCOPED_TRACE(std::string(to_string(law)) + ": " + search_why(r));
    EXPECT_TRUE(r.ok());
    EXPECT_GE(r.searches, 1);
    EXPECT_LE(r.metrics.peak_force, 30.0);
    EXPECT_LE(peak_while_searching(r), 30.0);
    ASSERT_FALSE(r.samples.empty());
    // the search's samples: in contact, the joints inside their ranges and speed limits, no
    // motor clipped (HQP-AC's hard bounds; the SE(3) law has none but must not need them)
    int searching = 0;
    for (const DockingSample& s : r.samples) {
      if (!(s.t >= r.miss_time && s.t <= r.drop_time)) continue;
      ++searching;
      EXPECT_TRUE(s.within_limits) << s.t;
      EXPECT_LE(s.joint_velocity_ratio, 1.0) << s.t;
      EXPECT_FALSE(s.saturated) << s.t;
      EXPECT_FALSE(s.other_contact) << s.t;
    }
    EXPECT_GT(searching, 10);
    EXPECT_EQ(r.metrics.saturation, 0.0);
    EXPECT_EQ(r.qp_least_squares, 0);
  }
}

TEST(DockingSearch, InsideTheGridNothingChanges) {
  // offsets of the 27-offset grid land on the chamfer: no miss, the run of the search off
  for (const DockingLaw law : {DockingLaw::se3, DockingLaw::hqp_ac}) {
    DockingOptions on = quick_search(6.0, -6.0, 15.0, law);
    DockingOptions off = on;
    off.motion.search.pattern = SearchPattern::none;
    const DockingReport a = run_docking(on), b = run_docking(off);
    EXPECT_EQ(a.searches, 0) << search_why(a);
    EXPECT_TRUE(a.ok()) << search_why(a);
    EXPECT_EQ(a.metrics.peak_force, b.metrics.peak_force);
    EXPECT_EQ(a.run.ticks, b.run.ticks);
  }
}

}  // namespace
}  // namespace mjarm
