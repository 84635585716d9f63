#include "mjarm/lie/rotation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <random>

#include "lie/lie_test_support.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::kPi;
using test::max_abs;

Eigen::Matrix3d axis_rotation(int axis, double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

TEST(Rotation, RpyIsExtrinsicXyz) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> a(-kPi, kPi);
  for (int i = 0; i < 50; ++i) {
    const double r = a(rng), p = a(rng), y = a(rng);
    const Eigen::Matrix3d expected =
        axis_rotation(2, y) * axis_rotation(1, p) * axis_rotation(0, r);
    EXPECT_LT(max_abs(rotation_from_rpy(r, p, y) - expected), 1e-15);
    EXPECT_LT(max_abs(rotation_from_rpy(Eigen::Vector3d(r, p, y)) - expected), 1e-15);
  }
}

TEST(Rotation, RpyRoundTripAwayFromGimbalLock) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> a(-kPi, kPi);
  std::uniform_real_distribution<double> b(-kPi / 2 + 1e-3, kPi / 2 - 1e-3);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d rpy(a(rng), b(rng), a(rng));
    const Eigen::Vector3d back = rpy_from_rotation(rotation_from_rpy(rpy));
    EXPECT_LT(max_abs(back - rpy), 1e-12) << rpy.transpose();
  }
}

TEST(Rotation, RpyReproducesRandomRotations) {
  std::mt19937 rng(23);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Matrix3d R = random_rotation(rng);
    const Eigen::Vector3d rpy = rpy_from_rotation(R);
    EXPECT_LE(std::fabs(rpy(1)), kPi / 2);
    EXPECT_LE(std::fabs(rpy(0)), kPi);
    EXPECT_LE(std::fabs(rpy(2)), kPi);
    EXPECT_LT(max_abs(rotation_from_rpy(rpy) - R), 1e-14);
  }
}

TEST(Rotation, RpyAtAndNearGimbalLock) {
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> a(-kPi, kPi);
  for (double sign : {1.0, -1.0}) {
    for (double gap : {0.0, 1e-15, 1e-12, 1e-9, 1e-6}) {
      for (int i = 0; i < 20; ++i) {
        const double pitch = sign * (kPi / 2 - gap);
        const Eigen::Matrix3d R = rotation_from_rpy(a(rng), pitch, a(rng));
        const Eigen::Vector3d rpy = rpy_from_rotation(R);
        EXPECT_LT(max_abs(rotation_from_rpy(rpy) - R), 1e-14) << sign << " " << gap;
        EXPECT_NEAR(rpy(1), pitch, 1e-7) << sign << " " << gap;
      }
    }
    // exactly at lock the convention puts the rotation about z into yaw, with roll = 0
    const Eigen::Matrix3d R = axis_rotation(2, 0.7) * axis_rotation(1, sign * kPi / 2);
    const Eigen::Vector3d rpy = rpy_from_rotation(R);
    EXPECT_EQ(rpy(0), 0.0);
    EXPECT_NEAR(rpy(1), sign * kPi / 2, 1e-15);
    EXPECT_NEAR(rpy(2), 0.7, 1e-15);
  }
}

TEST(Rotation, QuaternionMatchesEigenAndRoundTrips) {
  std::mt19937 rng(25);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector4d q = Eigen::Vector4d(n(rng), n(rng), n(rng), n(rng));
    const Eigen::Matrix3d R = rotation_from_quaternion(q);  // unnormalised input is accepted
    const Eigen::Vector4d u = q.normalized();
    EXPECT_LT(max_abs(R - Eigen::Quaterniond(u(0), u(1), u(2), u(3)).toRotationMatrix()), 1e-15);
    EXPECT_EQ(max_abs(R - rotation_from_quaternion(q(0), q(1), q(2), q(3))), 0.0);
    const Eigen::Vector4d back = quaternion_from_rotation(R);
    EXPECT_GE(back(0), 0.0);
    EXPECT_NEAR(back.norm(), 1.0, 1e-15);
    // q and −q are the same rotation; the canonical one has w ≥ 0
    EXPECT_LT(max_abs(back - (u(0) < 0 ? -u : u)), 1e-14);
  }
}

TEST(Rotation, QuaternionNearHalfTurn) {
  // w → 0: the scalar part is tiny and must still come out accurately
  for (double gap : {0.0, 1e-12, 1e-6}) {
    const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
    const double angle = kPi - gap;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    const Eigen::Vector4d q = quaternion_from_rotation(R);
    EXPECT_NEAR(q(0), std::cos(angle / 2), 1e-15) << gap;
    EXPECT_LT(max_abs(q.tail<3>() - std::sin(angle / 2) * axis), 1e-15) << gap;
    EXPECT_LT(max_abs(rotation_from_quaternion(q) - R), 1e-15) << gap;
  }
}

TEST(Rotation, RpyAndQuaternionAgree) {
  std::mt19937 rng(26);
  std::uniform_real_distribution<double> a(-kPi, kPi);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Matrix3d R = rotation_from_rpy(a(rng), a(rng) / 2, a(rng));
    EXPECT_LT(max_abs(rotation_from_quaternion(quaternion_from_rotation(R)) - R), 1e-15);
  }
}

TEST(Rotation, DegenerateQuaternionThrows) {
  EXPECT_THROW(rotation_from_quaternion(0.0, 0.0, 0.0, 0.0), Error);
  EXPECT_THROW(rotation_from_quaternion(1e-13, 0.0, 0.0, 0.0), Error);
  EXPECT_THROW(rotation_from_quaternion(NAN, 0.0, 0.0, 1.0), Error);
  EXPECT_THROW(rotation_from_quaternion(Eigen::Vector4d(INFINITY, 0.0, 0.0, 0.0)), Error);
  EXPECT_NO_THROW(rotation_from_quaternion(1e-6, 0.0, 0.0, 0.0));
}

TEST(WrapToPi, GivesTheNearestEquivalentAngle) {
  constexpr double pi = std::numbers::pi;
  EXPECT_DOUBLE_EQ(wrap_to_pi(0.5), 0.5);
  EXPECT_NEAR(wrap_to_pi(3.0 * pi / 2.0), -pi / 2.0, 1e-15);
  EXPECT_NEAR(wrap_to_pi(-3.0 * pi / 2.0), pi / 2.0, 1e-15);
  EXPECT_NEAR(wrap_to_pi(7.0), 7.0 - 2.0 * pi, 1e-15);
  EXPECT_NEAR(wrap_to_pi(1000.0 * pi + 0.25), 0.25, 1e-12);
  for (double a = -20.0; a <= 20.0; a += 0.37) {
    const double w = wrap_to_pi(a);
    EXPECT_LE(std::abs(w), pi);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-12);  // the same angle
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-12);
  }
  EXPECT_TRUE(std::isnan(wrap_to_pi(std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(wrap_to_pi(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace mjarm
