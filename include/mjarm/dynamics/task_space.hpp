#pragma once
/// @file
/// `TaskSpaceDynamics`: operational-space inertia Λ, the dynamically consistent generalized
/// inverse J̄ and the null-space projector N of one task Jacobian, with a bounded path near
/// singularities.

#include <Eigen/Core>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "mjarm/dynamics/chain_dynamics.hpp"

namespace mjarm {

/// Tuning of the robust Λ path.
struct TaskSpaceOptions {
  /// Floor on the eigenvalues of Λ⁻¹ = J·M⁻¹·Jᵀ [1/kg for linear rows, 1/(kg·m²) for angular
  /// rows]: eigenvalues below it are replaced by it, so no direction of Λ exceeds 1/floor
  /// (1000 kg or kg·m² by default). Away from singularities (every eigenvalue above the floor)
  /// Λ is the exact inverse. Must be > 0 and finite.
  double min_eigenvalue = 1e-3;
};

/// Outcome of one `TaskSpaceDynamics::update`.
enum class TaskSpaceStatus {
  ok,                    ///< Λ is the exact inverse of J·M⁻¹·Jᵀ
  damped,                ///< near a singularity: at least one eigenvalue was floored
  not_positive_definite  ///< M failed its Cholesky factorization; outputs are left unchanged
};

/// Human name of a status ("ok", "damped", "not_positive_definite").
const char* to_string(TaskSpaceStatus status) noexcept;

/// Task-space (operational-space) dynamics for an m×n task Jacobian J (1 ≤ m ≤ 6) and an n×n
/// joint-space inertia M:
///
///     Λ = (J·M⁻¹·Jᵀ)⁻¹          m×m   task-space inertia [kg, kg·m²]
///     J̄ = M⁻¹·Jᵀ·Λ              n×m   dynamically consistent generalized inverse
///     N = I − J̄·J               n×n   null-space projector of joint velocities; Nᵀ for torques
///
/// Λ⁻¹ is eigendecomposed (V·diag(λ)·Vᵀ) and Λ = V·diag(1/max(λ, floor))·Vᵀ: exact away from
/// singularities. Always: M·N = Nᵀ·M and N·M⁻¹ = M⁻¹·Nᵀ (N is self-adjoint in the M inner
/// product).
/// When no eigenvalue is floored (status ok) also: Λ·J·M⁻¹·Jᵀ = I, J·J̄ = I, N·J̄ = 0, J·N = 0,
/// N² = N. When floored (status damped) they hold only along the unfloored eigen-directions.
///
/// All buffers are allocated in the constructor; `update` allocates nothing and never throws.
class TaskSpaceDynamics {
 public:
  /// @param dofs n, the number of joint-space dofs (≥ 1).
  /// @param task_rows m, the number of task rows (1..6): 6 for a full pose task, 3 for position.
  /// @throws Error when a size is out of range or options.min_eigenvalue is not > 0 and finite.
  TaskSpaceDynamics(int dofs, int task_rows = 6, TaskSpaceOptions options = {});

  int dofs() const noexcept { return n_; }        ///< n
  int task_rows() const noexcept { return m_; }   ///< m
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

  /// M⁻¹ (n×n).
  const Eigen::MatrixXd& mass_inverse() const noexcept { return M_inv_; }
  /// Λ (m×m, symmetric positive definite) [kg for linear rows, kg·m² for angular rows].
  const Eigen::MatrixXd& lambda() const noexcept { return Lambda_; }
  /// Λ⁻¹ = J·M⁻¹·Jᵀ as computed (m×m), before flooring.
  const Eigen::MatrixXd& lambda_inverse() const noexcept { return Lambda_inv_; }
  /// J̄ = M⁻¹·Jᵀ·Λ (n×m).
  const Eigen::MatrixXd& jbar() const noexcept { return Jbar_; }
  /// N = I − J̄·J (n×n); a joint torque τ₀ acts in the null space as Nᵀ·τ₀.
  const Eigen::MatrixXd& nullspace() const noexcept { return N_; }

  /// Writes Nᵀ·@p tau0 into @p tau (both n): the part of τ₀ that produces no task acceleration.
  void project_torque(const Eigen::Ref<const Eigen::VectorXd>& tau0,
                      Eigen::Ref<Eigen::VectorXd> tau) const noexcept;

  /// Eigenvalues of J·M⁻¹·Jᵀ, ascending (m), before flooring.
  const Eigen::VectorXd& eigenvalues() const noexcept { return eigenvalues_; }
  /// Smallest singular value of J·M^(−1/2) = √(smallest eigenvalue of J·M⁻¹·Jᵀ); → 0 at a
  /// singularity.
  double min_singular_value() const noexcept;
  /// Condition number of J·M⁻¹·Jᵀ (largest / smallest eigenvalue; +inf when singular).
  double condition() const noexcept;

 private:
  // at most 6×6: fixed-capacity storage keeps the eigen solver off the heap
  using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

  int n_ = 0;
  int m_ = 0;
  TaskSpaceOptions options_;
  TaskSpaceStatus status_ = TaskSpaceStatus::ok;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::SelfAdjointEigenSolver<SmallMatrix> eigen_;
  SmallMatrix small_;  // Λ⁻¹ handed to the eigen solver
  SmallMatrix scaled_vectors_;  // V·diag(1/λ)
  Eigen::MatrixXd M_inv_;
  Eigen::MatrixXd MinvJt_;  // n×m
  Eigen::MatrixXd Lambda_inv_;
  Eigen::MatrixXd Lambda_;
  Eigen::MatrixXd Jbar_;
  Eigen::MatrixXd N_;
  Eigen::VectorXd eigenvalues_;
  SmallVector scaled_;  // 1 / floored eigenvalues
};

}  // namespace mjarm
