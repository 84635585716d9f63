#include "trajectory/path/reachability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mjarm::topp {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// a row whose u coefficient is this small is a bound on x alone: |α·u| is then far below the
// limits' rounding for any u the other rows allow
constexpr double kNoControl = 1e-14;

// x within [lo, hi] and the pair bound  (R − r)·x ≥ p − P  (an upper bound P + R·x on u against
// a lower bound p + r·x)
void intersect_pair(double P, double R, double p, double r, XInterval& x) noexcept {
  const double c = R - r, d = p - P;
  if (c > 0.0)
    x.lo = std::max(x.lo, d / c);
  else if (c < 0.0)
    x.hi = std::min(x.hi, d / c);
  else if (d > 0.0)
    x.lo = kInfinity;  // parallel bounds that cross: empty
}

}  // namespace

XInterval controllable_interval(const StepRows& rows, double delta, XInterval next, double x_lo,
                                double x_hi) noexcept {
  XInterval x{x_lo, x_hi};
  if (next.empty()) return {kInfinity, -kInfinity};
  // the landing rows: next.lo ≤ x + 2Δu ≤ next.hi  ⇔  u ∈ [(next.lo − x)/2Δ, (next.hi − x)/2Δ]
  const double inv = 1.0 / (2.0 * delta);
  const double land_lo_p = next.lo * inv, land_hi_p = next.hi * inv, land_r = -inv;
  intersect_pair(land_hi_p, land_r, land_lo_p, land_r, x);
  // every bound on u is  p + r·x  (p = γ/α, r = −β/α): a lower one for α < 0, an upper one
  // for α > 0; pair each with the landing bounds of the other side and with every bound of the
  // other side
  const int m = rows.count;
  for (int k = 0; k < m; ++k) {
    const double a = rows.alpha[k], b = rows.beta[k], c = rows.gamma[k];
    if (std::abs(a) <= kNoControl) {
      if (b > 0.0)
        x.hi = std::min(x.hi, c / b);
      else if (b < 0.0)
        x.lo = std::max(x.lo, c / b);
      else if (c < 0.0)
        x.lo = kInfinity;
      continue;
    }
    const double p = c / a, r = -b / a;
    if (a > 0.0) {
      intersect_pair(p, r, land_lo_p, land_r, x);
      for (int j = 0; j < m; ++j)
        if (rows.alpha[j] < -kNoControl)
          intersect_pair(p, r, rows.gamma[j] / rows.alpha[j], -rows.beta[j] / rows.alpha[j], x);
    } else {
      intersect_pair(land_hi_p, land_r, p, r, x);
    }
  }
  return x;
}

XInterval feasible_controls(const StepRows& rows, double delta, XInterval next, double x) noexcept {
  const double inv = 1.0 / (2.0 * delta);
  XInterval u{(next.lo - x) * inv, (next.hi - x) * inv};
  for (int k = 0; k < rows.count; ++k) {
    const double a = rows.alpha[k];
    if (std::abs(a) <= kNoControl) continue;
    const double bound = (rows.gamma[k] - rows.beta[k] * x) / a;
    if (a > 0.0)
      u.hi = std::min(u.hi, bound);
    else
      u.lo = std::max(u.lo, bound);
  }
  return u;
}

}  // namespace mjarm::topp
