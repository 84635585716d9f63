#include "mjarm/trajectory/min_jerk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"

namespace mjarm {
namespace {

TEST(MinJerk, StartsAndStopsAtRest) {
  const MinJerkProfile profile(0.7);
  const auto start = profile.at(0.0);
  const auto end = profile.at(0.7);
  EXPECT_EQ(start.s, 0.0);
  EXPECT_EQ(start.ds, 0.0);
  EXPECT_EQ(start.dds, 0.0);
  EXPECT_EQ(end.s, 1.0);
  EXPECT_EQ(end.ds, 0.0);
  EXPECT_EQ(end.dds, 0.0);
  // clamped outside [0, T], NaN gives the start
  EXPECT_EQ(profile.at(-1.0).s, 0.0);
  EXPECT_EQ(profile.at(5.0).s, 1.0);
  EXPECT_EQ(profile.at(std::nan("")).s, 0.0);
  // just inside the ends the values are continuous with the clamped ones
  EXPECT_NEAR(profile.at(1e-9).s, 0.0, 1e-20);
  EXPECT_NEAR(profile.at(0.7 - 1e-9).s, 1.0, 1e-15);
  EXPECT_NEAR(profile.at(0.7 - 1e-9).ds, 0.0, 1e-12);
}

TEST(MinJerk, DerivativesMatchFiniteDifferences) {
  const double T = 0.45;
  const MinJerkProfile profile(T);
  for (double t = 0.01; t < T - 0.01; t += 0.017) {
    // central differences of (s, ṡ) at t
    const Eigen::Vector2d d = finite_difference_derivative(
        [&](double u) { return Eigen::Vector2d(profile.at(u).s, profile.at(u).ds); }, t);
    const auto c = profile.at(t);
    EXPECT_NEAR(d[0], c.ds, 1e-6) << t;
    EXPECT_NEAR(d[1], c.dds, 1e-4) << t;
  }
}

TEST(MinJerk, PeaksAreWhereTheFormulaSays) {
  const double T = 0.3;
  const MinJerkProfile profile(T);
  double peak_v = 0.0, peak_a = 0.0;
  for (int i = 0; i <= 30000; ++i) {
    const auto x = profile.at(T * i / 30000.0);
    peak_v = std::max(peak_v, x.ds);
    peak_a = std::max(peak_a, std::abs(x.dds));
    EXPECT_GE(x.s, 0.0);
    EXPECT_LE(x.s, 1.0);
    EXPECT_GE(x.ds, 0.0);  // monotone
  }
  EXPECT_NEAR(peak_v * T, MinJerkProfile::kPeakVelocity, 1e-9);
  EXPECT_NEAR(peak_a * T * T, MinJerkProfile::kPeakAcceleration, 1e-6);
  EXPECT_NEAR(profile.at(T / 2).s, 0.5, 1e-15);  // symmetric
}

TEST(MinJerk, DurationRespectsEveryBound) {
  // acceleration-bound move: 0.3 m at 10 m/s²
  const double T = MinJerkProfile::duration_for(0.3, 100.0, 10.0, 0.05);
  EXPECT_NEAR(MinJerkProfile::kPeakAcceleration * 0.3 / (T * T), 10.0, 1e-12);
  // velocity-bound move
  const double Tv = MinJerkProfile::duration_for(2.0, 1.0, 1e6, 0.05);
  EXPECT_NEAR(MinJerkProfile::kPeakVelocity * 2.0 / Tv, 1.0, 1e-12);
  // tiny move: the minimum duration
  EXPECT_EQ(MinJerkProfile::duration_for(0.0, 1.0, 1.0, 0.2), 0.2);
}

TEST(MinJerk, RejectsBadInput) {
  EXPECT_THROW(MinJerkProfile(0.0), Error);
  EXPECT_THROW(MinJerkProfile(-1.0), Error);
  EXPECT_THROW(MinJerkProfile(std::numeric_limits<double>::infinity()), Error);
  EXPECT_THROW(MinJerkProfile::duration_for(-0.1, 1.0, 1.0, 0.1), Error);
  EXPECT_THROW(MinJerkProfile::duration_for(0.1, 0.0, 1.0, 0.1), Error);
  EXPECT_THROW(MinJerkProfile::duration_for(0.1, 1.0, std::nan(""), 0.1), Error);
  EXPECT_THROW(MinJerkProfile::duration_for(0.1, 1.0, 1.0, 0.0), Error);
}

}  // namespace
}  // namespace mjarm
