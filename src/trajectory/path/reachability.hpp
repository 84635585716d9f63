#pragma once
// The two one-step operations of TOPP-RA (Pham & Pham 2018) on one grid step [s_i, s_{i+1}] of
// length Δ, in x = ṡ² at s_i and u = s̈ on the step (x_{i+1} = x + 2Δu): every constraint is a
// row  α·u + β·x ≤ γ.  The controllable set of s_i is the projection onto x of the polygon of
// (x, u) that satisfy the rows and land in the next set; here it is computed in closed form by
// eliminating u (Fourier–Motzkin: every lower bound on u against every upper bound gives a
// half-line in x), instead of the paper's 2-variable LPs, with the same result.

#include <Eigen/Core>

namespace mjarm::topp {

/// Rows α·u + β·x ≤ γ of one step, in preallocated arrays (capacity rows); count in use.
struct StepRows {
  Eigen::VectorXd alpha, beta, gamma;
  int count = 0;
  Eigen::VectorXd offset, slope;  // scratch: each row's bound on u as offset + slope·x

  explicit StepRows(int capacity)
      : alpha(capacity), beta(capacity), gamma(capacity), offset(capacity), slope(capacity) {}
  /// Appends the two sides of lo ≤ α·u + β·x ≤ hi.
  void add_two_sided(double a, double b, double lo, double hi) noexcept {
    add(a, b, hi);
    add(-a, -b, -lo);
  }
  void add(double a, double b, double c) noexcept {
    alpha[count] = a;
    beta[count] = b;
    gamma[count] = c;
    ++count;
  }
};

/// An interval [lo, hi] of x; empty when lo > hi.
struct XInterval {
  double lo = 0.0;
  double hi = 0.0;
  bool empty() const noexcept { return !(lo <= hi); }
};

/// The x ∈ [x_lo, x_hi] from which some u satisfies @p rows and x + 2Δu lies in @p next
/// (the paper's one-step set Q(K_{i+1})). Allocates nothing.
XInterval controllable_interval(StepRows& rows, double delta, XInterval next, double x_lo,
                                double x_hi) noexcept;

/// The feasible u at a given @p x (the interval may be empty by rounding; the caller decides).
/// Allocates nothing.
XInterval feasible_controls(const StepRows& rows, double delta, XInterval next, double x) noexcept;

}  // namespace mjarm::topp
