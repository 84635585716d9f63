#pragma once
/// @file
/// `Polynomial` and `real_roots`: the real roots of a polynomial of degree ≤ 4 in an interval,
/// without allocation. The jerk-limited profile solvers reduce every profile structure to such a
/// polynomial in one unknown (otg/min_time.hpp).

#include <array>

namespace mjarm {

/// A real polynomial c₀ + c₁x + … + c₄x⁴ of fixed capacity (no allocation).
struct Polynomial {
  /// Highest degree a polynomial can hold.
  static constexpr int kMaxDegree = 4;
  /// Coefficients, lowest degree first; entries above `degree` are zero.
  std::array<double, kMaxDegree + 1> c{};
  /// Degree bound: c[i] = 0 for i > degree (the leading coefficient may still be 0).
  int degree = 0;

  /// The value at @p x (Horner).
  double operator()(double x) const noexcept;
  /// The first derivative.
  Polynomial derivative() const noexcept;
};

/// Most roots `real_roots` returns (the capacity of its output).
inline constexpr int kMaxRoots = Polynomial::kMaxDegree;

/// The real roots of @p p in [@p lo, @p hi], ascending, written to @p roots; returns their number.
///
/// The roots of p′ (found the same way; a quadratic in closed form) split the interval into
/// pieces on which p is monotone; each piece whose ends differ in sign holds one root, found by
/// Newton steps safeguarded by bisection to full double precision. A critical point (or an
/// interval end) where |p| is at round-off level counts as a root, so tangent (double) roots are
/// not lost. Leading coefficients whose terms are negligible over the interval (1e-15 of the
/// largest term) are dropped; infinite bounds are clipped to Cauchy's root bound. A zero or
/// non-finite polynomial has no roots reported. Never allocates, never throws.
int real_roots(const Polynomial& p, double lo, double hi,
               std::array<double, kMaxRoots>& roots) noexcept;

}  // namespace mjarm
