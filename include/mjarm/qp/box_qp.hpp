#pragma once
/// @file
/// Strictly convex QP with simple bounds only: primal active-set method on the bounds.
///
///     minimize    ½ xᵀ H x + gᵀ x        x ∈ ℝⁿ
///     subject to  lb ≤ x ≤ ub            (±∞ allowed; lb_j = ub_j fixes x_j)
///
/// H must be symmetric positive definite. The solver keeps a feasible iterate and a working set
/// of variables held at a bound (the free set F is the rest). Each iteration solves the free
/// variables' reduced system H_FF z = −(g_F + H_FA x_A) with a Cholesky factor of H_FF, then
/// either moves towards z until the first free variable reaches a bound (which joins the working
/// set) or, when z is feasible, takes it and releases the bound whose multiplier has the most
/// wrong sign (none left: solved). The factor is kept in working order, free variables first:
/// a variable leaving F recomputes only the factor rows after its position, a released one
/// appends one row. The first iteration factors all of H in that order, which is also the
/// positive-definiteness check (pivot ≤ 1e-14·max|H_jj| → not_convex).
///
/// A warm start begins from the previous solution's bound pattern (the bounds that are finite
/// now) with the free variables at the previous solution clamped into the box; when that
/// pattern is the answer, one reduced solve and one gradient settle it. Every iteration either
/// adds a bound or lowers the objective strictly, so a strictly convex problem is solved in
/// finitely many steps; BoxQpSettings::max_iterations guards against cycling on round-off.
/// All workspace is allocated by the constructor; solve() allocates nothing and never throws.
///
/// Multiplier convention (as DenseQp's y_bound): H x + g + y = 0 on the working set, y_j ≥ 0
/// when x_j = ub_j, y_j ≤ 0 when x_j = lb_j, y_j = 0 for a free variable; a fixed variable
/// (lb_j = ub_j) takes either sign.

#include <Eigen/Core>

#include "mjarm/qp/dense_qp.hpp"

namespace mjarm::qp {

/// Tuning knobs of BoxQp; the defaults suit well-scaled problems.
struct BoxQpSettings {
  /// Most iterations (reduced solves) per solve; ≤ 0 selects 10·n + 100.
  int max_iterations = 0;
  /// A bound is released only when its multiplier has the wrong sign by more than this
  /// fraction of |g_j| + Σ_k |H_jk x_k| (the scale of the gradient entry's round-off).
  double dual_tolerance = 1e-12;
};

constexpr auto declared_fields(const BoxQpSettings*) {
  using S = BoxQpSettings;
  return declare<S>(
      "box QP",
      field("max_iterations", &S::max_iterations, "", Range{},
            "most reduced solves per solve; ≤ 0: 10·n + 100"),
      field("dual_tolerance", &S::dual_tolerance, "", Range::non_negative(),
            "wrong-sign multiplier, as a fraction of the gradient's scale, that releases a bound"));
}

/// Result of BoxQp::solve(); owned by the solver (vectors preallocated at construction).
struct BoxQpResult {
  QpStatus status =
      QpStatus::invalid_input;  ///< solved, not_convex, invalid_input, iteration_limit
  Eigen::VectorXd x;            ///< primal solution (n); the last (feasible) iterate unless solved
  double objective = 0.0;       ///< ½xᵀHx + gᵀx at x
  int iterations = 0;           ///< reduced solves taken (≥ 1 when solved)
  double kkt_residual = 0.0;  ///< max of ‖stationarity‖∞ on F, primal violation, wrong-sign y
  Eigen::VectorXd y_bound;    ///< bound multipliers (n), sign per active side
  int active_count = 0;       ///< variables at a bound at x (fixed ones included)
  bool warm_started = false;  ///< the solve began from the previous bound pattern
};

/// Box-constrained QP solver with preallocated workspace (see the file comment).
///
/// Until set: H = 0 (so solve() reports not_convex), g = 0, lb = −∞, ub = +∞.
class BoxQp {
 public:
  /// Preallocates everything for n variables.
  /// @throws mjarm::Error when n < 1
  explicit BoxQp(int n);

  /// Sets H (n×n, symmetric positive definite; the lower triangle is read and mirrored).
  /// @throws mjarm::Error on a size mismatch
  void set_hessian(const Eigen::Ref<const Eigen::MatrixXd>& H);
  /// Sets the linear term g (n).
  /// @throws mjarm::Error on a size mismatch
  void set_gradient(const Eigen::Ref<const Eigen::VectorXd>& g);
  /// Sets the bounds lb, ub (n each; −∞/+∞ for a missing side).
  /// @throws mjarm::Error on a size mismatch
  void set_bounds(const Eigen::Ref<const Eigen::VectorXd>& lb,
                  const Eigen::Ref<const Eigen::VectorXd>& ub);

  /// Solves the QP. Allocates nothing, never throws.
  /// @param start cold (free set = every variable whose bounds differ, start at clamp(0)), or
  ///        warm from the last solved bound pattern and x (cold when there is none)
  /// @return the result, valid until the next solve()
  const BoxQpResult& solve(QpStart start = QpStart::warm) noexcept;

  /// Forgets the bound pattern kept for warm starts (the next solve() starts cold).
  void reset_warm_start() noexcept { have_warm_ = false; }

  /// Settings used by the next solve().
  BoxQpSettings& settings() noexcept { return settings_; }
  /// Settings used by the next solve().
  const BoxQpSettings& settings() const noexcept { return settings_; }
  /// Result of the last solve().
  const BoxQpResult& result() const noexcept { return result_; }
  /// Number of variables n.
  int num_variables() const noexcept { return n_; }

 private:
  QpStatus run(bool warm, int& iterations) noexcept;
  bool factor_rows(int from, int to) noexcept;
  void solve_free() noexcept;
  void gradient() noexcept;
  void finalize(QpStatus status, int iterations, bool warm) noexcept;

  int n_;
  BoxQpSettings settings_;
  BoxQpResult result_;

  // problem data
  Eigen::MatrixXd H_;  // symmetric, both triangles
  Eigen::VectorXd g_, lb_, ub_;
  double pivot_min_ = 0.0;  // 1e-14·max|H_jj|
  bool hessian_ok_ = true, gradient_ok_ = true, bounds_ok_ = true;

  // working set: state_ per variable 0 free, −1 at lb, +1 at ub, 2 fixed (lb = ub);
  // order_ lists the free variables (first nf_) then the bound ones
  Eigen::VectorXi state_, order_;
  int nf_ = 0;
  bool have_warm_ = false;

  // factor of H in working order, row-major (row k of L contiguous), and its inverse diagonal
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> L_;
  Eigen::VectorXd inv_diag_;

  // iterate, reduced solution (working order), gradient H x + g
  Eigen::VectorXd x_, z_, grad_;
};

}  // namespace mjarm::qp
