#pragma once
/// @file
/// Dense strictly convex QP solver: dual active-set method of Goldfarb & Idnani (1983).
///
///     minimize    ½ xᵀ H x + gᵀ x                    x ∈ ℝⁿ
///     subject to  A_eq x = b_eq                       (m_eq rows)
///                 l ≤ C x ≤ u                         (m_in two-sided rows, ±∞ allowed)
///                 lb ≤ x ≤ ub                         (simple bounds, ±∞ allowed)
///
/// H must be symmetric positive definite. The solver starts from the unconstrained minimizer
/// −H⁻¹g (cold) or from the previous working set (warm), keeps every iterate dual feasible and
/// adds the most violated constraint (violation scaled by the row norm) until all hold. Simple
/// bounds are their own constraint kind: their normal is a unit vector, so each costs O(n)
/// instead of a dense row's O(n²). All workspace is allocated by the constructor; solve()
/// allocates nothing and never throws.
///
/// Each step recomputes the minimizer on the working set from the factorization (O(n²)), so
/// iterates carry no drift; general rows whose margin at the last full evaluation of C·x exceeds
/// the distance moved since are skipped by the search for the most violated row (exactly: a
/// skipped row cannot be violated). Degenerate steps (a new normal linearly dependent on the
/// working set) move the multipliers only and drop the first one to reach zero; when none can,
/// the problem is infeasible.
///
/// Multiplier convention (dual of each constraint, returned in QpResult):
///     H x + g + A_eqᵀ y_eq + Cᵀ y_in + y_bound = 0,
/// y_in[i] ≥ 0 when C_i x = u_i (upper side active), ≤ 0 when C_i x = l_i, 0 when inactive;
/// y_bound[j] likewise for lb_j/ub_j; y_eq has any sign.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/qp/active_set_factor.hpp"

namespace mjarm::qp {

/// Outcome of DenseQp::solve().
enum class QpStatus {
  solved,           ///< KKT point found (the unique minimizer)
  infeasible,       ///< the constraints have no common point (the dual is unbounded)
  iteration_limit,  ///< no convergence in QpSettings::max_iterations steps (or a numerical
                    ///< breakdown, e.g. a non-finite iterate)
  not_convex,       ///< H is not numerically positive definite (its Cholesky factor fails)
  invalid_input,  ///< non-finite data, l > u, lb > ub, a lower limit +∞ or an upper limit −∞
};

constexpr auto declared_names(const QpStatus*) {
  using S = QpStatus;
  return std::array{EnumName{S::solved, "solved", "KKT point found"},
                    EnumName{S::infeasible, "infeasible", "the constraints have no common point"},
                    EnumName{S::iteration_limit, "iteration_limit", "no convergence in the steps"},
                    EnumName{S::not_convex, "not_convex", "H not positive definite"},
                    EnumName{S::invalid_input, "invalid_input", "non-finite or crossed data"}};
}

/// Tuning knobs of DenseQp; the defaults suit well-scaled problems.
struct QpSettings {
  /// Most Goldfarb–Idnani steps (additions, drops) per solve; ≤ 0 selects
  /// 10·(n + m) + 100 with m = m_eq + m_in + n.
  int max_iterations = 0;
  /// A constraint counts as violated when (row·x − limit)/‖row‖ is worse than this (units of x).
  double primal_tolerance = 1e-10;
  /// A constraint is linearly dependent on the working set when the part of its normal outside
  /// the working set is below this fraction of the whole (both in the H⁻¹ metric).
  double dependence_tolerance = 1e-10;
};

constexpr auto declared_fields(const QpSettings*) {
  using S = QpSettings;
  return declare<S>(
      "dense QP",
      field("max_iterations", &S::max_iterations, "", Range{},
            "most steps per solve; ≤ 0: 10·(n + m) + 100"),
      field("primal_tolerance", &S::primal_tolerance, "", Range::non_negative(),
            "scaled violation that counts as violated, in units of x"),
      field("dependence_tolerance", &S::dependence_tolerance, "", Range::non_negative(),
            "fraction below which a new normal is dependent on the working set"));
}

/// Result of a solve; owned by the solver (all vectors preallocated at construction).
struct QpResult {
  QpStatus status = QpStatus::invalid_input;  ///< outcome
  Eigen::VectorXd x;          ///< primal solution (n); the last iterate unless solved
  double objective = 0.0;     ///< ½xᵀHx + gᵀx at x
  int iterations = 0;         ///< Goldfarb–Idnani steps taken (additions + drops)
  double kkt_residual = 0.0;  ///< max of ‖stationarity‖∞, primal violation, |complementarity|
  Eigen::VectorXd y_eq;       ///< multipliers of A_eq x = b_eq (m_eq)
  Eigen::VectorXd y_in;       ///< multipliers of l ≤ Cx ≤ u (m_in), sign per active side
  Eigen::VectorXd y_bound;    ///< multipliers of lb ≤ x ≤ ub (n), sign per active side
  bool warm_started = false;  ///< the solve began from the previous working set
};

/// How solve() chooses its first working set.
enum class QpStart {
  cold,  ///< empty working set: start at the unconstrained minimizer
  warm,  ///< the previous solution's working set if there is one, else cold
};

constexpr auto declared_names(const QpStart*) {
  return std::array{EnumName{QpStart::cold, "cold", "start at the unconstrained minimizer"},
                    EnumName{QpStart::warm, "warm", "the previous working set if any"}};
}

/// Dense QP solver with preallocated workspace (see the file comment for the problem).
///
/// Data are set through the setters, whose sizes are fixed at construction. Until set: H = 0
/// (so solve() reports not_convex), g = 0, A_eq = 0, b_eq = 0, C = 0, l = −∞, u = +∞,
/// lb = −∞, ub = +∞. The Cholesky factor of H is kept until set_hessian() is called again;
/// the working-set factorization of the last solve is reused by a warm start while H, A_eq and
/// C are unchanged (changing g, b_eq and limits keeps it).
class DenseQp {
 public:
  /// Preallocates everything for the given sizes.
  /// @param n number of variables (≥ 1)
  /// @param m_eq number of equality rows (≥ 0)
  /// @param m_in number of two-sided general inequality rows (≥ 0)
  /// @throws mjarm::Error on a negative size or n < 1
  DenseQp(int n, int m_eq, int m_in);

