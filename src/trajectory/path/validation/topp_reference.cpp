#include "mjarm/trajectory/path/validation/topp_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

// q′ and q″ at every grid point (n × (N + 1) each)
void path_derivatives_on_grid(const JointPath& path, const Eigen::VectorXd& grid,
                              Eigen::MatrixXd& d1, Eigen::MatrixXd& d2) {
  const Eigen::Index n = path.dofs();
  d1.resize(n, grid.size());
  d2.resize(n, grid.size());
  Eigen::VectorXd q(n), dq(n), ddq(n);
  for (Eigen::Index i = 0; i < grid.size(); ++i) {
    path.evaluate(grid[i], q, dq, ddq);
    d1.col(i) = dq;
    d2.col(i) = ddq;
  }
}

void require_reference_sizes(const JointPath& path, const Eigen::VectorXd& v,
                             const Eigen::VectorXd& a, const Eigen::VectorXd& grid) {
  if (v.size() != path.dofs() || a.size() != path.dofs())
    throw Error("TOPP reference: the limits must have one entry per joint (" +
                std::to_string(path.dofs()) + ")");
  if (grid.size() < 2) throw Error("TOPP reference: the grid needs at least 2 points");
}

}  // namespace

ToppReference solve_topp_reference(const JointPath& path, const Eigen::VectorXd& max_velocity,
                                   const Eigen::VectorXd& max_acceleration,
                                   const Eigen::VectorXd& grid, const Eigen::VectorXd* start) {
  require_reference_sizes(path, max_velocity, max_acceleration, grid);
  const int N = static_cast<int>(grid.size()) - 1;
  const int n = static_cast<int>(path.dofs());
  if (start != nullptr && start->size() != N + 1)
    throw Error("TOPP reference: the start needs one squared speed per grid point");
  Eigen::MatrixXd d1, d2;
  path_derivatives_on_grid(path, grid, d1, d2);

  const int variables = N + 1;
  Eigen::VectorXd upper(variables);
  for (int i = 0; i <= N; ++i) {
    double bound = 1e12;  // where no joint moves the velocity bound is absent: a cap
    for (int j = 0; j < n; ++j)
      if (d1(j, i) != 0.0) bound = std::min(bound, std::pow(max_velocity[j] / d1(j, i), 2));
    upper[i] = bound;
  }
  upper[0] = upper[N] = 0.0;  // at rest at both ends
  // acceleration rows, scaled by 1/a_j: two per joint and step
  const int rows = 2 * n * N;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(rows, variables);
  for (int i = 0; i < N; ++i) {
    const double inv = 1.0 / (2.0 * (grid[i + 1] - grid[i]));  // u_i = (x_{i+1} − x_i)·inv
    for (int j = 0; j < n; ++j) {
      const double w = 1.0 / max_acceleration[j];
      const int r = 2 * (n * i + j);
      C(r, i) = w * (d2(j, i) - d1(j, i) * inv);  // at s_i with x_i
      C(r, i + 1) = w * d1(j, i) * inv;
      C(r + 1, i) = -w * d1(j, i + 1) * inv;  // at s_{i+1} with x_{i+1}
      C(r + 1, i + 1) = w * (d2(j, i + 1) + d1(j, i + 1) * inv);
    }
  }
  const Eigen::VectorXd lower_row = Eigen::VectorXd::Constant(rows, -1.0);
  const Eigen::VectorXd upper_row = Eigen::VectorXd::Ones(rows);

  ToppReference reference;
  qp::DenseQp qp(variables, 0, rows);
  Eigen::VectorXd x;
  if (start != nullptr) {
    x = start->cwiseMax(0.0).cwiseMin(upper);
  } else {
    // a feasible start: the nearest feasible point to the velocity bounds
    qp.set_hessian(Eigen::MatrixXd::Identity(variables, variables));
    qp.set_gradient(-upper);
    qp.set_inequalities(C, lower_row, upper_row);
    qp.set_bounds(Eigen::VectorXd::Zero(variables), upper);
    const qp::QpResult& first = qp.solve(qp::QpStart::cold);
    reference.iterations += first.iterations;
    reference.status = first.status;
    if (!reference.solved()) return reference;
    x = first.x.cwiseMax(0.0);
  }

  // Newton steps on T(x) = Σ c_i/(√x_i + √x_{i+1}), c_i = 2Δ_i (convex: 1/(a concave positive
  // function)), each a QP in the step d with x + d feasible; x_0 = x_N = 0 stay fixed by their
  // bounds (their terms' derivatives are taken at the interior end only)
  qp.set_inequalities(C, lower_row, upper_row);
  Eigen::MatrixXd H(variables, variables);
  Eigen::VectorXd g(variables);
  const auto duration_of = [&](const Eigen::VectorXd& y) { return topp_grid_duration(grid, y); };
  double T = duration_of(x);
  for (int iteration = 0; iteration < 60; ++iteration) {
    H.setZero();
    g.setZero();
    for (int i = 0; i < N; ++i) {
      const double c = 2.0 * (grid[i + 1] - grid[i]);
      const double a = std::max(x[i], 1e-300), b = std::max(x[i + 1], 1e-300);
      const double ra = std::sqrt(a), rb = std::sqrt(b), S = ra + rb;
      const bool free_a = i > 0, free_b = i + 1 < N;
      if (free_a) {
        g[i] += -c / (S * S) / (2.0 * ra);
        H(i, i) += c / (2.0 * a * S * S * S) + c / (4.0 * a * ra * S * S);
      }
      if (free_b) {
        g[i + 1] += -c / (S * S) / (2.0 * rb);
        H(i + 1, i + 1) += c / (2.0 * b * S * S * S) + c / (4.0 * b * rb * S * S);
      }
      if (free_a && free_b) {
        const double cross = c / (2.0 * S * S * S * ra * rb);
        H(i, i + 1) += cross;
        H(i + 1, i) += cross;
      }
    }
    H(0, 0) = H(N, N) = 1.0;
    H.diagonal().array() += 1e-12 * H.diagonal().maxCoeff();
    qp.set_hessian(H);
    qp.set_gradient(g);
    // the step's bounds and rows: x + d within them
    qp.set_bounds(-x, upper - x);
    const Eigen::VectorXd Cx = C * x;
    qp.set_inequality_limits(lower_row - Cx, upper_row - Cx);
    const qp::QpResult& step = qp.solve(qp::QpStart::warm);
    reference.iterations += step.iterations;
    reference.status = step.status;
    if (!reference.solved()) break;
    const Eigen::VectorXd& d = step.x;
    const double decrease = -g.dot(d);
    if (!(decrease > 1e-13 * T)) break;
    double alpha = 1.0;
    for (int k = 0; k < 40; ++k, alpha *= 0.5) {
      const double trial = duration_of((x + alpha * d).cwiseMax(0.0));
      if (trial <= T - 1e-4 * alpha * decrease) {
        x = (x + alpha * d).cwiseMax(0.0);
        T = trial;
        break;
      }
    }
    ++reference.newton_steps;
  }
  reference.squared_speeds = x;
  reference.duration = reference.solved() ? T : std::numeric_limits<double>::infinity();
  return reference;
}

