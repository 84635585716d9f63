#include "mjarm/lie/se3_jacobian.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <numbers>
#include <random>
#include <string>

#include "lie/lie_test_support.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/so3_jacobian.hpp"

namespace mjarm::se3 {
namespace {

using test::kPi;
using test::max_abs;
using test::random_twist;
using test::random_unit;

Vector6d twist(const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  Vector6d xi;
  xi << v, w;
  return xi;
}

// columns: central differences of δ ↦ log(exp(ξ + hδ)·exp(ξ)⁻¹) (left) or
// log(exp(ξ)⁻¹·exp(ξ + hδ)) (right)
Matrix6d fd_jacobian(const Vector6d& xi, bool left) {
  const Pose X_inv = exp(xi).inverse();
  const auto f = [&](const Eigen::VectorXd& d) -> Vector6d {
    const Pose Xd = exp(xi + d);
    return left ? log(Xd * X_inv) : log(X_inv * Xd);
  };
  return finite_difference_jacobian(f, Vector6d::Zero());
}

// central difference of t ↦ f(ξ + t·ξ̇) at t = 0
Matrix6d fd_rate(const std::function<Matrix6d(const Vector6d&)>& f, const Vector6d& xi,
                 const Vector6d& xi_dot) {
  return finite_difference_derivative([&](double t) { return f(xi + t * xi_dot); }, 0.0, 1e-5);
}

TEST(Se3Jacobian, LeftAndRightMatchFiniteDifferencesOfExp) {
  std::mt19937 rng(51);
  for (int i = 0; i < 100; ++i) {
    const Vector6d xi = random_twist(rng, 3.0);
    EXPECT_LT(max_abs(left_jacobian(xi) - fd_jacobian(xi, true)), 1e-8) << xi.transpose();
    EXPECT_LT(max_abs(right_jacobian(xi) - fd_jacobian(xi, false)), 1e-8) << xi.transpose();
  }
  for (double theta : {0.0, 1e-9, 1e-6, 0.999, 1.001}) {
    const Vector6d xi = twist(random_unit(rng), theta * random_unit(rng));
    EXPECT_LT(max_abs(left_jacobian(xi) - fd_jacobian(xi, true)), 1e-8) << theta;
    EXPECT_LT(max_abs(right_jacobian(xi) - fd_jacobian(xi, false)), 1e-8) << theta;
  }
}

TEST(Se3Jacobian, LeftJacobianIsTheSeriesInAd) {
  // Jl(ξ) = Σ_k ad_ξ^k / (k+1)!, an independent check of the Q block
  std::mt19937 rng(52);
  for (int i = 0; i < 50; ++i) {
    const Vector6d xi = random_twist(rng, 2.0);
    const Matrix6d A = ad(xi);
    Matrix6d term = Matrix6d::Identity(), sum = Matrix6d::Identity();
    for (int k = 1; k < 40; ++k) {
      term = term * A / static_cast<double>(k + 1);
      sum += term;
    }
    EXPECT_LT(max_abs(left_jacobian(xi) - sum), 1e-13) << xi.transpose();
    EXPECT_LT(max_abs(q_block(xi.head<3>(), xi.tail<3>()) - sum.topRightCorner<3, 3>()), 1e-13);
  }
}

TEST(Se3Jacobian, StructuralIdentities) {
  std::mt19937 rng(53);
  for (int i = 0; i < 100; ++i) {
    const Vector6d xi = random_twist(rng, 6.0);
    const Matrix6d Jl = left_jacobian(xi), Jr = right_jacobian(xi);
    EXPECT_LT(max_abs(Jr - left_jacobian(-xi)), 1e-15);
    EXPECT_LT(max_abs(Jl - adjoint(exp(xi)) * Jr), 1e-12);  // Jl = Ad(exp ξ)·Jr
    EXPECT_LT(max_abs(Jl * xi - xi), 1e-13);
    EXPECT_LT(max_abs(Jl.topLeftCorner<3, 3>() - so3::left_jacobian(xi.tail<3>())), 1e-15);
    EXPECT_EQ(max_abs(Jl.bottomLeftCorner(3, 3)), 0.0);
  }
}

TEST(Se3Jacobian, InverseTimesJacobianIsIdentity) {
  std::mt19937 rng(54);
  for (int i = 0; i < 200; ++i) {
    const Vector6d xi = random_twist(rng, 2 * kPi - 1e-2);
    const Matrix6d Jl = left_jacobian(xi), Jr = right_jacobian(xi);
    const double tol = 1e-13 * Jl.norm() * left_jacobian_inverse(xi).norm();
    EXPECT_LT(max_abs(left_jacobian_inverse(xi) * Jl - Matrix6d::Identity()), tol);
    EXPECT_LT(max_abs(Jl * left_jacobian_inverse(xi) - Matrix6d::Identity()), tol);
    EXPECT_LT(max_abs(right_jacobian_inverse(xi) * Jr - Matrix6d::Identity()), tol);
  }
  for (double theta : {0.0, 1e-9, 1e-6, kPi}) {
    const Vector6d xi = twist(random_unit(rng), theta * random_unit(rng));
    EXPECT_LT(max_abs(left_jacobian_inverse(xi) * left_jacobian(xi) - Matrix6d::Identity()), 1e-14);
  }
}

TEST(Se3Jacobian, LogOfPerturbedPoseUsesTheInverse) {
  // log(exp(δ)·exp(ξ)) ≈ ξ + Jl⁻¹(ξ)·δ, the relation IK relies on
  std::mt19937 rng(55);
  for (int i = 0; i < 50; ++i) {
    const Vector6d xi = random_twist(rng, 3.0), d = random_twist(rng, 1.0);
    const Vector6d fd =
        finite_difference_derivative([&](double t) { return log(exp(t * d) * exp(xi)); }, 0.0);
    EXPECT_LT(max_abs(fd - left_jacobian_inverse(xi) * d), 1e-8);
  }
}

void check_rates(const Vector6d& xi, const Vector6d& xi_dot) {
  const double scale = 1.0 + std::pow(left_jacobian_inverse(xi).norm(), 3);
  const auto Jl = [](const Vector6d& x) { return left_jacobian(x); };
  const auto Jr = [](const Vector6d& x) { return right_jacobian(x); };
  const auto Jl_inv = [](const Vector6d& x) { return left_jacobian_inverse(x); };
  const auto Jr_inv = [](const Vector6d& x) { return right_jacobian_inverse(x); };
  EXPECT_LT(max_abs(left_jacobian_derivative(xi, xi_dot) - fd_rate(Jl, xi, xi_dot)), 1e-8)
      << xi.transpose();
  EXPECT_LT(max_abs(right_jacobian_derivative(xi, xi_dot) - fd_rate(Jr, xi, xi_dot)), 1e-8)
      << xi.transpose();
  EXPECT_LT(max_abs(left_jacobian_inverse_derivative(xi, xi_dot) - fd_rate(Jl_inv, xi, xi_dot)),
            1e-8 * scale)
      << xi.transpose();
  EXPECT_LT(max_abs(right_jacobian_inverse_derivative(xi, xi_dot) - fd_rate(Jr_inv, xi, xi_dot)),
            1e-8 * scale)
      << xi.transpose();
  // the Q block on its own
  const auto Q = [](const Vector6d& x) {
    Matrix6d m = Matrix6d::Zero();
    m.topRightCorner<3, 3>() = q_block(x.head<3>(), x.tail<3>());
    return m;
  };
  const Eigen::Matrix3d Q_dot =
      q_block_derivative(xi.head<3>(), xi.tail<3>(), xi_dot.head<3>(), xi_dot.tail<3>());
  EXPECT_LT(max_abs(Q_dot - fd_rate(Q, xi, xi_dot).topRightCorner<3, 3>()), 1e-8);
}

TEST(Se3Jacobian, TimeDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(56);
  for (int i = 0; i < 100; ++i) check_rates(random_twist(rng, 6.0), 2.0 * random_twist(rng, 1.0));
}

TEST(Se3Jacobian, TimeDerivativesNearZeroAndAtTheSeriesSwitch) {
  std::mt19937 rng(57);
  for (double theta : {0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.99999, 1.0, 1.00001, kPi, 2 * kPi - 0.3}) {
    for (int i = 0; i < 5; ++i) {
      // ω̇ both along and across ω, and a path through ω = 0 when θ = 0
      check_rates(twist(random_unit(rng), theta * random_unit(rng)),
                  twist(random_unit(rng), random_unit(rng)));
    }
  }
}

TEST(Se3Jacobian, InverseDomainIsBelowTwoPi) {
  const Eigen::Vector3d u = Eigen::Vector3d(-1, 2, 0.5).normalized();
  const Vector6d xi_dot = Vector6d::Constant(0.1);
  const Vector6d inside = twist(Eigen::Vector3d(1, 2, 3), (2 * kPi - 1e-6) * u);
  EXPECT_NO_THROW(left_jacobian_inverse(inside));
  EXPECT_TRUE(left_jacobian_inverse(inside).allFinite());
  EXPECT_NO_THROW(right_jacobian_inverse_derivative(inside, xi_dot));
  for (const Vector6d& xi :
       {twist(Eigen::Vector3d(1, 2, 3), 2 * kPi * u), twist(Eigen::Vector3d::Zero(), 10.0 * u),
        twist(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, NAN, 0.0))}) {
    EXPECT_THROW(left_jacobian_inverse(xi), Error);
    EXPECT_THROW(right_jacobian_inverse(xi), Error);
    EXPECT_THROW(left_jacobian_inverse_derivative(xi, xi_dot), Error);
    EXPECT_THROW(right_jacobian_inverse_derivative(xi, xi_dot), Error);
  }
  try {
    left_jacobian_inverse(twist(Eigen::Vector3d::Zero(), 2 * kPi * u));
    FAIL() << "expected mjarm::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("se3::left_jacobian_inverse"), std::string::npos);
  }
}

}  // namespace
}  // namespace mjarm::se3
