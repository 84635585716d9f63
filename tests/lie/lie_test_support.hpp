#pragma once
/// @file
/// What the Lie-group tests share: π, the largest entry of a matrix, random unit vectors and
/// random twists.

#include <Eigen/Core>
#include <numbers>
#include <random>

#include "mjarm/lie/types.hpp"

namespace mjarm::test {

inline constexpr double kPi = std::numbers::pi;

/// max |mᵢⱼ|
template <typename Derived>
double max_abs(const Eigen::MatrixBase<Derived>& m) {
  return m.cwiseAbs().maxCoeff();
}

/// A direction uniform on the unit sphere.
inline Eigen::Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

/// ξ = [v; ω] with ‖ω‖ uniform in [0, max_angle) and ‖v‖ uniform in [0, 2).
inline Vector6d random_twist(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> angle(0.0, max_angle), length(0.0, 2.0);
  Vector6d xi;
  xi << length(rng) * random_unit(rng), angle(rng) * random_unit(rng);
  return xi;
}

}  // namespace mjarm::test
