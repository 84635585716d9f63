#pragma once
/// @file
/// Log-based pose errors for inverse kinematics and pose control, and the Jacobians that relate
/// their rates to the twist of the moving frame E (the target T is fixed).
///
/// Body (local) error, expressed in E:
///   e_E = log(X_EW·X_WT) = log(X_ET),   so that X_WT = X_WE·exp(e_E).
///   If E moves with body twist V_E (expressed in E, X_WE⁺ = X_WE·exp(V_E·dt)), then exactly
///   ė_E = −Jlog(e_E)·V_E  with  Jlog(e) = se3::left_jacobian_inverse(e) = dexp⁻¹(e).
/// World-aligned error, expressed in E[W] (origin at E, axes of W):
///   e_W = blockdiag(R_WE, R_WE)·e_E,  so that X_WT = T(p_WE)·exp(e_W)·T(−p_WE)·X_WE.
///   If V_E^W = [ṗ_WE; ω_WE] is E's world-aligned twist (Jacobian J_{E[W]}·q̇), then exactly
///   ė_W = −(Jl⁻¹(e_W) + ad(e_W)·diag(0, I))·V_E^W, i.e. the linear part of V_E^W goes through
///   the left and the angular part through the right inverse Jacobian (Jr⁻¹ − Jl⁻¹ = ad).
/// Both Jacobians tend to the identity as the error goes to zero, so e ≈ −V·dt to first order.

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Body pose error e_E = log(X_EW·X_WT) = [v; ω] (m; rad), expressed in frame E.
/// Zero iff X_WE == X_WT; ‖ω‖ ≤ π.
/// @param X_WE pose of the moving frame E (end effector) in W
/// @param X_WT pose of the target frame T in W
Vector6d log_error(const Pose& X_WE, const Pose& X_WT) noexcept;

/// World-aligned pose error e_W = blockdiag(R_WE, R_WE)·log(X_EW·X_WT) (m; rad), expressed in
/// E[W]: the same error twist with its components along W's axes (origin still at E).
/// @param X_WE pose of the moving frame E in W
/// @param X_WT pose of the target frame T in W
Vector6d log_error_world_aligned(const Pose& X_WE, const Pose& X_WT) noexcept;

/// Jlog for the body error: ė_E = −Jlog(e_E)·V_E with V_E the body twist of E (6×6).
/// Equals se3::left_jacobian_inverse(e_E).
/// @param e_E body error from log_error (‖ω‖ < 2π)
/// @throws mjarm::Error if ‖ω‖ ≥ 2π
Matrix6d log_error_jacobian(const Vector6d& e_E);

/// Jlog for the world-aligned error: ė_W = −Jlog(e_W)·V_E^W with V_E^W = [ṗ_WE; ω_WE] (6×6).
/// Equals Jl⁻¹(e_W) + ad(e_W)·diag(0, I) (= Jl⁻¹ on the linear columns, Jr⁻¹ on the angular).
/// @param e_W world-aligned error from log_error_world_aligned (‖ω‖ < 2π)
/// @throws mjarm::Error if ‖ω‖ ≥ 2π
Matrix6d log_error_world_aligned_jacobian(const Vector6d& e_W);

}  // namespace mjarm
