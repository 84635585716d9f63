#include "mjarm/lie/pose_error.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "lie/lie_test_support.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm {
namespace {

using test::max_abs;
using test::random_twist;
using test::random_unit;

Pose translation(const Eigen::Vector3d& p) { return Pose{Eigen::Matrix3d::Identity(), p}; }

TEST(PoseError, ZeroWhenPosesCoincide) {
  std::mt19937 rng(61);
  const Pose X = se3::exp(random_twist(rng, 3.0));
  EXPECT_LT(max_abs(log_error(X, X)), 1e-15);
  EXPECT_LT(max_abs(log_error_world_aligned(X, X)), 1e-15);
}

TEST(PoseError, ErrorsReconstructTheTarget) {
  std::mt19937 rng(62);
  for (int i = 0; i < 100; ++i) {
    const Pose X_WE = se3::exp(random_twist(rng, 3.1));
    const Pose X_WT = se3::exp(random_twist(rng, 3.1));
    const Vector6d e_E = log_error(X_WE, X_WT);
    const Vector6d e_W = log_error_world_aligned(X_WE, X_WT);
    // body: X_WT = X_WE·exp(e_E)
    EXPECT_TRUE((X_WE * se3::exp(e_E)).is_approx(X_WT, 1e-13));
    // world-aligned: X_WT = T(p_WE)·exp(e_W)·T(−p_WE)·X_WE
    EXPECT_TRUE(
        (translation(X_WE.p) * se3::exp(e_W) * translation(-X_WE.p) * X_WE).is_approx(X_WT, 1e-13));
    EXPECT_LE(e_E.tail<3>().norm(), std::numbers::pi + 1e-15);
    EXPECT_NEAR(e_W.norm(), e_E.norm(), 1e-13);
  }
}

TEST(PoseError, PureTranslationErrorIsTheOffset) {
  const Pose X_WE{so3::exp(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2)),
                  Eigen::Vector3d(1.0, 0.0, 0.0)};
  const Pose X_WT{X_WE.R, Eigen::Vector3d(1.0, 2.0, 0.0)};
  Vector6d expected_W;
  expected_W << 0.0, 2.0, 0.0, 0.0, 0.0, 0.0;
  EXPECT_LT(max_abs(log_error_world_aligned(X_WE, X_WT) - expected_W), 1e-15);
  Vector6d expected_E;  // the offset seen from E, which is yawed by +90°
  expected_E << 2.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  EXPECT_LT(max_abs(log_error(X_WE, X_WT) - expected_E), 1e-15);
}

TEST(PoseError, BodyRateIsMinusJlogTimesBodyTwist) {
  std::mt19937 rng(63);
  for (int i = 0; i < 100; ++i) {
    // the target at a known error of up to 3 rad, away from log's branch cut at π
    const Pose X_WE = se3::exp(random_twist(rng, 3.0));
    const Pose X_WT = X_WE * se3::exp(random_twist(rng, 3.0));
    const Vector6d V_E = random_twist(rng, 2.0);  // body twist of E, in E
    const Vector6d fd = finite_difference_derivative(
        [&](double t) { return log_error(X_WE * se3::exp(t * V_E), X_WT); }, 0.0);
    const Vector6d e_E = log_error(X_WE, X_WT);
    EXPECT_LT(max_abs(fd + log_error_jacobian(e_E) * V_E), 1e-7) << e_E.transpose();
  }
}

TEST(PoseError, WorldAlignedRateUsesItsOwnJacobian) {
  std::mt19937 rng(64);
  for (int i = 0; i < 100; ++i) {
    const Pose X_WE = se3::exp(random_twist(rng, 3.0));
    const Pose X_WT = X_WE * se3::exp(random_twist(rng, 3.0));
    const Vector6d V_W = random_twist(rng, 2.0);  // [ṗ_WE; ω_WE], world-aligned at E
    // a path with that world-aligned twist: p(t) = p + t·ṗ, R(t) = exp(t·ω)·R
    const auto moved = [&](double t) {
      return Pose{so3::exp(t * V_W.tail<3>()) * X_WE.R, X_WE.p + t * V_W.head<3>()};
    };
    const Vector6d fd = finite_difference_derivative(
        [&](double t) { return log_error_world_aligned(moved(t), X_WT); }, 0.0);
    const Vector6d e_W = log_error_world_aligned(X_WE, X_WT);
    EXPECT_LT(max_abs(fd + log_error_world_aligned_jacobian(e_W) * V_W), 1e-7) << e_W.transpose();
  }
}

TEST(PoseError, JacobiansTendToIdentityAndCheckTheirDomain) {
  Vector6d small;
  small << 1e-9, -2e-9, 3e-9, 1e-9, 1e-9, -1e-9;
  EXPECT_LT(max_abs(log_error_jacobian(small) - Matrix6d::Identity()), 1e-8);
  EXPECT_LT(max_abs(log_error_world_aligned_jacobian(small) - Matrix6d::Identity()), 1e-8);
  Vector6d bad = Vector6d::Zero();
  bad(3) = 2 * std::numbers::pi;
  EXPECT_THROW(log_error_jacobian(bad), Error);
  EXPECT_THROW(log_error_world_aligned_jacobian(bad), Error);
}

}  // namespace
}  // namespace mjarm
