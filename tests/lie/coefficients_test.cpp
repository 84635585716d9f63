#include "mjarm/lie/coefficients.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"

namespace mjarm::lie {
namespace {

// closed forms in long double (64-bit mantissa) as an independent reference where their
// cancellation is mild (θ ≥ 0.3)
struct Reference {
  long double sinc, a, b, c, d, e;
};
Reference closed_form(long double t) {
  const long double s = std::sin(t), co = std::cos(t);
  Reference r;
  r.sinc = s / t;
  r.a = (1.0L - co) / (t * t);
  r.b = (t - s) / (t * t * t);
  r.c = (t * t + 2.0L * co - 2.0L) / (2.0L * t * t * t * t);
  r.d = (2.0L * t - 3.0L * s + t * co) / (2.0L * t * t * t * t * t);
  r.e = 1.0L / (t * t) - std::cos(t / 2.0L) / std::sin(t / 2.0L) / (2.0L * t);
  return r;
}

void expect_rel(double value, long double reference, double tol, const char* what, double t) {
  EXPECT_LE(std::fabs(static_cast<long double>(value) - reference),
            tol * std::fabs(reference) + 1e-300)
      << what << " at theta = " << t;
}

TEST(LieCoefficients, MatchClosedFormsAcrossTheSeriesThreshold) {
  // covers the series branch (θ < 1) and the closed-form branch (θ ≥ 1), up to near 2π
  for (double t = 0.3; t < 6.2; t += 0.05) {
    const SeriesCoefficients k = series_coefficients(t);
    const InverseCoefficients ki = inverse_coefficients(t);
    const Reference r = closed_form(t);
    expect_rel(k.sinc, r.sinc, 1e-14, "sinc", t);
    expect_rel(k.a, r.a, 1e-14, "a", t);
    expect_rel(k.b, r.b, 1e-13, "b", t);
    expect_rel(k.c, r.c, 1e-12, "c", t);
    expect_rel(k.d, r.d, 1e-11, "d", t);
    expect_rel(ki.e, r.e, 1e-12, "e", t);
  }
}

TEST(LieCoefficients, LimitsAtZero) {
  const SeriesCoefficients k = series_coefficients(0.0);
  EXPECT_DOUBLE_EQ(k.sinc, 1.0);
  EXPECT_DOUBLE_EQ(k.a, 0.5);
  EXPECT_DOUBLE_EQ(k.b, 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(k.c, 1.0 / 24.0);
  EXPECT_DOUBLE_EQ(k.d, 1.0 / 120.0);
  EXPECT_DOUBLE_EQ(k.a_rate, -1.0 / 12.0);
  EXPECT_DOUBLE_EQ(inverse_coefficients(0.0).e, 1.0 / 12.0);
}

TEST(LieCoefficients, ContinuousAtSeriesThreshold) {
  const double lo = std::nextafter(kSeriesThreshold, 0.0);
  const SeriesCoefficients a = series_coefficients(lo);
  const SeriesCoefficients b = series_coefficients(kSeriesThreshold);
  const double fa[] = {a.sinc, a.a, a.b, a.c, a.d, a.a_rate, a.b_rate, a.c_rate, a.d_rate};
  const double fb[] = {b.sinc, b.a, b.b, b.c, b.d, b.a_rate, b.b_rate, b.c_rate, b.d_rate};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(fa[i], fb[i], 1e-12 * std::fabs(fb[i])) << i;
  const InverseCoefficients ia = inverse_coefficients(lo);
  const InverseCoefficients ib = inverse_coefficients(kSeriesThreshold);
  EXPECT_NEAR(ia.e, ib.e, 1e-13 * ib.e);
  EXPECT_NEAR(ia.e_rate, ib.e_rate, 1e-12 * ib.e_rate);
}

TEST(LieCoefficients, RatesMatchFiniteDifferences) {
  // f'(θ)/θ against a central difference of f, on both branches
  for (double t : {0.05, 0.4, 0.9, 1.1, 2.0, 3.1, 4.5, 6.0}) {
    const double h = 1e-5;
    const SeriesCoefficients k = series_coefficients(t);
    // central differences of (a, b, c, d) at t
    const Eigen::Vector4d d = finite_difference_derivative(
        [](double s) {
          const SeriesCoefficients c = series_coefficients(s);
          return Eigen::Vector4d(c.a, c.b, c.c, c.d);
        },
        t, h);
    EXPECT_NEAR(k.a_rate, d[0] / t, 1e-8) << t;
    EXPECT_NEAR(k.b_rate, d[1] / t, 1e-8) << t;
    EXPECT_NEAR(k.c_rate, d[2] / t, 1e-8) << t;
    EXPECT_NEAR(k.d_rate, d[3] / t, 1e-8) << t;
    const InverseCoefficients ki = inverse_coefficients(t);
    const double fd =
        finite_difference_derivative([](double s) { return inverse_coefficients(s).e; }, t, h) / t;
    EXPECT_NEAR(ki.e_rate, fd, 1e-7 * std::max(1.0, std::fabs(fd))) << t;
  }
}

TEST(LieCoefficients, InverseDomain) {
  EXPECT_NO_THROW(require_inverse_domain(0.0, "f"));
  EXPECT_NO_THROW(require_inverse_domain(std::nextafter(kTwoPi, 0.0), "f"));
  EXPECT_THROW(require_inverse_domain(kTwoPi, "f"), Error);
  EXPECT_THROW(require_inverse_domain(7.0, "f"), Error);
  EXPECT_THROW(require_inverse_domain(std::nan(""), "f"), Error);
  try {
    require_inverse_domain(kTwoPi, "my_function");
    FAIL() << "expected mjarm::Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("my_function"), std::string::npos) << message;
    EXPECT_NE(message.find("2*pi"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace mjarm::lie
