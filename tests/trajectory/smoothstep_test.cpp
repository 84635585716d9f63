#include "mjarm/trajectory/smoothstep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/trajectory/quintic.hpp"

namespace mjarm {
namespace {

TEST(Smoothstep, ValuesEndsAndClipping) {
  EXPECT_EQ(smoothstep(0.0).s, 0.0);
  EXPECT_EQ(smoothstep(1.0).s, 1.0);
  EXPECT_EQ(smoothstep(0.5).s, 0.5);
  EXPECT_NEAR(smoothstep(0.25).s, 0.0625 * 2.5, 1e-15);
  EXPECT_EQ(smoothstep(-3.0).s, 0.0);
  EXPECT_EQ(smoothstep(4.0).s, 1.0);
  EXPECT_EQ(smoothstep(4.0).ds, 0.0);
  EXPECT_EQ(smoothstep(std::nan("")).s, 0.0);
  EXPECT_EQ(smoothstep(0.0).ds, 0.0);  // C¹ at both ends
  EXPECT_EQ(smoothstep(1.0).ds, 0.0);
  EXPECT_EQ(smoothstep(0.5).ds, 1.5);
  EXPECT_EQ(smootherstep(0.0).s, 0.0);
  EXPECT_EQ(smootherstep(1.0).s, 1.0);
  EXPECT_EQ(smootherstep(0.5).s, 0.5);
  EXPECT_EQ(smootherstep(1.0).dds, 0.0);  // C² at both ends
  EXPECT_EQ(smootherstep(0.0).dds, 0.0);
  EXPECT_EQ(smootherstep(2.0).s, 1.0);
  EXPECT_EQ(smootherstep(-2.0).ddds, 0.0);
}

TEST(Smoothstep, DerivativesMatchFiniteDifferences) {
  const double h = 1e-6;
  for (double x = 0.01; x < 1.0; x += 0.0137) {
    for (const auto f : {&smoothstep, &smootherstep}) {
      const RampSample a = f(x - h), b = f(x + h), c = f(x);
      EXPECT_NEAR((b.s - a.s) / (2 * h), c.ds, 1e-8) << x;
      EXPECT_NEAR((b.ds - a.ds) / (2 * h), c.dds, 1e-7) << x;
      EXPECT_NEAR((b.dds - a.dds) / (2 * h), c.ddds, 1e-6) << x;
      EXPECT_GE(c.ds, 0.0);
    }
  }
}

TEST(Smoothstep, SmootherstepIsTheRestToRestQuintic) {
  // the minimum-jerk scaling: the quintic from rest at 0 to rest at 1 (its own coefficients)
  const Quintic q({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 2.0);
  const SmoothRamp ramp(SmoothRamp::Kind::smootherstep, 2.0);
  for (double t = 0.0; t <= 2.0; t += 0.1) {
    EXPECT_NEAR(ramp.at(t).s, q.at(t).p, 1e-15) << t;
    EXPECT_NEAR(ramp.at(t).ds, q.at(t).v, 1e-14) << t;
    EXPECT_NEAR(ramp.at(t).dds, q.at(t).a, 1e-13) << t;
    EXPECT_NEAR(ramp.at(t).ddds, q.at(t).j, 1e-12) << t;
  }
  const Quintic::Peaks peaks = q.peaks();
  EXPECT_NEAR(peaks.velocity * 2.0, SmoothRamp::peak_slope(SmoothRamp::Kind::smootherstep), 1e-12);
  EXPECT_NEAR(peaks.acceleration * 4.0, SmoothRamp::peak_curvature(SmoothRamp::Kind::smootherstep),
              1e-10);
  EXPECT_NEAR(peaks.jerk * 8.0, SmoothRamp::peak_jerk(SmoothRamp::Kind::smootherstep), 1e-9);
  EXPECT_EQ(SmoothRamp::peak_jerk(SmoothRamp::Kind::smoothstep), 12.0);  // s‴ = −12 throughout
}

TEST(SmoothRamp, TimeDerivativesAndTheShortestDuration) {
  for (const auto kind : {SmoothRamp::Kind::smoothstep, SmoothRamp::Kind::smootherstep}) {
    const double d = 0.08, v = 0.1, a = 0.3;
    const double T = SmoothRamp::duration_for(kind, d, v, a);
    const SmoothRamp ramp(kind, T);
    double peak_v = 0.0, peak_a = 0.0;
    for (int k = 0; k <= 20000; ++k) {
      const RampSample s = ramp.at(T * k / 20000.0);
      peak_v = std::max(peak_v, d * s.ds);
      peak_a = std::max(peak_a, std::abs(d * s.dds));
    }
    EXPECT_LE(peak_v, v * (1 + 1e-12));
    EXPECT_LE(peak_a, a * (1 + 1e-12));
    // one of the two limits is met (to the sampling resolution)
    EXPECT_GT(std::max(peak_v / v, peak_a / a), 1.0 - 1e-6);
    const double h = 1e-6;
    EXPECT_NEAR((ramp.at(0.3 * T + h).s - ramp.at(0.3 * T - h).s) / (2 * h), ramp.at(0.3 * T).ds,
                1e-7);
    EXPECT_EQ(ramp.at(T + 1).s, 1.0);
  }
  EXPECT_EQ(SmoothRamp::duration_for(SmoothRamp::Kind::smoothstep, 0.0, 1.0, 1.0), 0.0);
}

TEST(SmoothRamp, RejectsBadInput) {
  using K = SmoothRamp::Kind;
  EXPECT_THROW(SmoothRamp(K::smoothstep, 0.0), Error);
  EXPECT_THROW(SmoothRamp(K::smoothstep, -1.0), Error);
  EXPECT_THROW(SmoothRamp(K::smootherstep, std::numeric_limits<double>::infinity()), Error);
  EXPECT_THROW(SmoothRamp::duration_for(K::smoothstep, -0.1, 1.0, 1.0), Error);
  EXPECT_THROW(SmoothRamp::duration_for(K::smoothstep, 0.1, 0.0, 1.0), Error);
  EXPECT_THROW(SmoothRamp::duration_for(K::smoothstep, 0.1, 1.0, std::nan("")), Error);
  EXPECT_THROW(SmoothRamp(K::smoothstep, std::nan("")), Error);
  EXPECT_THROW(SmoothRamp::duration_for(K::smootherstep, std::nan(""), 1.0, 1.0), Error);
  // finite input whose duration overflows
  EXPECT_THROW(SmoothRamp::duration_for(K::smootherstep, 1e300, 1e-300, 1.0), Error);
}

}  // namespace
}  // namespace mjarm
