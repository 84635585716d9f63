#pragma once
/// @file
/// Left and right Jacobians of SE(3) (dexp), their inverses, and their time derivatives.
///
/// For ξ = [v; ω] (linear first):
/// - left Jacobian Jl(ξ) = dexp: exp(ξ + δ) ≈ exp(Jl(ξ)·δ)·exp(ξ) (perturbation on the left, in
///   the fixed frame);  Jl(ξ) = [Jl(ω), Q(v, ω); 0, Jl(ω)] with the SO(3) left Jacobian Jl(ω)
///   and the rotation-translation coupling block (Barfoot; Sola et al.)
///     Q(v, ω) = ½v̂ + b (ω̂v̂ + v̂ω̂ + ω̂v̂ω̂) + c (ω̂²v̂ + v̂ω̂² − 3ω̂v̂ω̂) + d (ω̂v̂ω̂² + ω̂²v̂ω̂),
///     b = (θ − sin θ)/θ³, c = (θ² + 2cos θ − 2)/(2θ⁴), d = (2θ − 3sin θ + θcos θ)/(2θ⁵);
/// - right Jacobian Jr(ξ) = Jl(−ξ): exp(ξ + δ) ≈ exp(ξ)·exp(Jr(ξ)·δ) (body frame); the body
///   twist of X(t) = exp(ξ(t)) is Jr(ξ)·ξ̇, the spatial twist Jl(ξ)·ξ̇;
/// - inverses: Jl⁻¹(ξ) = [Jl⁻¹(ω), −Jl⁻¹(ω) Q Jl⁻¹(ω); 0, Jl⁻¹(ω)], Jr⁻¹(ξ) = Jl⁻¹(−ξ). They
///   exist for ‖ω‖ < 2π only; the inverse family throws mjarm::Error for ‖ω‖ ≥ 2π.
/// Time derivatives take ξ(t), ξ̇(t) and return d/dt of the 6×6 matrix in closed form (Taylor
/// series near ω = 0, see lie/coefficients.hpp), including the derivative of Q.

#include <Eigen/Core>

#include "mjarm/lie/types.hpp"

namespace mjarm::se3 {

/// Coupling block Q(v, ω) of the SE(3) left Jacobian (3×3, units of v).
/// @param v linear part (m) @param w rotation vector (rad)
Eigen::Matrix3d q_block(const Eigen::Vector3d& v, const Eigen::Vector3d& w) noexcept;

/// d/dt Q(v(t), ω(t)) (3×3).
/// @param v linear part v(t) @param w rotation vector ω(t) (rad)
/// @param v_dot v̇(t) @param w_dot ω̇(t) (rad/s)
Eigen::Matrix3d q_block_derivative(const Eigen::Vector3d& v, const Eigen::Vector3d& w,
                                   const Eigen::Vector3d& v_dot,
                                   const Eigen::Vector3d& w_dot) noexcept;

/// Left Jacobian Jl(ξ) (dexp, 6×6). @param xi [v; ω]
Matrix6d left_jacobian(const Vector6d& xi) noexcept;

/// Right Jacobian Jr(ξ) = Jl(−ξ) (6×6). @param xi [v; ω]
Matrix6d right_jacobian(const Vector6d& xi) noexcept;

/// Inverse left Jacobian Jl⁻¹(ξ) (dexp⁻¹, 6×6).
/// @param xi [v; ω] with ‖ω‖ < 2π
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Matrix6d left_jacobian_inverse(const Vector6d& xi);

/// Inverse right Jacobian Jr⁻¹(ξ) = Jl⁻¹(−ξ) (6×6).
/// @param xi [v; ω] with ‖ω‖ < 2π
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Matrix6d right_jacobian_inverse(const Vector6d& xi);

/// d/dt Jl(ξ(t)) (6×6). @param xi ξ(t) = [v; ω] @param xi_dot ξ̇(t)
Matrix6d left_jacobian_derivative(const Vector6d& xi, const Vector6d& xi_dot) noexcept;

/// d/dt Jr(ξ(t)) (6×6). @param xi ξ(t) = [v; ω] @param xi_dot ξ̇(t)
Matrix6d right_jacobian_derivative(const Vector6d& xi, const Vector6d& xi_dot) noexcept;

/// d/dt Jl⁻¹(ξ(t)) (6×6).
/// @param xi ξ(t) = [v; ω] with ‖ω‖ < 2π @param xi_dot ξ̇(t)
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Matrix6d left_jacobian_inverse_derivative(const Vector6d& xi, const Vector6d& xi_dot);

/// d/dt Jr⁻¹(ξ(t)) (6×6).
/// @param xi ξ(t) = [v; ω] with ‖ω‖ < 2π @param xi_dot ξ̇(t)
/// @throws mjarm::Error if ‖ω‖ ≥ 2π or ω is not finite
Matrix6d right_jacobian_inverse_derivative(const Vector6d& xi, const Vector6d& xi_dot);

}  // namespace mjarm::se3
