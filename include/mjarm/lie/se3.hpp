#pragma once
/// @file
/// The rigid-motion group SE(3): twists, hat/vee, exp/log, Adjoint, ad, and twist/wrench
/// changes of frame.
///
/// Conventions (linear first everywhere):
/// - se(3) coordinates / twists ξ = [v; ω] (m or m/s; rad or rad/s);
///   ξ^ = [ω̂ v; 0 0] (4×4);
/// - exp(ξ) = [exp(ω), Jl(ω)·v; 0 1] with Jl the SO(3) left Jacobian; log is its inverse with
///   ‖ω‖ ≤ π;
/// - Ad_X = [R, p̂R; 0, R] maps a twist expressed in B to the same motion expressed in A
///   (V_A = Ad_{X_AB} V_B, equivalently (Ad_X ξ)^ = X ξ^ X⁻¹);
/// - ad_ξ = [ω̂, v̂; 0, ω̂], the matrix of the Lie bracket: ad_ξ η = [ξ^, η^]∨;
/// - wrenches F = [f; τ] (N; N·m, torque about the frame's origin) transform with the
///   co-adjoint Ad_X^{−T} = [R, 0; p̂R, R], so that the power Fᵀ·V is frame independent.
///
/// The functions here are the arithmetic of the hot loops: they check nothing (NaN in, NaN
/// out). Numbers from users are checked where they enter: the `Pose` factories, the IK targets
/// and controller references, the Python bindings (a non-finite argument is an `mjarm.Error`).

#include <Eigen/Core>

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm::se3 {

/// 4×4 matrix ξ^ = [ω̂ v; 0 0] of se(3) coordinates ξ = [v; ω].
Eigen::Matrix4d hat(const Vector6d& xi) noexcept;

/// Inverse of hat: [v; ω] from a 4×4 matrix [W v; · ·]; ω from the skew part of W.
Vector6d vee(const Eigen::Matrix4d& xi_hat) noexcept;

/// Exponential map se(3) → SE(3): exp([v; ω]) = [exp(ω), Jl(ω)·v; 0 1].
/// @param xi se(3) coordinates [v; ω] (m; rad), any norm
Pose exp(const Vector6d& xi) noexcept;

/// Logarithm SE(3) → se(3), principal branch (‖ω‖ ≤ π): [Jl⁻¹(ω)·p; log(R)].
/// @param X pose (rotation orthonormal)
/// @return se(3) coordinates [v; ω] (m; rad) with exp(ξ) = X
Vector6d log(const Pose& X) noexcept;

/// Adjoint Ad_{X_AB} = [R, p̂R; 0, R] (6×6): V_A = Ad_{X_AB}·V_B for twists [v; ω].
Matrix6d adjoint(const Pose& X_AB) noexcept;

/// Small adjoint ad_ξ = [ω̂, v̂; 0, ω̂] (6×6): ad_ξ·η = [ξ^, η^]∨ (Lie bracket).
/// @param xi twist or se(3) coordinates [v; ω]
Matrix6d ad(const Vector6d& xi) noexcept;

/// Co-adjoint Ad_{X_AB}^{−T} = [R, 0; p̂R, R] (6×6): F_A = Ad_{X_AB}^{−T}·F_B for wrenches
/// [f; τ]. Note Ad_{X_AB}ᵀ maps the other way, F_B = Ad_{X_AB}ᵀ·F_A.
Matrix6d coadjoint(const Pose& X_AB) noexcept;

/// Changes the frame of a twist: V_A = Ad_{X_AB}·V_B, computed without forming the 6×6 matrix.
/// @param X_AB pose of B in A
/// @param V_B  twist [v; ω] expressed in B (linear velocity of the point at B's origin)
/// @return the same twist expressed in A (linear velocity of the point at A's origin)
Vector6d transform_twist(const Pose& X_AB, const Vector6d& V_B) noexcept;

/// Changes the frame of a wrench: F_A = Ad_{X_AB}^{−T}·F_B, i.e. f_A = R f_B and
/// τ_A = R τ_B + p_AB × (R f_B). Power is preserved: F_Aᵀ·V_A = F_Bᵀ·V_B.
/// @param X_AB pose of B in A
/// @param F_B  wrench [f; τ] expressed in B, torque about B's origin (N; N·m)
/// @return the same wrench expressed in A, torque about A's origin (N; N·m)
Vector6d transform_wrench(const Pose& X_AB, const Vector6d& F_B) noexcept;

}  // namespace mjarm::se3
