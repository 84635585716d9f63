#include "mjarm/lie/se3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <random>

#include "lie/lie_test_support.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/so3.hpp"
#include "support/reference_linear_algebra.hpp"

namespace mjarm::se3 {
namespace {

using test::kPi;
using test::max_abs;
using test::random_twist;
using test::random_unit;

Pose random_pose(std::mt19937& rng) { return exp(random_twist(rng, 3.1)); }

TEST(Se3, HatVee) {
  std::mt19937 rng(41);
  for (int i = 0; i < 20; ++i) {
    const Vector6d xi = random_twist(rng, 3.0);
    const Eigen::Matrix4d M = hat(xi);
    EXPECT_LT(max_abs(vee(M) - xi), 1e-15);
    EXPECT_EQ(M.row(3), Eigen::RowVector4d::Zero());
    // ξ^ acting on a homogeneous point: ω × p + v
    const Eigen::Vector3d p(0.5, -1.0, 2.0);
    EXPECT_LT(max_abs((M * p.homogeneous()).head<3>() - (xi.tail<3>().cross(p) + xi.head<3>())),
              1e-15);
  }
}

TEST(Se3, ExpMatchesMatrixExponential) {
  std::mt19937 rng(42);
  for (int i = 0; i < 50; ++i) {
    const Vector6d xi = random_twist(rng, 6.0);
    const Eigen::Matrix4d expected = test::matrix_exponential(hat(xi));
    EXPECT_LT(max_abs(exp(xi).matrix() - expected), 1e-12) << xi.transpose();
  }
}

TEST(Se3, LogExpRoundTripRandom) {
  std::mt19937 rng(43);
  for (int i = 0; i < 500; ++i) {
    const Vector6d xi = random_twist(rng, kPi);
    EXPECT_LT(max_abs(log(exp(xi)) - xi), 1e-12) << xi.transpose();
  }
}

TEST(Se3, ExpLogRoundTripRandomPoses) {
  std::mt19937 rng(44);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Pose X{Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix(),
                 Eigen::Vector3d(n(rng), n(rng), n(rng))};
    EXPECT_TRUE(exp(log(X)).is_approx(X, 1e-13));
  }
}

TEST(Se3, RoundTripNearZeroAndNearPi) {
  std::mt19937 rng(45);
  for (double theta : {0.0, 1e-12, 1e-9, 1e-6, 1e-3, kPi - 1e-6, kPi - 1e-9, kPi - 1e-12}) {
    for (int i = 0; i < 10; ++i) {
      Vector6d xi;
      xi << random_unit(rng), theta * random_unit(rng);
      const Pose X = exp(xi);
      EXPECT_LT(max_abs(log(X) - xi), 1e-12 + 1e-13 * theta) << theta;
      EXPECT_TRUE(exp(log(X)).is_approx(X, 1e-14)) << theta;
    }
  }
  // exactly π: the rotation vector is defined up to sign, the pose must round-trip
  for (int i = 0; i < 10; ++i) {
    Vector6d xi;
    xi << random_unit(rng), kPi * random_unit(rng);
    const Pose X = exp(xi);
    const Vector6d back = log(X);
    EXPECT_NEAR(back.tail<3>().norm(), kPi, 1e-14);
    EXPECT_TRUE(exp(back).is_approx(X, 1e-13));
  }
}

TEST(Se3, ExpOfPureTranslationAndPureRotation) {
  Vector6d xi;
  xi << 1.0, 2.0, 3.0, 0.0, 0.0, 0.0;
  EXPECT_TRUE(exp(xi).is_approx(Pose{Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 2, 3)}, 0.0));
  xi << 0.0, 0.0, 0.0, 0.0, 0.0, kPi / 2;
  const Pose X = exp(xi);
  EXPECT_LT(max_abs(X.R - so3::exp(Eigen::Vector3d(0, 0, kPi / 2))), 1e-16);
  EXPECT_EQ(X.p, Eigen::Vector3d::Zero());
}