  /// Sets H (n×n, symmetric positive definite; the lower triangle is read and mirrored).
  /// Marks the Cholesky factor stale: it is recomputed on the next solve().
  /// @throws mjarm::Error on a size mismatch
  void set_hessian(const Eigen::Ref<const Eigen::MatrixXd>& H);
  /// Sets the linear term g (n).
  /// @throws mjarm::Error on a size mismatch
  void set_gradient(const Eigen::Ref<const Eigen::VectorXd>& g);
  /// Sets A_eq (m_eq×n) and b_eq (m_eq).
  /// @throws mjarm::Error on a size mismatch
  void set_equalities(const Eigen::Ref<const Eigen::MatrixXd>& A_eq,
                      const Eigen::Ref<const Eigen::VectorXd>& b_eq);
  /// Sets b_eq only (m_eq); keeps the working-set factorization for warm starts.
  /// @throws mjarm::Error on a size mismatch
  void set_equality_rhs(const Eigen::Ref<const Eigen::VectorXd>& b_eq);
  /// Sets C (m_in×n) and its limits l, u (m_in each; −∞/+∞ for a missing side).
  /// @throws mjarm::Error on a size mismatch
  void set_inequalities(const Eigen::Ref<const Eigen::MatrixXd>& C,
                        const Eigen::Ref<const Eigen::VectorXd>& l,
                        const Eigen::Ref<const Eigen::VectorXd>& u);
  /// Sets l and u only (m_in each); keeps the working-set factorization for warm starts.
  /// @throws mjarm::Error on a size mismatch
  void set_inequality_limits(const Eigen::Ref<const Eigen::VectorXd>& l,
                             const Eigen::Ref<const Eigen::VectorXd>& u);
  /// Sets the simple bounds lb, ub (n each; −∞/+∞ for a missing side).
  /// @throws mjarm::Error on a size mismatch
  void set_bounds(const Eigen::Ref<const Eigen::VectorXd>& lb,
                  const Eigen::Ref<const Eigen::VectorXd>& ub);

  /// Solves the QP. Allocates nothing, never throws. A warm start that ends infeasible or at the
  /// iteration limit is retried cold, so the status never depends on the start.
  /// @param start cold, or warm from the last solved working set
  /// @return the result, valid until the next solve()
  const QpResult& solve(QpStart start = QpStart::warm) noexcept;

  /// Forgets the working set kept for warm starts (the next solve() starts cold).
  void reset_warm_start() noexcept {
    warm_count_ = 0;
    factor_current_ = false;
  }

