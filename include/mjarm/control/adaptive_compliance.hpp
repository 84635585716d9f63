#pragma once
/// @file
/// `AdaptiveCompliance`: the force-adaptive stiffness and the reference damping of HQP-AC,
/// K_r = clip((1 − α(F))·K0, r_min·K0, K0) and D_r = Λ^½·K_r^½ + K_r^½·Λ^½.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/workspace_ptr.hpp"

namespace mjarm {

/// Settings of `AdaptiveCompliance`.
struct AdaptiveComplianceOptions {
  /// K0: the nominal task stiffness [N/m; N·m/rad] (6×6, symmetric positive definite; rows
  /// [x, y, z, rx, ry, rz] in world axes). Note that α(0) = ½: in free space K_r = K0/2.
  Matrix6d stiffness = (Vector6d() << 1500, 1500, 1500, 150, 150, 150).finished().asDiagonal();
  double deadband = 2.0;             ///< forces below it do not soften [N] (≥ 0)
  double force_gain = 1.0;           ///< k_α of the sigmoid [1/N] (> 0)
  double min_stiffness_ratio = 0.3;  ///< r_min: K_r ≥ r_min·K0 (in (0, 1])
  /// Floor on the eigenvalues of Λ⁻¹ when taking Λ^½ [1/kg, 1/(kg·m²)] (> 0): as
  /// `TaskSpaceOptions::min_eigenvalue`, so that Λ^½ stays bounded near singularities.
  double min_eigenvalue = 1e-3;
};

// the stiffness matrix K0 is checked by hand (symmetric positive definite)
constexpr auto declared_fields(const AdaptiveComplianceOptions*) {
  using S = AdaptiveComplianceOptions;
  return declare<S>(
      "hqp-ac",
      field("deadband", &S::deadband, "N", Range::non_negative(), "forces below it do not soften"),
      field("force_gain", &S::force_gain, "1/N", Range::positive(), "k_α of the sigmoid"),
      field("min_stiffness_ratio", &S::min_stiffness_ratio, "", Range::open_closed(0.0, 1.0),
            "r_min: K_r ≥ r_min·K0"),
      field("min_eigenvalue", &S::min_eigenvalue, "1/kg or 1/(kg·m²)", Range::positive(),
            "floor on the eigenvalues of Λ⁻¹ when taking Λ^½"));
}

/// Force-adaptive compliance of one end effector. Each `update` with the measured wrench
/// F = [f; n] (N; N·m) and the task-space inverse inertia Λ⁻¹ = J·M⁻¹·Jᵀ:
///
///     F_eff = max(‖[f; n]‖ − deadband, 0)
///     α     = 1 / (1 + exp(−k_α·F_eff))                          ∈ [½, 1)
///     s     = clip(1 − α, r_min, 1),  K_r = s·K0,  K_r^½ = √s·K0^½
///     Λ^½   = V·diag(1/√max(μ_i, floor))·Vᵀ                     (Λ⁻¹ = V·diag(μ)·Vᵀ)
///     D_r   = Λ^½·K_r^½ + K_r^½·Λ^½
///
/// D_r is symmetric; for commuting Λ and K it is the critical damping 2·(Λ·K_r)^½ of
/// Λ·ë + D_r·ė + K_r·e = 0. It need not be positive definite when Λ and K0 do not commute (an
/// anisotropic K0 with a coupled Λ): `damping_min_eigenvalue` reports it. Allocates nothing
/// after construction; never throws after construction.
class AdaptiveCompliance {
 public:
  /// @throws Error when K0 is not symmetric positive definite or finite (naming its
  ///         eigenvalues), or a scalar option is out of range.
  explicit AdaptiveCompliance(const AdaptiveComplianceOptions& options = {});
  ~AdaptiveCompliance();
  AdaptiveCompliance(const AdaptiveCompliance& other);
  AdaptiveCompliance& operator=(const AdaptiveCompliance& other);
  AdaptiveCompliance(AdaptiveCompliance&& other) noexcept;
  AdaptiveCompliance& operator=(AdaptiveCompliance&& other) noexcept;

  const AdaptiveComplianceOptions& options() const noexcept { return options_; }

  /// Recomputes K_r, D_r and Λ^½ for the wrench norm of @p F and @p Lambda_inv (6×6, symmetric
  /// positive semi-definite; unchecked). A non-finite wrench counts as zero force.
  void update(const Vector6d& F, const Eigen::Ref<const Eigen::MatrixXd>& Lambda_inv) noexcept;

  double effective_force() const noexcept { return force_; }  ///< F_eff [N]
  double alpha() const noexcept { return alpha_; }            ///< α ∈ [½, 1)
  double scale() const noexcept { return scale_; }            ///< s = K_r/K0 ∈ [r_min, ½]
  const Matrix6d& stiffness() const noexcept { return K_; }   ///< K_r
  const Matrix6d& damping() const noexcept { return D_; }     ///< D_r
  const Matrix6d& lambda_sqrt() const noexcept { return Lambda_sqrt_; }         ///< Λ^½
  const Matrix6d& nominal_stiffness_sqrt() const noexcept { return K0_sqrt_; }  ///< K0^½
  /// Smallest eigenvalue of D_r (an eigen solve; for diagnostics, not part of `update`).
  double damping_min_eigenvalue() const noexcept;

 private:
  AdaptiveComplianceOptions options_;
  Matrix6d K0_sqrt_ = Matrix6d::Identity();
  struct Solver;  // the eigen solver of Λ⁻¹ (in the .cpp: Eigen/Eigenvalues)
  WorkspacePtr<Solver> eigen_;
  double force_ = 0.0;
  double alpha_ = 0.5;
  double scale_ = 0.5;
  Matrix6d K_ = Matrix6d::Zero();
  Matrix6d D_ = Matrix6d::Zero();
  Matrix6d Lambda_sqrt_ = Matrix6d::Zero();
};

}  // namespace mjarm
