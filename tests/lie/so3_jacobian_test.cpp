#include "mjarm/lie/so3_jacobian.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <numbers>
#include <random>

#include "lie/lie_test_support.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm::so3 {
namespace {

using test::kPi;
using test::max_abs;
using test::random_unit;

// columns: central differences of δ ↦ log(exp(ω + hδ)·exp(ω)ᵀ) (left) or
// log(exp(ω)ᵀ·exp(ω + hδ)) (right)
Eigen::Matrix3d fd_jacobian(const Eigen::Vector3d& w, bool left) {
  const Eigen::Matrix3d R = exp(w);
  const auto f = [&](const Eigen::VectorXd& d) -> Eigen::Vector3d {
    const Eigen::Matrix3d Rd = exp(w + d);
    return left ? log(Rd * R.transpose()) : log(R.transpose() * Rd);
  };
  return finite_difference_jacobian(f, Eigen::Vector3d::Zero());
}

// central difference of t ↦ f(ω + t·ω̇) at t = 0
Eigen::Matrix3d fd_rate(const std::function<Eigen::Matrix3d(const Eigen::Vector3d&)>& f,
                        const Eigen::Vector3d& w, const Eigen::Vector3d& w_dot) {
  return finite_difference_derivative([&](double t) { return f(w + t * w_dot); }, 0.0, 1e-5);
}

TEST(So3Jacobian, LeftAndRightMatchFiniteDifferencesOfExp) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 3.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d w = angle(rng) * random_unit(rng);
    EXPECT_LT(max_abs(left_jacobian(w) - fd_jacobian(w, true)), 1e-8) << w.transpose();
    EXPECT_LT(max_abs(right_jacobian(w) - fd_jacobian(w, false)), 1e-8) << w.transpose();
  }
  for (double theta : {0.0, 1e-9, 1e-6, 0.999, 1.001}) {
    const Eigen::Vector3d w = theta * random_unit(rng);
    EXPECT_LT(max_abs(left_jacobian(w) - fd_jacobian(w, true)), 1e-8) << theta;
  }
}

TEST(So3Jacobian, RelationsBetweenLeftAndRight) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> angle(0.0, 6.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d w = angle(rng) * random_unit(rng);
    const Eigen::Matrix3d Jl = left_jacobian(w), Jr = right_jacobian(w);
    EXPECT_LT(max_abs(Jr - left_jacobian(-w)), 1e-15);
    EXPECT_LT(max_abs(Jr - Jl.transpose()), 1e-14);
    // Jl = R·Jr
    EXPECT_LT(max_abs(Jl - exp(w) * Jr), 1e-13);
    EXPECT_LT(max_abs(Jl * w - w), 1e-13);  // ω is a fixed vector of both
  }
}

TEST(So3Jacobian, InverseTimesJacobianIsIdentity) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi - 1e-3);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d w = angle(rng) * random_unit(rng);
    const Eigen::Matrix3d Jl = left_jacobian(w), Jr = right_jacobian(w);
    const double tol = 1e-12 * Jl.inverse().norm();
    EXPECT_LT(max_abs(left_jacobian_inverse(w) * Jl - I), tol) << w.norm();
    EXPECT_LT(max_abs(right_jacobian_inverse(w) * Jr - I), tol) << w.norm();
  }
  for (double theta : {0.0, 1e-9, 1e-6, 1.0, kPi}) {
    const Eigen::Vector3d w = theta * random_unit(rng);
    EXPECT_LT(max_abs(left_jacobian_inverse(w) * left_jacobian(w) - I), 1e-14) << theta;
  }
}

TEST(So3Jacobian, TimeDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> angle(0.0, 6.0);
  const auto check = [](const Eigen::Vector3d& w, const Eigen::Vector3d& w_dot) {
    const double scale = 1.0 + left_jacobian_inverse(w).norm();
    EXPECT_LT(max_abs(left_jacobian_derivative(w, w_dot) -
                      fd_rate([](const Eigen::Vector3d& x) { return left_jacobian(x); }, w, w_dot)),
              1e-8)
        << w.transpose();
    EXPECT_LT(
        max_abs(right_jacobian_derivative(w, w_dot) -
                fd_rate([](const Eigen::Vector3d& x) { return right_jacobian(x); }, w, w_dot)),
        1e-8)
        << w.transpose();
    EXPECT_LT(max_abs(left_jacobian_inverse_derivative(w, w_dot) -
                      fd_rate([](const Eigen::Vector3d& x) { return left_jacobian_inverse(x); }, w,
                              w_dot)),
              1e-8 * scale * scale)
        << w.transpose();
    EXPECT_LT(max_abs(right_jacobian_inverse_derivative(w, w_dot) -
                      fd_rate([](const Eigen::Vector3d& x) { return right_jacobian_inverse(x); }, w,
                              w_dot)),
              1e-8 * scale * scale)
        << w.transpose();
  };
  for (int i = 0; i < 100; ++i) check(angle(rng) * random_unit(rng), 2.0 * random_unit(rng));
  // near zero (including through zero) and around the series/closed-form switch
  for (double theta : {0.0, 1e-9, 1e-6, 1e-3, 0.99999, 1.0, 1.00001, kPi, 2 * kPi - 0.3}) {
    check(theta * random_unit(rng), random_unit(rng));
  }
}

TEST(So3Jacobian, InverseDerivativeIsMinusInverseTimesDerivativeTimesInverse) {
  std::mt19937 rng(15);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d w = 2.5 * random_unit(rng), w_dot = random_unit(rng);
    const Eigen::Matrix3d A = left_jacobian_inverse(w);
    EXPECT_LT(max_abs(left_jacobian_inverse_derivative(w, w_dot) +
                      A * left_jacobian_derivative(w, w_dot) * A),
              1e-13);
  }
}

TEST(So3Jacobian, InverseDomainIsBelowTwoPi) {
  const Eigen::Vector3d u = Eigen::Vector3d(1, 2, 3).normalized();
  const Eigen::Vector3d w_dot(0.1, 0.2, 0.3);
  const Eigen::Vector3d inside = (2 * kPi - 1e-6) * u;
  EXPECT_NO_THROW(left_jacobian_inverse(inside));
  EXPECT_TRUE(left_jacobian_inverse(inside).allFinite());
  for (const Eigen::Vector3d& w :
       {Eigen::Vector3d(2 * kPi * u), Eigen::Vector3d(7.0 * u), Eigen::Vector3d(NAN, 0.0, 0.0)}) {
    EXPECT_THROW(left_jacobian_inverse(w), Error);
    EXPECT_THROW(right_jacobian_inverse(w), Error);
    EXPECT_THROW(left_jacobian_inverse_derivative(w, w_dot), Error);
    EXPECT_THROW(right_jacobian_inverse_derivative(w, w_dot), Error);
  }
  // the forward Jacobian is defined (and singular) at 2π: no throw
  EXPECT_NO_THROW(left_jacobian(2 * kPi * u));
  EXPECT_NEAR(left_jacobian(2 * kPi * u).determinant(), 0.0, 1e-12);
}

}  // namespace
}  // namespace mjarm::so3