  /// Settings used by the next solve().
  QpSettings& settings() noexcept { return settings_; }
  /// Settings used by the next solve().
  const QpSettings& settings() const noexcept { return settings_; }
  /// Result of the last solve().
  const QpResult& result() const noexcept { return result_; }

  /// Number of variables n.
  int num_variables() const noexcept { return n_; }
  /// Number of equality rows m_eq.
  int num_equalities() const noexcept { return me_; }
  /// Number of general two-sided inequality rows m_in.
  int num_inequalities() const noexcept { return mi_; }
  /// How many Cholesky factorizations of H solve() has done (diagnostics: H reuse).
  int hessian_factorizations() const noexcept { return factorizations_; }
  /// The working-set factorization left by the last solve (diagnostics).
  const ActiveSetFactor& factor() const noexcept { return factor_; }
  /// Size of the working set at the end of the last solve (equalities included).
  int active_count() const noexcept { return factor_.active_count(); }

 private:
  // constraint ids: [0, me) equality rows; me + 2i (+1) lower (upper) side of row i;
  // me + 2 mi + 2j (+1) lower (upper) bound of x_j
  QpStatus run(bool warm, int max_iterations, int& iterations) noexcept;
  bool start_working_set(bool warm, int max_iterations, int& steps) noexcept;
  void normal_projection(int id, Eigen::VectorXd& d) const noexcept;
  double rhs(int id) const noexcept;
  double slack(int id) const noexcept;
  int most_violated(double& slack_p) noexcept;
  int refresh_reference() noexcept;
  void update_margins() noexcept;
  void set_state(int id, int value) noexcept;
  void push_active(int id) noexcept;
  void drop_active(int k, Eigen::VectorXd* d) noexcept;
  void finalize(QpStatus status, int iterations, bool warm) noexcept;
  bool data_valid() const noexcept;

  int n_, me_, mi_;
  QpSettings settings_;
  QpResult result_;

  // problem data
  Eigen::MatrixXd H_;
  Eigen::VectorXd g_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> a_eq_;
  Eigen::VectorXd b_eq_;
  Eigen::VectorXd eq_scale_;  // 1 / row norm of A_eq (1 for a zero row)
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c_;
  Eigen::MatrixXd c_cols_;  // C again, column-major: for the pass over all rows
  Eigen::VectorXd l_, u_, lb_, ub_;
  Eigen::VectorXd c_scale_;  // 1 / row norm of C (1 for a zero row)
  bool hessian_ok_ = true, gradient_ok_ = true, a_eq_ok_ = true, b_eq_ok_ = true, c_ok_ = true,
       limits_ok_ = true, bounds_ok_ = true;
  bool hessian_dirty_ = true;
  bool hessian_convex_ = false;
  int factorizations_ = 0;

  // working set
  ActiveSetFactor factor_;
  bool factor_current_ = false;   // factor_ holds the last solved working set for this data
  Eigen::VectorXi active_;        // constraint id per working-set position (n)
  Eigen::VectorXd b_active_;      // right-hand side per position (n)
  Eigen::VectorXd u_active_;      // multiplier per position, H x + g = N u (n)
  Eigen::VectorXi state_;         // per row of C then per x_j: 0 free, -1 lower, +1 upper active
  Eigen::VectorXd row_skip_;      // per row of C: 0 free, +inf active (masks the violation scan)
  Eigen::VectorXi redundant_eq_;  // equality rows skipped as linearly dependent (me)
  int redundant_count_ = 0;
  int eq_active_ = 0;     // equalities in the working set (its first positions)
  Eigen::VectorXi warm_;  // inequality ids of the last solved working set (n)
  int warm_count_ = 0;
  int warm_reuses_ = 0;                      // warm starts on the kept factorization in a row
  static constexpr int kRebuildPeriod = 64;  // then one rebuild from J0

  // scratch
  Eigen::VectorXd x_, d_, r_, hx_, stat_;
  // row products C·x_ref_ at a reference point and the scaled margins there, to skip rows that
  // provably hold (dense_qp_search.cpp; valid while C is unchanged)
  Eigen::VectorXd x_ref_, cx_ref_, margin_ref_;
  Eigen::VectorXi near_;     // scratch: rows near their limits (m_in + 1)
  Eigen::VectorXd near_cx_;  // scratch: their products with x (m_in + 1)
  bool ref_valid_ = false;
  bool margins_stale_ = true;  // the limits changed since margin_ref_ was computed
};

}  // namespace mjarm::qp