TEST(Se3, AdjointIdentities) {
  std::mt19937 rng(46);
  for (int i = 0; i < 100; ++i) {
    const Pose X = random_pose(rng), Y = random_pose(rng);
    const Vector6d xi = random_twist(rng, 3.0);
    // Ad(XY) = Ad(X) Ad(Y), Ad(X⁻¹) = Ad(X)⁻¹
    EXPECT_LT(max_abs(adjoint(X * Y) - adjoint(X) * adjoint(Y)), 1e-13);
    EXPECT_LT(max_abs(adjoint(X.inverse()) * adjoint(X) - Matrix6d::Identity()), 1e-13);
    // (Ad(X) ξ)^ = X ξ^ X⁻¹
    EXPECT_LT(max_abs(hat(adjoint(X) * xi) - X.matrix() * hat(xi) * X.inverse().matrix()), 1e-13);
    // exp(Ad(X) ξ) = X exp(ξ) X⁻¹
    EXPECT_TRUE(exp(adjoint(X) * xi).is_approx(X * exp(xi) * X.inverse(), 1e-12));
    // transform_twist is Ad(X)·V without the matrix
    EXPECT_LT(max_abs(transform_twist(X, xi) - adjoint(X) * xi), 1e-14);
  }
}

TEST(Se3, SmallAdjointIsTheCommutator) {
  std::mt19937 rng(47);
  for (int i = 0; i < 100; ++i) {
    const Vector6d xi = random_twist(rng, 3.0), eta = random_twist(rng, 3.0);
    const Eigen::Matrix4d A = hat(xi), B = hat(eta);
    EXPECT_LT(max_abs(hat(ad(xi) * eta) - (A * B - B * A)), 1e-14);
    EXPECT_LT(max_abs(ad(xi) * xi), 1e-15);
    // ad is the derivative of Ad along exp: d/dt Ad(exp(tξ)) at t = 0
    const Matrix6d fd =
        finite_difference_derivative([&](double t) { return adjoint(exp(t * xi)); }, 0.0);
    EXPECT_LT(max_abs(fd - ad(xi)), 1e-8);
    // Ad(exp(ξ)) = exp(ad(ξ))
    const Matrix6d ad_exp = test::matrix_exponential(ad(xi));
    EXPECT_LT(max_abs(adjoint(exp(xi)) - ad_exp), 1e-11);
  }
}

TEST(Se3, WrenchTransformPreservesPower) {
  std::mt19937 rng(48);
  for (int i = 0; i < 100; ++i) {
    const Pose X_AB = random_pose(rng);
    const Vector6d V_B = random_twist(rng, 3.0), F_B = random_twist(rng, 3.0);
    const Vector6d V_A = transform_twist(X_AB, V_B);
    const Vector6d F_A = transform_wrench(X_AB, F_B);
    EXPECT_NEAR(F_A.dot(V_A), F_B.dot(V_B), 1e-12);
    EXPECT_LT(max_abs(F_A - coadjoint(X_AB) * F_B), 1e-14);
    EXPECT_LT(max_abs(coadjoint(X_AB) - test::inverse(adjoint(X_AB)).transpose()), 1e-12);
    EXPECT_LT(max_abs(adjoint(X_AB).transpose() * F_A - F_B), 1e-13);
  }
}

TEST(Se3, WrenchTransformMovesTheMomentPoint) {
  // a pure force f at B's origin, with B translated by p from A: τ_A = p × f
  const Pose X_AB{Eigen::Matrix3d::Identity(), Eigen::Vector3d(1.0, 0.0, 0.0)};
  Vector6d F_B;
  F_B << 0.0, 0.0, -10.0, 0.0, 0.0, 0.0;
  const Vector6d F_A = transform_wrench(X_AB, F_B);
  EXPECT_LT(max_abs(F_A.head<3>() - F_B.head<3>()), 1e-15);
  EXPECT_LT(max_abs(F_A.tail<3>() - Eigen::Vector3d(0.0, 10.0, 0.0)), 1e-15);
}

}  // namespace
}  // namespace mjarm::se3
