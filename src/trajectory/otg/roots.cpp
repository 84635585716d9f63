#include "mjarm/trajectory/otg/roots.hpp"

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

/// Value of the degree-N polynomial @p c at @p x.
template <int N>
double value(const double* c, double x) noexcept {
  double y = c[N];
  for (int i = N - 1; i >= 0; --i) y = y * x + c[i];
  return y;
}

/// Sum of the magnitudes of the terms at @p x: the scale of the round-off of value() there.
template <int N>
double magnitude(const double* c, double x) noexcept {
  const double ax = std::abs(x);
  double y = std::abs(c[N]);
  for (int i = N - 1; i >= 0; --i) y = y * ax + std::abs(c[i]);
  return y;
}

/// True when @p fx, the value at @p x, is zero to round-off.
template <int N>
bool at_round_off(const double* c, double x, double fx) noexcept {
  return std::abs(fx) <= 4e-15 * magnitude<N>(c, x);
}

/// The root of the degree-N polynomial @p c, monotone on [a, b], whose ends have the values
/// @p fa and @p fb of opposite signs: Newton steps from the secant estimate, each kept inside the
/// shrinking bracket (a bisection step otherwise).
template <int N>
double bracketed_root(const double* c, double a, double b, double fa, double fb) noexcept {
  double x = a - fa * (b - a) / (fb - fa);
  if (!(x > a && x < b)) x = 0.5 * (a + b);
  for (int it = 0; it < 64; ++it) {
    double f = c[N], d = 0.0;
    for (int i = N - 1; i >= 0; --i) {
      d = d * x + f;
      f = f * x + c[i];
    }
    if (f == 0.0) return x;
    if ((f < 0.0) == (fa < 0.0)) {
      a = x;
      fa = f;
    } else {
      b = x;
    }
    double next = d != 0.0 ? x - f / d : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);  // also NaN
    const double step = std::abs(next - x);
    x = next;
    if (step <= 2e-16 * std::abs(x) || !(b - a > 2e-16 * std::max(std::abs(a), std::abs(b))))
      return x;
  }
  return x;
}

/// Roots of the degree-N polynomial @p c (c[N] ≠ 0) in [lo, hi], ascending.
template <int N>
int roots_in(const double* c, double lo, double hi, double* roots) noexcept {
  if constexpr (N == 1) {
    const double x = -c[0] / c[1];
    if (x >= lo && x <= hi) {
      roots[0] = x;
      return 1;
    }
    return 0;
  } else if constexpr (N == 2) {
    const double a = c[2], b = c[1], k = c[0];
    const double disc = b * b - 4.0 * a * k;
    const double scale = b * b + std::abs(4.0 * a * k);
    double xs[2];
    int m = 0;
    if (disc < -1e-15 * scale) return 0;
    if (disc <= 1e-15 * scale) {
      xs[m++] = -b / (2.0 * a);
    } else {
      // the stable pair: no cancellation between b and √disc
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      xs[m++] = q / a;
      if (q != 0.0) xs[m++] = k / q;
      if (m == 2 && xs[0] > xs[1]) std::swap(xs[0], xs[1]);
    }
    int n = 0;
    for (int i = 0; i < m; ++i)
      if (xs[i] >= lo && xs[i] <= hi) roots[n++] = xs[i];
    return n;
  } else {
    double d[N];
    for (int i = 1; i <= N; ++i) d[i - 1] = i * c[i];
    double crit[N - 1];
    const int nc = roots_in<N - 1>(d, lo, hi, crit);
    int n = 0;
    double a = lo;
    double fa = value<N>(c, a);
    bool a_root = at_round_off<N>(c, a, fa);
    if (a_root) roots[n++] = a;
    for (int i = 0; i <= nc; ++i) {
      const double b = i < nc ? crit[i] : hi;
      if (b <= a && i < nc) continue;
      const double fb = value<N>(c, b);
      const bool b_root = at_round_off<N>(c, b, fb);
      if (!a_root && !b_root && (fa < 0.0) != (fb < 0.0) && n < N)
        roots[n++] = bracketed_root<N>(c, a, b, fa, fb);
      if (b_root && (n == 0 || roots[n - 1] != b) && n < N) roots[n++] = b;
      a = b;
      fa = fb;
      a_root = b_root;
    }
    return n;
  }
}

/// Budan–Fourier: sign variations of (p, p′, …, p⁽ᴺ⁾) at @p x, zeros skipped; −1 when one of
/// them is zero to round-off (its sign is then not to be trusted). V(a) − V(b) bounds the number
/// of roots in (a, b] from above and has their parity.
template <int N>
int sign_variations(const double* c, double x) noexcept {
  // Taylor coefficients at x by repeated synthetic division (proportional to the derivatives)
  double t[N + 1];
  for (int i = 0; i <= N; ++i) t[i] = c[i];
  for (int k = 0; k < N; ++k)
    for (int i = N - 1; i >= k; --i) t[i] += x * t[i + 1];
  // a coefficient far above a bound of its round-off is trusted without computing that exactly
  const double ax = std::abs(x);
  double bound = 0.0, power = 1.0;
  for (int i = 0; i <= N; ++i, power *= std::max(ax, 1.0))
    bound = std::max(bound, std::abs(c[i]) * power);
  bound *= 16.0;  // ≥ the binomial weights of the shift for N ≤ 4
  bool sure = true;
  for (int i = 1; i < N; ++i) sure = sure && std::abs(t[i]) > 1e-9 * bound;
  if (!sure) {
    double m[N + 1];
    for (int i = 0; i <= N; ++i) m[i] = std::abs(c[i]);
    for (int k = 0; k < N; ++k)
      for (int i = N - 1; i >= k; --i) m[i] += ax * m[i + 1];
    for (int i = 1; i < N; ++i)
      if (std::abs(t[i]) <= 1e-12 * m[i]) return -1;
  }
  int changes = 0;
  bool negative = t[0] < 0.0;
  for (int i = 1; i <= N; ++i) {
    if ((t[i] < 0.0) != negative) ++changes;
    negative = t[i] < 0.0;
  }
  return changes;
}

