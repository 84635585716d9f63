#include "mjarm/lie/coefficients.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm::lie {
namespace {

// Taylor coefficients in powers of θ² (k-th entry multiplies θ^(2k)); a series of f gives the
// series of f'(θ)/θ as Σ 2k f_k θ^(2k−2), listed separately for clarity.
constexpr int kTerms = 10;
using Series = std::array<double, kTerms>;

constexpr Series kSinc = {1.0,
                          -1.0 / 6.0,
                          1.0 / 120.0,
                          -1.0 / 5040.0,
                          1.0 / 362880.0,
                          -1.0 / 39916800.0,
                          1.0 / 6227020800.0,
                          -1.0 / 1307674368000.0,
                          1.0 / 355687428096000.0,
                          -1.0 / 121645100408832000.0};
constexpr Series kA = {1.0 / 2.0,
                       -1.0 / 24.0,
                       1.0 / 720.0,
                       -1.0 / 40320.0,
                       1.0 / 3628800.0,
                       -1.0 / 479001600.0,
                       1.0 / 87178291200.0,
                       -1.0 / 20922789888000.0,
                       1.0 / 6402373705728000.0,
                       -1.0 / 2432902008176640000.0};
constexpr Series kB = {1.0 / 6.0,
                       -1.0 / 120.0,
                       1.0 / 5040.0,
                       -1.0 / 362880.0,
                       1.0 / 39916800.0,
                       -1.0 / 6227020800.0,
                       1.0 / 1307674368000.0,
                       -1.0 / 355687428096000.0,
                       1.0 / 121645100408832000.0,
                       -1.0 / 51090942171709440000.0};
constexpr Series kC = {1.0 / 24.0,
                       -1.0 / 720.0,
                       1.0 / 40320.0,
                       -1.0 / 3628800.0,
                       1.0 / 479001600.0,
                       -1.0 / 87178291200.0,
                       1.0 / 20922789888000.0,
                       -1.0 / 6402373705728000.0,
                       1.0 / 2432902008176640000.0,
                       -1.0 / 1124000727777607680000.0};
constexpr Series kD = {1.0 / 120.0,
                       -1.0 / 2520.0,
                       1.0 / 120960.0,
                       -1.0 / 9979200.0,
                       1.0 / 1245404160.0,
                       -1.0 / 217945728000.0,
                       1.0 / 50812489728000.0,
                       -1.0 / 15205637551104000.0,
                       1.0 / 5676771352412160000.0,
                       -1.0 / 2585201673888497664000.0};
constexpr Series kE = {1.0 / 12.0,
                       1.0 / 720.0,
                       1.0 / 30240.0,
                       1.0 / 1209600.0,
                       1.0 / 47900160.0,
                       691.0 / 1307674368000.0,
                       1.0 / 74724249600.0,
                       3617.0 / 10670622842880000.0,
                       43867.0 / 5109094217170944000.0,
                       174611.0 / 802857662698291200000.0};

// f'(θ)/θ series: entry k multiplies θ^(2k)
constexpr Series rate_series(const Series& f) {
  Series r{};
  for (int k = 0; k + 1 < kTerms; ++k) r[k] = 2.0 * (k + 1) * f[k + 1];
  r[kTerms - 1] = 0.0;
  return r;
}
constexpr Series kARate = rate_series(kA);
constexpr Series kBRate = rate_series(kB);
constexpr Series kCRate = rate_series(kC);
constexpr Series kDRate = rate_series(kD);
constexpr Series kERate = rate_series(kE);

// Horner evaluation in t2 = θ²
double horner(const Series& s, double t2) noexcept {
  double r = s[kTerms - 1];
  for (int k = kTerms - 2; k >= 0; --k) r = r * t2 + s[k];
  return r;
}

}  // namespace

SeriesCoefficients series_coefficients(double theta) noexcept {
  SeriesCoefficients k;
  const double t2 = theta * theta;
  if (theta < kSeriesThreshold) {
    k.sinc = horner(kSinc, t2);
    k.a = horner(kA, t2);
    k.b = horner(kB, t2);
    k.c = horner(kC, t2);
    k.d = horner(kD, t2);
    k.a_rate = horner(kARate, t2);
    k.b_rate = horner(kBRate, t2);
    k.c_rate = horner(kCRate, t2);
    k.d_rate = horner(kDRate, t2);
    return k;
  }
  // closed forms, each written through the previous ones so that every step is one division
  const double s = std::sin(theta);
  const double half_sin = std::sin(0.5 * theta);
  k.sinc = s / theta;
  k.a = 2.0 * half_sin * half_sin / t2;  // (1 − cos θ) = 2 sin²(θ/2) avoids cancellation
  k.b = (theta - s) / (theta * t2);
  k.c = (0.5 - k.a) / t2;
  k.d = (3.0 * k.b - k.a) / (2.0 * t2);
  // rates: f'(θ)/θ, from differentiating the expressions above
  k.a_rate = (k.sinc - 2.0 * k.a) / t2;
  k.b_rate = (k.a - 3.0 * k.b) / t2;
  k.c_rate = (-k.a_rate - 2.0 * k.c) / t2;
  k.d_rate = (0.5 * (3.0 * k.b_rate - k.a_rate) - 2.0 * k.d) / t2;
  return k;
}

InverseCoefficients inverse_coefficients(double theta) noexcept {
  InverseCoefficients k;
  const double t2 = theta * theta;
  if (theta < kSeriesThreshold) {
    k.e = horner(kE, t2);
    k.e_rate = horner(kERate, t2);
    return k;
  }
  // e = (1 − h cot h)/θ² with h = θ/2; d(h cot h)/dθ = (cot h − h/sin² h)/2
  const double h = 0.5 * theta;
  const double sh = std::sin(h);
  const double cot_h = std::cos(h) / sh;
  k.e = (1.0 - h * cot_h) / t2;
  const double k_rate = (cot_h - h / (sh * sh)) / (2.0 * theta);
  k.e_rate = (-k_rate - 2.0 * k.e) / t2;
  return k;
}

void require_inverse_domain(double theta, const char* function) {
  if (theta < kTwoPi) return;
  char buffer[96];
  std::snprintf(buffer, sizeof(buffer), "%.17g", theta);
  throw Error(std::string(function) + ": rotation angle |w| = " + buffer +
              " rad is outside the domain |w| < 2*pi (6.283185307179586 rad) of the inverse "
              "Jacobian dexp^-1, which is singular at |w| = 2*pi; wrap the rotation vector to "
              "|w| <= pi (e.g. via so3::log(so3::exp(w))) first");
}

}  // namespace mjarm::lie
