#include "mjarm/lie/pose.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>
#include <string>
#include <random>

#include "lie/lie_test_support.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"

namespace mjarm {
namespace {

using test::max_abs;

Pose random_pose(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Matrix3d R =
      Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  return Pose{R, Eigen::Vector3d(n(rng), n(rng), n(rng))};
}

TEST(Pose, DefaultIsIdentity) {
  const Pose X;
  EXPECT_EQ(X.R, Eigen::Matrix3d::Identity());
  EXPECT_EQ(X.p, Eigen::Vector3d::Zero());
  EXPECT_TRUE(Pose::identity().is_approx(X, 0.0));
}

TEST(Pose, CompositionAndInverseMatchHomogeneousMatrices) {
  std::mt19937 rng(31);
  for (int i = 0; i < 100; ++i) {
    const Pose X_AB = random_pose(rng), X_BC = random_pose(rng);
    const Pose X_AC = X_AB * X_BC;
    EXPECT_LT(max_abs(X_AC.matrix() - X_AB.matrix() * X_BC.matrix()), 1e-14);
    EXPECT_LT(max_abs(X_AB.inverse().matrix() - X_AB.matrix().inverse()), 1e-13);
    EXPECT_TRUE((X_AB * X_AB.inverse()).is_approx(Pose::identity(), 1e-14));
    // points: p_A = X_AB · p_B, composed action equals action of composition
    const Eigen::Vector3d p_C(0.3, -1.2, 2.0);
    EXPECT_LT(max_abs(X_AC.act(p_C) - X_AB.act(X_BC.act(p_C))), 1e-14);
    const Eigen::Vector4d h = X_AB.matrix() * p_C.homogeneous();
    EXPECT_LT(max_abs(X_AB.act(p_C) - h.head<3>()), 1e-14);
    EXPECT_EQ(max_abs(X_AB.rotate(p_C) - X_AB.R * p_C), 0.0);
  }
}

TEST(Pose, IsometryAndMatrixRoundTrip) {
  std::mt19937 rng(32);
  for (int i = 0; i < 20; ++i) {
    const Pose X = random_pose(rng);
    EXPECT_TRUE(Pose::from_isometry(X.to_isometry()).is_approx(X, 0.0));
    EXPECT_TRUE(Pose::from_matrix(X.matrix()).is_approx(X, 0.0));
    EXPECT_EQ(max_abs(X.to_isometry().matrix() - X.matrix()), 0.0);
    const Eigen::Vector3d p(1, 2, 3);
    EXPECT_LT(max_abs(X.to_isometry() * p - X.act(p)), 1e-14);
  }
}

TEST(Pose, FromQuaternionAndRpy) {
  const Eigen::Vector3d p(0.1, 0.2, 0.3);
  const Pose Xq = Pose::from_quaternion(p, Eigen::Vector4d(0.0, 0.0, 0.0, 2.0));  // π about z
  EXPECT_LT(max_abs(Xq.R - Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()), 1e-15);
  EXPECT_EQ(Xq.p, p);
  const Pose Xr = Pose::from_rpy(p, Eigen::Vector3d(0.0, 0.0, std::numbers::pi));
  EXPECT_TRUE(Xr.is_approx(Xq, 1e-15));
  EXPECT_THROW(Pose::from_quaternion(p, Eigen::Vector4d::Zero()), Error);
  // π about z as a rotation vector, and a general one against the quaternion of axis·angle
  EXPECT_TRUE(Pose::from_rotation_vector(p, Eigen::Vector3d(0.0, 0.0, std::numbers::pi))
                  .is_approx(Xq, 1e-15));
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  const double angle = 0.7;
  const Eigen::Vector4d q(std::cos(angle / 2), std::sin(angle / 2) * axis.x(),
                          std::sin(angle / 2) * axis.y(), std::sin(angle / 2) * axis.z());
  EXPECT_TRUE(
      Pose::from_rotation_vector(p, angle * axis).is_approx(Pose::from_quaternion(p, q), 1e-15));
}

// issue 29, item 9: a NaN given to a pose factory came out as a NaN pose without a word
TEST(Pose, FactoriesRefuseNumbersThatAreNotFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d bad(0.1, nan, 0.3), good(0.1, 0.2, 0.3);
  const auto expect_refused = [](auto&& make, const char* needle) {
    try {
      make();
      ADD_FAILURE() << "no error for " << needle;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_refused([&] { Pose::from_rpy(good, bad); }, "Pose::from_rpy: rpy holds nan");
  expect_refused([&] { Pose::from_rpy(bad, good); }, "Pose::from_rpy: p holds nan");
  expect_refused([&] { Pose::from_rotation_vector(good, bad); }, "from_rotation_vector: phi");
  expect_refused([&] { Pose::from_quaternion(bad, Eigen::Vector4d(1, 0, 0, 0)); },
                 "from_quaternion: p holds nan");
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M(0, 3) = inf;
  expect_refused([&] { Pose::from_matrix(M); }, "Pose::from_matrix: p holds inf");
  M(0, 3) = 0.0;
  M(1, 1) = nan;
  expect_refused([&] { Pose::from_matrix(M); }, "Pose::from_matrix: R holds nan");
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = bad;
  expect_refused([&] { Pose::from_isometry(X); }, "from_isometry: the translation holds nan");
}

TEST(Pose, IsApproxDetectsDifferences) {
  Pose X;
  Pose Y = X;
  Y.p.x() += 1e-9;
  EXPECT_FALSE(X.is_approx(Y, 1e-10));
  EXPECT_TRUE(X.is_approx(Y, 1e-8));
}

}  // namespace
}  // namespace mjarm
