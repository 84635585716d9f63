#include "mjarm/trajectory/otg/roots.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mjarm/random.hpp"

namespace mjarm {
namespace {

/// The monic polynomial with the given roots.
Polynomial poly_from_roots(std::initializer_list<double> roots) {
  Polynomial p;
  p.c[0] = 1.0;
  p.degree = 0;
  for (const double r : roots) {
    Polynomial q;
    q.degree = p.degree + 1;
    for (int i = 0; i <= p.degree; ++i) {
      q.c[i + 1] += p.c[i];
      q.c[i] -= r * p.c[i];
    }
    p = q;
  }
  return p;
}

TEST(JerkLimitedRoots, FindsEveryRootOfAProductInOrder) {
  const Polynomial p = poly_from_roots({-2.5, -0.3, 0.7, 4.0});
  std::array<double, kMaxRoots> roots{};
  const int n = real_roots(p, -10.0, 10.0, roots);
  ASSERT_EQ(n, 4);
  const double expected[] = {-2.5, -0.3, 0.7, 4.0};
  for (int i = 0; i < n; ++i) EXPECT_NEAR(roots[i], expected[i], 1e-12) << i;
}

TEST(JerkLimitedRoots, KeepsOnlyTheInterval) {
  const Polynomial p = poly_from_roots({-1.0, 0.5, 2.0, 3.0});
  std::array<double, kMaxRoots> roots{};
  const int n = real_roots(p, 0.0, 2.5, roots);
  ASSERT_EQ(n, 2);
  EXPECT_NEAR(roots[0], 0.5, 1e-13);
  EXPECT_NEAR(roots[1], 2.0, 1e-13);
}

TEST(JerkLimitedRoots, FindsADoubleRootWhereTheSignDoesNotChange) {
  const Polynomial p = poly_from_roots({0.25, 0.25, -1.0});
  std::array<double, kMaxRoots> roots{};
  const int n = real_roots(p, -5.0, 5.0, roots);
  ASSERT_GE(n, 2);
  EXPECT_NEAR(roots[0], -1.0, 1e-12);
  EXPECT_NEAR(roots[1], 0.25, 1e-7);
}

TEST(JerkLimitedRoots, NoRealRootsAndDegenerateInput) {
  Polynomial p;  // x² + 1
  p.c = {1.0, 0.0, 1.0};
  p.degree = 2;
  std::array<double, kMaxRoots> roots{};
  EXPECT_EQ(real_roots(p, -1e9, 1e9, roots), 0);
  EXPECT_EQ(real_roots(Polynomial{}, -1.0, 1.0, roots), 0);  // zero polynomial
  p.c[0] = std::nan("");
  EXPECT_EQ(real_roots(p, -1.0, 1.0, roots), 0);
  // an infinite interval is clipped to the root bound
  const Polynomial q = poly_from_roots({-300.0, 7.0, 1e3});
  ASSERT_EQ(real_roots(q, -HUGE_VAL, HUGE_VAL, roots), 3);
  EXPECT_NEAR(roots[2], 1e3, 1e-9);
}

TEST(JerkLimitedRoots, RandomQuarticsMatchTheirConstruction) {
  mjarm::Random rng(11);
  const auto u = [](mjarm::Random& r) { return mjarm::uniform(r, -3.0, 3.0); };
  int checked = 0;
  for (int k = 0; k < 2000; ++k) {
    std::array<double, 4> r{};
    for (double& x : r) x = u(rng);
    std::sort(r.begin(), r.end());
    bool separated = true;
    for (int i = 1; i < 4; ++i) separated = separated && r[i] - r[i - 1] > 1e-3;
    if (!separated) continue;
    const Polynomial p = poly_from_roots({r[0], r[1], r[2], r[3]});
    std::array<double, kMaxRoots> roots{};
    ASSERT_EQ(real_roots(p, -4.0, 4.0, roots), 4) << k;
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(roots[i], r[i], 1e-9) << k;
    // a sub-interval holds exactly the roots inside it (the screening by the Taylor bound and by
    // Budan–Fourier decides most sub-intervals without the full isolation)
    const double lo = u(rng), hi = lo + 0.5 * (u(rng) + 3.0);
    int inside = 0;
    for (const double x : r) inside += x >= lo && x <= hi ? 1 : 0;
    const int n = real_roots(p, lo, hi, roots);
    EXPECT_EQ(n, inside) << k;
    for (int i = 0; i < n; ++i) EXPECT_TRUE(roots[i] >= lo && roots[i] <= hi);
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

// Random coefficients, not roots: every sign change a dense scan sees is a root found, and each
// root found is a zero to round-off.
TEST(JerkLimitedRoots, RandomCoefficientsAgreeWithADenseScan) {
  mjarm::Random rng(12);
  const auto u = [](mjarm::Random& r) { return mjarm::uniform(r, -1.0, 1.0); };
  for (int k = 0; k < 300; ++k) {
    Polynomial p;
    p.degree = 4;
    for (double& c : p.c) c = u(rng);
    if (k % 3 == 0) p.c[4] = 1e-12 * u(rng);  // a leading term negligible over the interval
    const double lo = -2.0, hi = 2.0;
    std::array<double, kMaxRoots> roots{};
    const int n = real_roots(p, lo, hi, roots);
    int changes = 0;
    double prev = p(lo);
    for (int i = 1; i <= 20000; ++i) {
      const double x = lo + (hi - lo) * i / 20000.0, y = p(x);
      if ((y < 0.0) != (prev < 0.0)) ++changes;
      prev = y;
    }
    EXPECT_GE(n, changes) << k;
    for (int i = 0; i < n; ++i) {
      EXPECT_LE(std::abs(p(roots[i])), 1e-12) << k;
      if (i > 0) {
        EXPECT_LE(roots[i - 1], roots[i]);
      }
    }
  }
}

}  // namespace
}  // namespace mjarm
