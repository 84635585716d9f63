#pragma once
// Small dense polynomials in one variable (coefficients in ascending powers) for the exact
// duration search of quintic profiles: arithmetic, and the real roots in an interval from the
// eigenvalues of the companion matrix, polished by Newton's method. Not for hot paths.

#include <vector>

namespace mjarm::polynomial {

using Poly = std::vector<double>;  // c[0] + c[1]·x + c[2]·x² + …

double evaluate(const Poly& p, double x) noexcept;
Poly derivative(const Poly& p);
Poly add(const Poly& a, const Poly& b);
Poly subtract(const Poly& a, const Poly& b);
Poly multiply(const Poly& a, const Poly& b);
Poly scale(const Poly& p, double factor);
// true when every coefficient is exactly zero
bool is_zero(const Poly& p) noexcept;

// The real roots of p in [lo, hi], ascending (duplicates within 1e-12 merged). Leading
// coefficients below 1e-14 of the largest are dropped first; a zero polynomial has none.
std::vector<double> real_roots(const Poly& p, double lo, double hi);

// The real roots of a + b·x + c·x² (any of them may be zero), ascending.
std::vector<double> quadratic_roots(double a, double b, double c);

}  // namespace mjarm::polynomial