/// The roots in [lo, hi] (values @p flo, @p fhi and Budan–Fourier counts @p v_lo, @p v_hi at the
/// ends, none of them at round-off): none when the counts allow none, the bracketed one when they
/// allow exactly one, else the halves again (@p depth times), else roots_in().
template <int N>
int screened(const double* c, double lo, double hi, double flo, double fhi, int v_lo, int v_hi,
             int depth, double* roots) noexcept {
  const int bound = v_lo - v_hi;
  if (bound <= 0) return 0;
  if (bound == 1 && (flo < 0.0) != (fhi < 0.0)) {
    roots[0] = bracketed_root<N>(c, lo, hi, flo, fhi);
    return 1;
  }
  const double mid = 0.5 * (lo + hi);
  const double fmid = value<N>(c, mid);
  const int v_mid = depth > 0 && !at_round_off<N>(c, mid, fmid) ? sign_variations<N>(c, mid) : -1;
  if (v_mid < 0) return roots_in<N>(c, lo, hi, roots);
  const int n = screened<N>(c, lo, mid, flo, fmid, v_lo, v_mid, depth - 1, roots);
  return n + screened<N>(c, mid, hi, fmid, fhi, v_mid, v_hi, depth - 1, roots + n);
}

/// roots_in() with cheap first looks. The Taylor expansion at the midpoint m bounds the
/// polynomial on [m − r, m + r]: |p(x) − p(m)| ≤ Σₖ₌₁ |tₖ|·rᵏ (tₖ = p⁽ᵏ⁾(m)/k!), so p has no root
/// there when |t₀| exceeds that; likewise p′ keeps its sign when |t₁| > Σₖ₌₂ k·|tₖ|·rᵏ⁻¹, and then
/// the ends tell whether the one possible root is there. Otherwise Budan–Fourier (screened()).
template <int N>
int roots_screened(const double* c, double lo, double hi, double* roots) noexcept {
  const double mid = 0.5 * (lo + hi), r = 0.5 * (hi - lo);
  double t[N + 1];
  for (int i = 0; i <= N; ++i) t[i] = c[i];
  for (int k = 0; k < N; ++k)
    for (int i = N - 1; i >= k; --i) t[i] += mid * t[i + 1];
  double b0 = 0.0, b1 = 0.0, power = 1.0;  // power = rᵏ⁻¹
  for (int k = 1; k <= N; ++k, power *= r) {
    const double term = std::abs(t[k]) * power;
    b0 += term * r;
    if (k >= 2) b1 += k * term;
  }
  const double round_off = 1e-13 * magnitude<N>(c, std::max(std::abs(lo), std::abs(hi)));
  if (std::abs(t[0]) > b0 + round_off) return 0;
  const double flo = value<N>(c, lo), fhi = value<N>(c, hi);
  const bool lo_root = at_round_off<N>(c, lo, flo), hi_root = at_round_off<N>(c, hi, fhi);
  if (!lo_root && !hi_root && std::abs(t[1]) > 1.000001 * b1) {
    if ((flo < 0.0) == (fhi < 0.0)) return 0;
    roots[0] = bracketed_root<N>(c, lo, hi, flo, fhi);
    return 1;
  }
  if (lo_root || hi_root) return roots_in<N>(c, lo, hi, roots);
  const int v_lo = sign_variations<N>(c, lo), v_hi = sign_variations<N>(c, hi);
  if (v_lo < 0 || v_hi < 0) return roots_in<N>(c, lo, hi, roots);
  return screened<N>(c, lo, hi, flo, fhi, v_lo, v_hi, 2, roots);
}

}  // namespace

int real_roots(const Polynomial& p, double lo, double hi,
               std::array<double, kMaxRoots>& roots) noexcept {
  int degree = std::clamp(p.degree, 0, Polynomial::kMaxDegree);
  for (int i = 0; i <= degree; ++i)
    if (!std::isfinite(p.c[i])) return 0;
  if (!(lo <= hi)) return 0;
  // infinite bounds: Cauchy's bound on the trimmed polynomial
  while (degree > 0 && p.c[degree] == 0.0) --degree;
  if (degree == 0) return 0;
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    double bound = 0.0;
    for (int i = 0; i < degree; ++i) bound = std::max(bound, std::abs(p.c[i] / p.c[degree]));
    bound += 1.0;
    lo = std::max(lo, -bound);
    hi = std::min(hi, bound);
    if (!(lo <= hi)) return 0;
  }
  // drop leading terms that are negligible everywhere in the interval
  const double x = std::max(std::abs(lo), std::abs(hi));
  double largest = 0.0, power = 1.0;
  double term[Polynomial::kMaxDegree + 1];
  for (int i = 0; i <= degree; ++i) {
    term[i] = std::abs(p.c[i]) * power;
    largest = std::max(largest, term[i]);
    power *= x;
  }
  while (degree > 0 && term[degree] <= 1e-15 * largest) --degree;
  double* out = roots.data();
  switch (degree) {
    case 1:
      return roots_in<1>(p.c.data(), lo, hi, out);
    case 2:
      return roots_in<2>(p.c.data(), lo, hi, out);
    case 3:
      return roots_screened<3>(p.c.data(), lo, hi, out);
    case 4:
      return roots_screened<4>(p.c.data(), lo, hi, out);
    default:
      return 0;
  }
}

}  // namespace mjarm
