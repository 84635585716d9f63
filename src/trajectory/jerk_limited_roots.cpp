#include "mjarm/trajectory/jerk_limited_roots.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

double Polynomial::operator()(double x) const noexcept {
  double y = c[degree];
  for (int i = degree - 1; i >= 0; --i) y = y * x + c[i];
  return y;
}

Polynomial Polynomial::derivative() const noexcept {
  Polynomial d;
  d.degree = degree > 0 ? degree - 1 : 0;
  for (int i = 1; i <= degree; ++i) d.c[i - 1] = i * c[i];
  return d;
}

namespace {

/// |p| summed term by term at x: the scale of p's round-off there.
double term_magnitude(const Polynomial& p, double x) noexcept {
  double y = std::abs(p.c[p.degree]);
  const double ax = std::abs(x);
  for (int i = p.degree - 1; i >= 0; --i) y = y * ax + std::abs(p.c[i]);
  return y;
}

/// The root of the monotone p in [a, b] where p(a), p(b) differ in sign.
double bracketed_root(const Polynomial& p, const Polynomial& dp, double a, double b,
                      double fa) noexcept {
  double x = 0.5 * (a + b);
  for (int it = 0; it < 100; ++it) {
    const double fx = p(x);
    if (fx == 0.0) return x;
    if ((fx < 0.0) == (fa < 0.0)) {
      a = x;
      fa = fx;
    } else {
      b = x;
    }
    const double d = dp(x);
    double next = d != 0.0 ? x - fx / d : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);  // also NaN
    if (std::abs(next - x) <= 1e-16 * std::max(1.0, std::abs(x)) || b - a <= 0.0) return next;
    x = next;
  }
  return x;
}

int roots_of_trimmed(const Polynomial& p, double lo, double hi,
                     std::array<double, kMaxRoots>& roots) noexcept {
  int n = 0;
  if (p.degree == 0) return 0;
  if (p.degree == 1) {
    const double x = -p.c[0] / p.c[1];
    if (x >= lo && x <= hi) roots[n++] = x;
    return n;
  }
  if (p.degree == 2) {
    const double a = p.c[2], b = p.c[1], c = p.c[0];
    const double disc = b * b - 4.0 * a * c;
    const double scale = b * b + std::abs(4.0 * a * c);
    double xs[2];
    int k = 0;
    if (disc < -1e-14 * scale) return 0;
    if (disc <= 1e-14 * scale) {
      xs[k++] = -b / (2.0 * a);
    } else {
      // the stable pair: no cancellation between b and √disc
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      xs[k++] = q / a;
      if (q != 0.0) xs[k++] = c / q;
      if (k == 2 && xs[0] > xs[1]) std::swap(xs[0], xs[1]);
    }
    for (int i = 0; i < k; ++i)
      if (xs[i] >= lo && xs[i] <= hi) roots[n++] = xs[i];
    return n;
  }
  // monotone pieces between the critical points
  const Polynomial dp = p.derivative();
  std::array<double, kMaxRoots> crit{};
  const int nc = real_roots(dp, lo, hi, crit);
  double a = lo;
  double fa = p(a);
  auto tiny = [&p](double x, double fx) { return std::abs(fx) <= 1e-13 * term_magnitude(p, x); };
  if (tiny(a, fa)) roots[n++] = a;
  for (int i = 0; i <= nc; ++i) {
    const double b = i < nc ? crit[i] : hi;
    const double fb = p(b);
    const bool a_root = n > 0 && roots[n - 1] == a;
    if (!a_root && !tiny(b, fb) && ((fa < 0.0) != (fb < 0.0)) && !tiny(a, fa)) {
      if (n < kMaxRoots) roots[n++] = bracketed_root(p, dp, a, b, fa);
    }
    if (tiny(b, fb) && (n == 0 || roots[n - 1] != b) && n < kMaxRoots) roots[n++] = b;
    a = b;
    fa = fb;
  }
  return n;
}

}  // namespace

int real_roots(const Polynomial& p_in, double lo, double hi,
               std::array<double, kMaxRoots>& roots) noexcept {
  Polynomial p = p_in;
  double biggest = 0.0;
  for (int i = 0; i <= p.degree; ++i) {
    if (!std::isfinite(p.c[i])) return 0;
    biggest = std::max(biggest, std::abs(p.c[i]));
  }
  if (biggest == 0.0) return 0;
  while (p.degree > 0 && std::abs(p.c[p.degree]) <= 1e-14 * biggest) --p.degree;
  if (p.degree == 0) return 0;
  // Cauchy's bound: every root has |x| ≤ 1 + max |cᵢ/c_n|
  double bound = 0.0;
  for (int i = 0; i < p.degree; ++i) bound = std::max(bound, std::abs(p.c[i] / p.c[p.degree]));
  bound += 1.0;
  lo = std::max(lo, -bound);
  hi = std::min(hi, bound);
  if (!(lo <= hi)) return 0;
  return roots_of_trimmed(p, lo, hi, roots);
}

}  // namespace mjarm
