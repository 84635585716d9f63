#pragma once
/// @file
/// `TaskSpaceDynamics`: operational-space inertia Λ, the dynamically consistent generalized
/// inverse J̄ and the null-space projector N of one task Jacobian, with a bounded path near
/// singularities.

#include <Eigen/Core>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/workspace_ptr.hpp"

namespace mjarm {

/// Tuning of the robust Λ path.
struct TaskSpaceOptions {
  /// Floor on the eigenvalues of Λ⁻¹ = J·M⁻¹·Jᵀ [1/kg for linear rows, 1/(kg·m²) for angular
  /// rows]: eigenvalues below it are replaced by it, so no direction of Λ exceeds 1/floor
  /// (1000 kg or kg·m² by default). Away from singularities (every eigenvalue above the floor)
  /// Λ is the exact inverse. Must be > 0 and finite.
  double min_eigenvalue = 1e-3;
  /// Always take the eigendecomposition path, even when the Cholesky fast path certifies that
  /// no eigenvalue is below the floor (the results agree to rounding; for tests and comparisons).
  bool always_eigendecompose = false;
  /// Use the run-time-size kernels even for the sizes that have compile-time ones (n = 6 or 7
  /// with m = 3 or 6); the results agree to rounding (for tests and comparisons).
  bool generic_kernels = false;
};

constexpr auto declared_fields(const TaskSpaceOptions*) {
  using S = TaskSpaceOptions;
  return declare<S>(
      "task-space dynamics",
      field("min_eigenvalue", &S::min_eigenvalue, "1/kg or 1/(kg·m²)", Range::positive(),
            "floor on the eigenvalues of Λ⁻¹"),
      field("always_eigendecompose", &S::always_eigendecompose,
            "always take the eigendecomposition path"),
      field("generic_kernels", &S::generic_kernels, "run-time-size kernels for every size"));
}

/// Outcome of one `TaskSpaceDynamics::update`.
enum class TaskSpaceStatus {
  ok,                    ///< Λ is the exact inverse of J·M⁻¹·Jᵀ
  damped,                ///< near a singularity: at least one eigenvalue was floored
  not_positive_definite  ///< M failed its Cholesky factorization; outputs are left unchanged
};

constexpr auto declared_names(const TaskSpaceStatus*) {
  using S = TaskSpaceStatus;
  return std::array{EnumName{S::ok, "ok", "Λ is the exact inverse"},
                    EnumName{S::damped, "damped", "an eigenvalue was floored"},
                    EnumName{S::not_positive_definite, "not_positive_definite",
                             "M failed its Cholesky factorization"}};
}

/// Task-space (operational-space) dynamics for an m×n task Jacobian J (1 ≤ m ≤ 6) and an n×n
/// joint-space inertia M:
///
///     Λ = (J·M⁻¹·Jᵀ)⁻¹          m×m   task-space inertia [kg, kg·m²]
///     J̄ = M⁻¹·Jᵀ·Λ              n×m   dynamically consistent generalized inverse
///     N = I − J̄·J               n×n   null-space projector of joint velocities; Nᵀ for torques
///
/// Λ⁻¹ is eigendecomposed (V·diag(λ)·Vᵀ) and Λ = V·diag(1/max(λ, floor))·Vᵀ: exact away from
/// singularities. Fast path: Λ⁻¹ = R·Rᵀ (Cholesky) and Λ = R⁻ᵀ·R⁻¹; it is kept when every
/// eigenvalue of Λ⁻¹ is certified above the floor, so that the eigen path would floor nothing:
/// cheaply by trace(Λ) ≤ 1/(2·floor) (trace(Λ) ≥ λ_max(Λ) = 1/λ_min(Λ⁻¹); the factor 2 is
/// far more than the rounding of Λ), else exactly by a Cholesky factorization of Λ⁻¹ − floor·I
/// (it exists iff Λ⁻¹ − floor·I ≻ 0). Otherwise the eigen path runs. Always: M·N = Nᵀ·M and
/// N·M⁻¹ = M⁻¹·Nᵀ (N is self-adjoint in the M inner product).
/// When no eigenvalue is floored (status ok) also: Λ·J·M⁻¹·Jᵀ = I, J·J̄ = I, N·J̄ = 0, J·N = 0,
/// N² = N. When floored (status damped) they hold only along the unfloored eigen-directions.
///
/// All buffers are allocated in the constructor; `update` allocates nothing and never throws.
/// M⁻¹, J̄, N and the eigenvalues are computed on first access after an `update` (cached, no
/// allocation): a control tick that needs only Λ and `project_torque` does not pay for them.
/// n = 6 or 7 with m = 3 or 6 run compile-time-size kernels (`TaskSpaceOptions::generic_kernels`
/// turns them off).
/// Those accessors are const but fill a cache: do not call them concurrently on one object.
class TaskSpaceDynamics {
 public:
  /// @param dofs n, the number of joint-space dofs (≥ 1).
  /// @param task_rows m, the number of task rows (1..6): 6 for a full pose task, 3 for position.
  /// @throws Error when a size is out of range or options.min_eigenvalue is not > 0 and finite.
  TaskSpaceDynamics(int dofs, int task_rows = 6, TaskSpaceOptions options = {});
  ~TaskSpaceDynamics();
  TaskSpaceDynamics(const TaskSpaceDynamics& other);
  TaskSpaceDynamics& operator=(const TaskSpaceDynamics& other);
  TaskSpaceDynamics(TaskSpaceDynamics&& other) noexcept;
  TaskSpaceDynamics& operator=(TaskSpaceDynamics&& other) noexcept;

