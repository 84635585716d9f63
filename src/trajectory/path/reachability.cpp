#include "trajectory/path/reachability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mjarm::topp {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// a row whose u coefficient is this small is a bound on x alone (the rows are in units of the
// limit: α = q′_j/a_j, a joint all but at rest): |α·u| is below 1e-9 of the limit for any |u| ≤ 1
// (and 1e-8 for |u| ≤ 10), while keeping it would put bounds of |γ/α| ≥ 1e9 on u, whose rounding
// (1e-7) the forward pass would then see
constexpr double kNoControl = 1e-9;

// The gap F(x) = min U(x) − max L(x) between the u bounds at x, and the slope of its active
// pieces there (a supergradient: F is concave).
struct Gap {
  double value = 0.0;
  double slope = 0.0;
  // the size of the active lines' terms (|offset| + |slope·x| of each): a row with a small u
  // coefficient has large ones, and its value at x is rounded relative to them
  double scale = 0.0;
};

Gap gap_at(const StepRows& rows, double land_lo, double land_hi, double land_slope,
           double x) noexcept {
  double upper = land_hi + land_slope * x, upper_slope = land_slope;
  double lower = land_lo + land_slope * x, lower_slope = land_slope;
  double upper_size = std::abs(land_hi) + std::abs(land_slope * x);
  double lower_size = std::abs(land_lo) + std::abs(land_slope * x);
  for (int k = 0; k < rows.count; ++k) {
    const double a = rows.alpha[k];
    if (std::abs(a) <= kNoControl) continue;
    const double bound = rows.offset[k] + rows.slope[k] * x;
    const double size = std::abs(rows.offset[k]) + std::abs(rows.slope[k] * x);
    if (a > 0.0) {
      if (bound < upper) upper = bound, upper_slope = rows.slope[k], upper_size = size;
    } else if (bound > lower) {
      lower = bound, lower_slope = rows.slope[k], lower_size = size;
    }
  }
  return {upper - lower, upper_slope - lower_slope, upper_size + lower_size};
}

bool gap_open(const Gap& g) noexcept { return g.value >= -1e-13 * (1.0 + g.scale); }

}  // namespace

XInterval controllable_interval(StepRows& rows, double delta, XInterval next, double x_lo,
                                double x_hi) noexcept {
  const XInterval empty{kInfinity, -kInfinity};
  if (next.empty()) return empty;
  XInterval x{x_lo, x_hi};
  const int m = rows.count;
  for (int k = 0; k < m; ++k) {
    const double a = rows.alpha[k], b = rows.beta[k], c = rows.gamma[k];
    if (std::abs(a) <= kNoControl) {  // a bound on x alone
      if (b > 0.0)
        x.hi = std::min(x.hi, c / b);
      else if (b < 0.0)
        x.lo = std::max(x.lo, c / b);
      else if (c < 0.0)
        return empty;
      continue;
    }
    rows.offset[k] = c / a;
    rows.slope[k] = -b / a;
  }
  // no joint moving at s_i leaves x unbounded by velocity: a cap keeps Newton's steps finite
  x.hi = std::min(x.hi, 1e12);
  if (x.empty()) return empty;
  // the landing rows: next.lo ≤ x + 2Δu ≤ next.hi  ⇔  u ∈ [(next.lo − x)/2Δ, (next.hi − x)/2Δ]
  const double inv = 1.0 / (2.0 * delta);
  const double land_lo = next.lo * inv, land_hi = next.hi * inv, land_slope = -inv;
  const int most_steps = 4 * m + 16;
  // the largest root: Newton from x.hi (each step lands on or right of the root, since the
  // active pieces' line lies above the concave gap)
  XInterval result = empty;
  for (int step = 0; step < most_steps; ++step) {
    const Gap g = gap_at(rows, land_lo, land_hi, land_slope, x.hi);
    if (gap_open(g)) {
      result.hi = x.hi;
      break;
    }
    if (!(g.slope < 0.0)) return empty;  // no root to the left
    x.hi -= g.value / g.slope;
    if (x.hi < x.lo) return empty;
  }
  if (result.hi == -kInfinity) return empty;
  // the smallest root: the same from x.lo
  for (int step = 0; step < most_steps; ++step) {
    const Gap g = gap_at(rows, land_lo, land_hi, land_slope, x.lo);
    if (gap_open(g)) {
      result.lo = x.lo;
      return result;
    }
    if (!(g.slope > 0.0)) return empty;  // no root to the right
    x.lo -= g.value / g.slope;
    if (x.lo > result.hi) return empty;
  }
  return empty;
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
