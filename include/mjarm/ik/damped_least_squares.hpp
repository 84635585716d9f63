#pragma once
/// @file
/// Damped least squares: the regularised pseudo-inverse step every local IK solver is built on,
/// with its own preallocated workspace.
///
/// For a task Jacobian J (m×n) and a task error e (m), the damped least-squares step
///   Δq = Jᵀ(JJᵀ + λ²I)⁻¹e = argmin ‖JΔq − e‖² + λ²‖Δq‖²
/// stays bounded at singularities (‖Δq‖ ≤ ‖e‖/(2λ)). The same factorisation with a tiny damping
/// ε² gives the (near-exact) null-space projector N = I − Jᵀ(JJᵀ + ε²I)⁻¹J whose eigenvalues
/// ε²/(σᵢ² + ε²) all lie in [0, 1], so projected secondary terms never blow up.

#include <Eigen/Core>

#include "mjarm/workspace_ptr.hpp"

namespace mjarm {

/// Workspace for damped least-squares steps and null-space projections of m×n Jacobians.
/// Every method allocates nothing (sizes are fixed at construction).
class DampedLeastSquares {
 public:
  /// Workspace for Jacobians of @p rows task rows and @p cols joints.
  /// @throws Error when a size is not positive.
  DampedLeastSquares(int rows, int cols);
  ~DampedLeastSquares();
  DampedLeastSquares(const DampedLeastSquares& other);
  DampedLeastSquares& operator=(const DampedLeastSquares& other);
  DampedLeastSquares(DampedLeastSquares&& other) noexcept;
  DampedLeastSquares& operator=(DampedLeastSquares&& other) noexcept;

  int rows() const noexcept { return static_cast<int>(A_.rows()); }
  int cols() const noexcept { return static_cast<int>(y_n_.size()); }

  /// Forms and factors JJᵀ + damping_sq·I. Must precede `step` and `project`/`projector`.
  /// @param J task Jacobian (rows × cols)
  /// @param damping_sq λ² > 0 (units of J squared)
  /// @return false when the factorisation failed (non-finite input)
  bool factor(const Eigen::Ref<const Eigen::MatrixXd>& J, double damping_sq) noexcept;

  /// Δq = Jᵀ(JJᵀ + λ²I)⁻¹e with the J and λ of the last `factor` (cols entries).
  /// @param J the Jacobian given to `factor` @param e task error (rows) @param dq output (cols)
  void step(const Eigen::Ref<const Eigen::MatrixXd>& J, const Eigen::Ref<const Eigen::VectorXd>& e,
            Eigen::Ref<Eigen::VectorXd> dq) noexcept;

  /// out = v − Jᵀ(JJᵀ + λ²I)⁻¹J·v: @p v with the part that moves the task removed (cols).
  /// @p v and @p out may alias.
  void project(const Eigen::Ref<const Eigen::MatrixXd>& J,
               const Eigen::Ref<const Eigen::VectorXd>& v,
               Eigen::Ref<Eigen::VectorXd> out) noexcept;

  /// P = Jᵀ(JJᵀ + λ²I)⁻¹J (cols × cols), the damped projector onto the task's row space.
  void row_space_projector(const Eigen::Ref<const Eigen::MatrixXd>& J,
                           Eigen::Ref<Eigen::MatrixXd> P) noexcept;

 private:
  struct Factor;                     // its Cholesky factor (in the .cpp: Eigen/Cholesky)
  Eigen::MatrixXd A_;                // JJᵀ + λ²I (rows × rows)
  WorkspacePtr<Factor> llt_;
  Eigen::VectorXd y_m_;              // rows-sized scratch
  Eigen::VectorXd y_n_;              // cols-sized scratch
  Eigen::MatrixXd X_;                // (JJᵀ + λ²I)⁻¹J (rows × cols)
};

}  // namespace mjarm