  int dofs() const noexcept { return n_; }                               ///< n
  int task_rows() const noexcept { return m_; }                          ///< m
  const TaskSpaceOptions& options() const noexcept { return options_; }  ///< as constructed

  /// Recomputes everything from @p M (n×n, symmetric positive definite) and @p J (m×n).
  /// Unchecked sizes (checked by the constructor's n and m in debug builds only).
  TaskSpaceStatus update(const Eigen::Ref<const Eigen::MatrixXd>& M,
                         const Eigen::Ref<const Eigen::MatrixXd>& J) noexcept;

  /// Same, from a `ChainDynamics` after its `update`: its mass matrix and the first m rows of its
  /// Jacobian (m = 3 takes the linear rows, m = 6 the whole pose Jacobian).
  TaskSpaceStatus update(const ChainDynamics& dynamics) noexcept;

  /// Status of the last `update`.
  TaskSpaceStatus status() const noexcept { return status_; }

  /// True when the last successful `update` went through the eigendecomposition (robust) path,
  /// false when the Cholesky fast path certified Λ (always true with status damped).
  bool eigendecomposed() const noexcept { return eigendecomposed_; }

  /// M⁻¹ (n×n), computed on first access after an update.
  const Eigen::MatrixXd& mass_inverse() const noexcept;
  /// Λ (m×m, symmetric positive definite) [kg for linear rows, kg·m² for angular rows].
  const Eigen::MatrixXd& lambda() const noexcept { return Lambda_; }
  /// Λ⁻¹ = J·M⁻¹·Jᵀ as computed (m×m), before flooring.
  const Eigen::MatrixXd& lambda_inverse() const noexcept { return Lambda_inv_; }
  /// J̄ = M⁻¹·Jᵀ·Λ (n×m), computed on first access after an update.
  const Eigen::MatrixXd& jbar() const noexcept;
  /// N = I − J̄·J (n×n), computed on first access after an update; a joint torque τ₀ acts in the
  /// null space as Nᵀ·τ₀.
  const Eigen::MatrixXd& nullspace() const noexcept;