double topp_grid_excess(const JointPath& path, const Eigen::VectorXd& max_velocity,
                        const Eigen::VectorXd& max_acceleration, const Eigen::VectorXd& grid,
                        const Eigen::VectorXd& squared_speeds) {
  require_reference_sizes(path, max_velocity, max_acceleration, grid);
  if (squared_speeds.size() != grid.size())
    throw Error("TOPP reference: one squared speed per grid point expected");
  Eigen::MatrixXd d1, d2;
  path_derivatives_on_grid(path, grid, d1, d2);
  const Eigen::Index N = grid.size() - 1;
  double worst = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i <= N; ++i) {
    const double x = squared_speeds[i];
    for (Eigen::Index j = 0; j < path.dofs(); ++j)
      worst =
          std::max(worst, std::abs(d1(j, i)) * std::sqrt(std::max(x, 0.0)) / max_velocity[j] - 1.0);
    if (i == N) break;
    const double u = (squared_speeds[i + 1] - x) / (2.0 * (grid[i + 1] - grid[i]));
    for (Eigen::Index j = 0; j < path.dofs(); ++j) {
      const double start = d1(j, i) * u + d2(j, i) * x;
      const double end = d1(j, i + 1) * u + d2(j, i + 1) * squared_speeds[i + 1];
      worst = std::max(worst, std::max(std::abs(start), std::abs(end)) / max_acceleration[j] - 1.0);
    }
  }
  return worst;
}

double topp_grid_duration(const Eigen::VectorXd& grid, const Eigen::VectorXd& squared_speeds) {
  double total = 0.0;
  for (Eigen::Index i = 0; i + 1 < grid.size(); ++i) {
    const double rate = std::sqrt(std::max(squared_speeds[i], 0.0)) +
                        std::sqrt(std::max(squared_speeds[i + 1], 0.0));
    total +=
        rate > 0.0 ? 2.0 * (grid[i + 1] - grid[i]) / rate : std::numeric_limits<double>::infinity();
  }
  return total;
}

}  // namespace mjarm
