#pragma once
/// @file
/// Fixed-size Eigen types shared by the Lie-group math and everything above it.
///
/// Conventions used throughout mjarm:
/// - a twist is `[v; ω]` (linear velocity first, then angular velocity), units m/s and rad/s;
/// - a wrench is `[f; τ]` (force first, then torque), units N and N·m;
/// - an se(3) coordinate vector ξ = `[v; ω]` follows the same linear-first order.

#include <Eigen/Core>

namespace mjarm {

/// A 6-vector: a twist `[v; ω]`, a wrench `[f; τ]` or se(3) coordinates, linear part first.
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// A 6×6 matrix acting on linear-first 6-vectors (Adjoint, ad, SE(3) Jacobians).
using Matrix6d = Eigen::Matrix<double, 6, 6>;

}  // namespace mjarm