  /// Writes Nᵀ·@p tau0 = τ₀ − Jᵀ·(J̄ᵀ·τ₀) into @p tau (both n, distinct): the part of τ₀ that
  /// produces no task acceleration (without forming N or J̄: J̄ᵀ·τ₀ = Λ·(L⁻¹·Jᵀ)ᵀ·(L⁻¹·τ₀) with
  /// M = L·Lᵀ). Reads only, no cache.
  void project_torque(const Eigen::Ref<const Eigen::VectorXd>& tau0,
                      Eigen::Ref<Eigen::VectorXd> tau) const noexcept;

  /// Eigenvalues of J·M⁻¹·Jᵀ, ascending (m), before flooring (computed on first access after an
  /// update on the fast path).
  const Eigen::VectorXd& eigenvalues() const noexcept;
  /// Smallest singular value of J·M^(−1/2) = √(smallest eigenvalue of J·M⁻¹·Jᵀ); → 0 at a
  /// singularity.
  double min_singular_value() const noexcept;
  /// Condition number of J·M⁻¹·Jᵀ (largest / smallest eigenvalue; +inf when singular).
  double condition() const noexcept;

 private:
  // at most 6×6: fixed-capacity storage keeps the eigen solver from allocating
  using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

  /// Which kernels `update` and `project_torque` run (compile-time sizes or the general ones).
  enum class Kernels { generic, n7_m6, n7_m3, n6_m6, n6_m3 };

  template <int kN, int kM>
  TaskSpaceStatus update_sized(const Eigen::Ref<const Eigen::MatrixXd>& M,
                               const Eigen::Ref<const Eigen::MatrixXd>& J) noexcept;
  template <int kN, int kM>
  void project_sized(const double* tau0, double* tau) const noexcept;
  /// The exact floor test: Λ⁻¹ − floor·I has a Cholesky factorization (uses small_ and
  /// scaled_vectors_ as scratch).
  bool above_floor_exactly() noexcept;
  /// Λ from Λ⁻¹ (in Lambda_inv_) by the eigendecomposition with the floor; true when floored.
  bool eigen_lambda() noexcept;
  /// Fills eigenvalues_ from Lambda_inv_.
  void compute_eigenvalues() const noexcept;

  int n_ = 0;
  int m_ = 0;
  TaskSpaceOptions options_;
  Kernels kernels_ = Kernels::generic;
  double certificate_trace_ = 0.0;  // 1/(2·floor): trace(Λ) at or below it certifies Λ
  TaskSpaceStatus status_ = TaskSpaceStatus::ok;
  bool eigendecomposed_ = true;
  // triangular factors hold the reciprocals of their diagonals (see task_space_kernels.hpp)
  Eigen::MatrixXd chol_;       // n×n, lower Cholesky factor L of M (M = L·Lᵀ)
  Eigen::MatrixXd chol_work_;  // n×n, factorization in progress (swapped in on success)
  Eigen::MatrixXd J_;          // m×n, the task Jacobian of the last update
  Eigen::MatrixXd Y_;          // n×m, L⁻¹·Jᵀ
  Eigen::MatrixXd Lambda_inv_;
  Eigen::MatrixXd Lambda_;
  SmallMatrix small_;           // Λ⁻¹ handed to the eigen solver; on the fast path its factor R
  SmallMatrix scaled_vectors_;  // V·diag(1/λ); on the fast path R⁻¹
  SmallVector scaled_;          // 1 / floored eigenvalues
  // the eigen solver (in the .cpp: Eigen/Eigenvalues stays out of this header)
  struct Solver;
  WorkspacePtr<Solver> solver_;
  // caches filled on first access after an update
  mutable Eigen::MatrixXd MinvJt_;  // n×m, M⁻¹·Jᵀ
  mutable Eigen::MatrixXd Jbar_;
  mutable Eigen::MatrixXd M_inv_;
  mutable Eigen::MatrixXd N_;
  mutable Eigen::VectorXd eigenvalues_;
  mutable bool Jbar_ready_ = true;
  mutable bool M_inv_ready_ = true;
  mutable bool N_ready_ = true;
  mutable bool eigenvalues_ready_ = true;
};

}  // namespace mjarm
