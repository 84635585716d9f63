#include "polynomial.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mjarm::polynomial {

double evaluate(const Poly& p, double x) noexcept {
  double y = 0.0;
  for (auto it = p.rbegin(); it != p.rend(); ++it) y = y * x + *it;
  return y;
}

Poly derivative(const Poly& p) {
  if (p.size() <= 1) return {0.0};
  Poly d(p.size() - 1);
  for (std::size_t k = 1; k < p.size(); ++k) d[k - 1] = static_cast<double>(k) * p[k];
  return d;
}

Poly add(const Poly& a, const Poly& b) {
  Poly c(std::max(a.size(), b.size()), 0.0);
  for (std::size_t k = 0; k < a.size(); ++k) c[k] += a[k];
  for (std::size_t k = 0; k < b.size(); ++k) c[k] += b[k];
  return c;
}

Poly subtract(const Poly& a, const Poly& b) { return add(a, scale(b, -1.0)); }

Poly multiply(const Poly& a, const Poly& b) {
  if (a.empty() || b.empty()) return {0.0};
  Poly c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

Poly scale(const Poly& p, double factor) {
  Poly c(p);
  for (double& v : c) v *= factor;
  return c;
}

bool is_zero(const Poly& p) noexcept {
  return std::all_of(p.begin(), p.end(), [](double v) { return v == 0.0; });
}

std::vector<double> quadratic_roots(double a, double b, double c) {
  std::vector<double> roots;
  if (c == 0.0) {
    if (b != 0.0) roots.push_back(-a / b);
    return roots;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return roots;
  // the form without cancellation
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (q != 0.0) roots.push_back(a / q);
  roots.push_back(q / c);
  std::sort(roots.begin(), roots.end());
  return roots;
}

std::vector<double> real_roots(const Poly& p, double lo, double hi) {
  std::vector<double> roots;
  double largest = 0.0;
  for (double v : p) largest = std::max(largest, std::abs(v));
  if (!(largest > 0.0) || !std::isfinite(largest)) return roots;
  std::size_t degree = p.size() - 1;
  while (degree > 0 && std::abs(p[degree]) <= 1e-14 * largest) --degree;
  if (degree == 0) return roots;
  // companion matrix of the monic polynomial
  const auto n = static_cast<Eigen::Index>(degree);
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 1; i < n; ++i) companion(i, i - 1) = 1.0;
  for (Eigen::Index i = 0; i < n; ++i)
    companion(i, n - 1) = -p[static_cast<std::size_t>(i)] / p[degree];
  const Eigen::VectorXcd eigenvalues =
      Eigen::EigenSolver<Eigen::MatrixXd>(companion, false).eigenvalues();
  const Poly dp = derivative(p);
  const double margin = 1e-6 * (hi - lo);
  for (const std::complex<double>& z : eigenvalues) {
    // near-real roots: a double root comes out as a pair with a small imaginary part
    if (std::abs(z.imag()) > 1e-4 * (1.0 + std::abs(z.real()))) continue;
    double x = z.real();
    if (x < lo - margin || x > hi + margin) continue;
    for (int k = 0; k < 4; ++k) {  // Newton polish
      const double slope = evaluate(dp, x);
      if (slope == 0.0) break;
      const double step = evaluate(p, x) / slope;
      if (!std::isfinite(step) || std::abs(step) > margin + 1e-3 * (hi - lo)) break;
      x -= step;
    }
    roots.push_back(std::clamp(x, lo, hi));
  }
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end(),
                          [](double a, double b) { return std::abs(a - b) <= 1e-12; }),
              roots.end());
  return roots;
}

}  // namespace mjarm::polynomial
