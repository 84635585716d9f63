#include "trajectory/path/reachability.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/random.hpp"

namespace mjarm {
namespace {

// The controllable interval by brute force: every lower bound on u against every upper bound
// (Fourier–Motzkin, the landing rows included as ordinary rows), intersected; a row whose u
// coefficient is at most 1e-9 bounds x alone, as in the library.
topp::XInterval reachability_by_pairs(const topp::StepRows& rows, double delta,
                                      topp::XInterval next, double lo, double hi) {
  struct Line {
    double a, b, c;
  };
  std::vector<Line> all;
  for (int k = 0; k < rows.count; ++k) all.push_back({rows.alpha[k], rows.beta[k], rows.gamma[k]});
  all.push_back({2.0 * delta, 1.0, next.hi});
  all.push_back({-2.0 * delta, -1.0, -next.lo});
  topp::XInterval x{lo, hi};
  for (const Line& row : all) {
    if (std::abs(row.a) > 1e-9) continue;
    if (row.b > 0.0) x.hi = std::min(x.hi, row.c / row.b);
    if (row.b < 0.0) x.lo = std::max(x.lo, row.c / row.b);
  }
  for (const Line& up : all) {
    if (up.a <= 1e-9) continue;
    for (const Line& down : all) {
      if (down.a >= -1e-9) continue;
      // (c_u − b_u x)/a_u ≥ (c_d − b_d x)/a_d
      const double slope = -up.b / up.a + down.b / down.a;
      const double rest = up.c / up.a - down.c / down.a;  // slope·x + rest ≥ 0
      if (slope > 0.0) x.lo = std::max(x.lo, -rest / slope);
      if (slope < 0.0) x.hi = std::min(x.hi, -rest / slope);
      if (slope == 0.0 && rest < 0.0) return {1.0, 0.0};
    }
  }
  return x;
}

// Newton's method on the concave gap finds the same interval as the pairs, on random steps of
// 7 joints (rows as TimeOptimalPath writes them: two-sided, both ends of the step), some with a
// joint at rest (a u coefficient of 1e-11: a bound on x) or nearly (1e-6: large bounds on u).
TEST(Reachability, NewtonOnTheGapMatchesPairwiseElimination) {
  Random rng(17);
  topp::StepRows rows(28);
  int nonempty = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    rows.count = 0;
    const double delta = uniform(rng, 0.01, 0.3);
    for (int j = 0; j < 7; ++j) {
      double d1 = uniform(rng, -1.0, 1.0), d1_next = d1 + uniform(rng, -0.2, 0.2);
      if (trial % 5 == 0 && j == 3) d1 = 1e-11, d1_next = -1e-11;
      if (trial % 5 == 1 && j == 3) d1 = 1e-6, d1_next = -1e-6;
      const double d2 = uniform(rng, -3.0, 3.0), d2_next = d2 + uniform(rng, -0.5, 0.5);
      const double a = uniform(rng, 1.0, 10.0);
      rows.add_two_sided(d1 / a, d2 / a, -1.0, 1.0);
      rows.add_two_sided((d1_next + 2.0 * delta * d2_next) / a, d2_next / a, -1.0, 1.0);
    }
    const topp::XInterval next{0.0, uniform(rng, 0.0, 5.0)};
    const double x_hi = uniform(rng, 0.5, 20.0);
    const topp::XInterval newton = topp::controllable_interval(rows, delta, next, 0.0, x_hi);
    const topp::XInterval pairs = reachability_by_pairs(rows, delta, next, 0.0, x_hi);
    ASSERT_EQ(newton.empty(), pairs.empty()) << "trial " << trial;
    if (pairs.empty()) continue;
    ++nonempty;
    EXPECT_NEAR(newton.lo, pairs.lo, 1e-9 * (1.0 + pairs.hi)) << "trial " << trial;
    EXPECT_NEAR(newton.hi, pairs.hi, 1e-9 * (1.0 + pairs.hi)) << "trial " << trial;
    // the forward pass's controls at the top of the interval are feasible, to the rounding of
    // the bounds (1e-16 of |γ/α| ≤ 1e7 for the joint nearly at rest)
    const topp::XInterval u = topp::feasible_controls(rows, delta, next, newton.hi);
    const double rounding = trial % 5 == 1 ? 1e-8 : 1e-9;
    EXPECT_GE(u.hi, u.lo - rounding * (1.0 + std::abs(u.lo))) << "trial " << trial;
  }
  EXPECT_GT(nonempty, 1000);
}

}  // namespace
}  // namespace mjarm
