#include "mjarm/trajectory/otg/validation/grid_reference.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/qp/dense_qp.hpp"

namespace mjarm {

bool grid_motion_exists(const KinematicState& start, const KinematicState& target,
                        const JerkLimits& limits, double duration, int steps) {
  if (steps < 1 || !(duration > 0.0) || !std::isfinite(duration))
    throw Error("grid_motion_exists: expected steps ≥ 1 and a positive finite duration, got " +
                std::to_string(steps) + " and " + number_text(duration));
  const int n = steps;
  const double h = duration / n;
  const double J = limits.jerk;
  // x_i = jerk of step i / J ∈ [−1, 1]; a state at time t depends on step i (ending before t)
  // through: a: J·h, v: J·h·(t − tᵢ − h/2), p: J·h·((t − tᵢ − h/2)²/2 + h²/24)
  Eigen::MatrixXd A_eq(3, n), C(2 * n, n);
  Eigen::VectorXd b_eq(3), l(2 * n), u(2 * n);
  C.setZero();
  const double T = duration;
  for (int i = 0; i < n; ++i) {
    const double s = T - i * h - 0.5 * h;
    A_eq(0, i) = J * h * (0.5 * s * s + h * h / 24.0);
    A_eq(1, i) = J * h * s;
    A_eq(2, i) = J * h;
  }
  b_eq << target.p - (start.p + start.v * T + 0.5 * start.a * T * T),
      target.v - (start.v + start.a * T), target.a - start.a;
  const double slack_v = J * h * h / 8.0;
  for (int k = 1; k <= n; ++k) {
    const double t = k * h;
    for (int i = 0; i < k; ++i) {
      C(k - 1, i) = J * h;                              // a(t)
      C(n + k - 1, i) = J * h * (t - i * h - 0.5 * h);  // v(t)
    }
    l(k - 1) = -limits.acceleration - start.a;
    u(k - 1) = limits.acceleration - start.a;
    l(n + k - 1) = -(limits.velocity - slack_v) - (start.v + start.a * t);
    u(n + k - 1) = (limits.velocity - slack_v) - (start.v + start.a * t);
  }
  qp::DenseQp qp(n, 3, 2 * n);
  qp.set_hessian(Eigen::MatrixXd::Identity(n, n));
  qp.set_equalities(A_eq, b_eq);
  qp.set_inequalities(C, l, u);
  qp.set_bounds(Eigen::VectorXd::Constant(n, -1.0), Eigen::VectorXd::Constant(n, 1.0));
  qp.settings().primal_tolerance = 1e-11;
  const qp::QpResult& r = qp.solve(qp::QpStart::cold);
  return r.status == qp::QpStatus::solved;
}

}  // namespace mjarm
