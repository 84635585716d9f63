#pragma once
/// @file
/// Left and right Jacobians of SO(3) (dexp), their inverses, and their time derivatives.
///
/// Conventions (θ = ‖ω‖, ω̂ = so3::hat(ω)):
/// - left Jacobian Jl(ω) = dexp: exp(ω + δ) ≈ exp(Jl(ω)·δ)·exp(ω) (perturbation on the left,
///   i.e. expressed in the fixed/world frame),
///   Jl(ω) = I + ((1 − cos θ)/θ²) ω̂ + ((θ − sin θ)/θ³) ω̂²;
/// - right Jacobian Jr(ω): exp(ω + δ) ≈ exp(ω)·exp(Jr(ω)·δ) (perturbation on the right, in the
///   body frame); Jr(ω) = Jl(−ω) = Jl(ω)ᵀ;
/// - the body angular velocity of R(t) = exp(ω(t)) is Jr(ω)·ω̇, the spatial one Jl(ω)·ω̇;
/// - inverses: Jl⁻¹(ω) = I − ½ω̂ + (1/θ² − cot(θ/2)/(2θ)) ω̂², Jr⁻¹(ω) = Jl⁻¹(−ω). They exist
///   for θ < 2π only; the inverse family throws mjarm::Error for θ ≥ 2π (or non-finite ω).
/// Time derivatives take ω(t) and ω̇(t) and return d/dt of the 3×3 matrix, in closed form
/// (Taylor series near θ = 0, see lie/coefficients.hpp).

#include <Eigen/Core>

namespace mjarm::so3 {

/// Left Jacobian Jl(ω) (dexp, 3×3, dimensionless). @param w rotation vector (rad)
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& w) noexcept;

/// Right Jacobian Jr(ω) = Jl(−ω) (3×3). @param w rotation vector (rad)
Eigen::Matrix3d right_jacobian(const Eigen::Vector3d& w) noexcept;

/// Inverse left Jacobian Jl⁻¹(ω) (dexp⁻¹, 3×3).
/// @param w rotation vector (rad), ‖ω‖ < 2π
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Eigen::Matrix3d left_jacobian_inverse(const Eigen::Vector3d& w);

/// Inverse right Jacobian Jr⁻¹(ω) = Jl⁻¹(−ω) (3×3).
/// @param w rotation vector (rad), ‖ω‖ < 2π
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Eigen::Matrix3d right_jacobian_inverse(const Eigen::Vector3d& w);

/// d/dt Jl(ω(t)) (3×3, 1/s).
/// @param w     rotation vector ω(t) (rad)
/// @param w_dot its time derivative ω̇(t) (rad/s)
Eigen::Matrix3d left_jacobian_derivative(const Eigen::Vector3d& w,
                                         const Eigen::Vector3d& w_dot) noexcept;

/// d/dt Jr(ω(t)) (3×3, 1/s). @param w ω(t) (rad) @param w_dot ω̇(t) (rad/s)
Eigen::Matrix3d right_jacobian_derivative(const Eigen::Vector3d& w,
                                          const Eigen::Vector3d& w_dot) noexcept;

/// d/dt Jl⁻¹(ω(t)) (3×3, 1/s).
/// @param w     rotation vector ω(t) (rad), ‖ω‖ < 2π
/// @param w_dot its time derivative ω̇(t) (rad/s)
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Eigen::Matrix3d left_jacobian_inverse_derivative(const Eigen::Vector3d& w,
                                                 const Eigen::Vector3d& w_dot);

/// d/dt Jr⁻¹(ω(t)) (3×3, 1/s).
/// @param w     rotation vector ω(t) (rad), ‖ω‖ < 2π
/// @param w_dot its time derivative ω̇(t) (rad/s)
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Eigen::Matrix3d right_jacobian_inverse_derivative(const Eigen::Vector3d& w,
                                                  const Eigen::Vector3d& w_dot);

}  // namespace mjarm::so3
