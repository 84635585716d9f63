#pragma once
/// @file
/// QP problems for the solver tests, held in plain Eigen types independent of the solver.

#include <Eigen/Core>
#include <limits>
#include <random>

#include "mjarm/qp/dense_qp.hpp"

namespace mjarm::test {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// min ½xᵀHx + gᵀx  s.t.  Ax = b, l ≤ Cx ≤ u, lb ≤ x ≤ ub.
struct Problem {
  Eigen::MatrixXd H, A, C;
  Eigen::VectorXd g, b, l, u, lb, ub;
  Eigen::VectorXd x0;  ///< a feasible point, when the generator knows one
  int n() const { return static_cast<int>(g.size()); }
};

/// Hands @p p to the solver.
inline void load(qp::DenseQp& qp, const Problem& p) {
  qp.set_hessian(p.H);
  qp.set_gradient(p.g);
  qp.set_equalities(p.A, p.b);
  qp.set_inequalities(p.C, p.l, p.u);
  qp.set_bounds(p.lb, p.ub);
}

/// A rows × cols matrix of independent N(0, σ²) entries, column by column.
inline Eigen::MatrixXd gaussian(std::mt19937& rng, int rows, int cols, double sigma = 1.0) {
  std::normal_distribution<double> normal(0.0, sigma);
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = normal(rng);
  return m;
}

}  // namespace mjarm::test
