#include "mjarm/lie/so3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <random>

#include "lie/lie_test_support.hpp"

namespace mjarm::so3 {
namespace {

using test::kPi;
using test::max_abs;
using test::random_unit;

TEST(So3, HatVee) {
  std::mt19937 rng(1);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d a = 3.0 * random_unit(rng);
    const Eigen::Vector3d b = random_unit(rng);
    const Eigen::Matrix3d A = hat(a);
    EXPECT_LT(max_abs(A + A.transpose()), 1e-15);
    EXPECT_LT(max_abs(A * b - a.cross(b)), 1e-15);
    EXPECT_LT(max_abs(vee(A) - a), 1e-15);
  }
}

TEST(So3, ExpMatchesAngleAxis) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> angle_dist(0.0, 3.0 * kPi);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d u = random_unit(rng);
    const double theta = angle_dist(rng);
    const Eigen::Matrix3d R = exp(theta * u);
    EXPECT_LT(max_abs(R - Eigen::AngleAxisd(theta, u).toRotationMatrix()), 1e-14);
    EXPECT_LT(max_abs(R.transpose() * R - Eigen::Matrix3d::Identity()), 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
  }
}

TEST(So3, LogExpRoundTripRandom) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle_dist(0.0, kPi);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d w = angle_dist(rng) * random_unit(rng);
    EXPECT_LT(max_abs(log(exp(w)) - w), 1e-13) << w.transpose();
    EXPECT_NEAR(angle(exp(w)), w.norm(), 1e-13);
  }
}

TEST(So3, ExpLogRoundTripRandomRotations) {
  std::mt19937 rng(4);
  for (int i = 0; i < 200; ++i) {
    Eigen::Vector4d q;
    std::normal_distribution<double> n(0.0, 1.0);
    q << n(rng), n(rng), n(rng), n(rng);
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized().toRotationMatrix();
    const Eigen::Vector3d w = log(R);
    EXPECT_LE(w.norm(), kPi + 1e-15);
    EXPECT_LT(max_abs(exp(w) - R), 1e-14);
  }
}

TEST(So3, NearZeroIsRelativelyAccurate) {
  std::mt19937 rng(5);
  for (double theta : {0.0, 1e-300, 1e-12, 1e-9, 1e-6, 1e-3}) {
    const Eigen::Vector3d w = theta * random_unit(rng);
    const Eigen::Matrix3d R = exp(w);
    // first-order check of exp: R ≈ I + ω̂ + ½ω̂²
    const Eigen::Matrix3d W = hat(w);
    EXPECT_LT(max_abs(R - (Eigen::Matrix3d::Identity() + W + 0.5 * W * W)),
              1e-15 + std::pow(theta, 3))
        << theta;
    // log recovers ω to relative precision, not only absolute
    EXPECT_LE((log(R) - w).norm(), 1e-14 * theta + 1e-300) << theta;
  }
}

TEST(So3, NearPiRoundTrip) {
  std::mt19937 rng(6);
  for (double gap : {1e-6, 1e-9, 1e-12, 0.0}) {
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector3d u = random_unit(rng);
      const Eigen::Vector3d w = (kPi - gap) * u;
      const Eigen::Matrix3d R = exp(w);
      const Eigen::Vector3d w_back = log(R);
      EXPECT_LT(max_abs(exp(w_back) - R), 1e-14) << gap;
      EXPECT_NEAR(w_back.norm(), kPi - gap, 1e-14) << gap;
      if (gap == 0.0) {
        // at exactly π, ω and −ω are the same rotation: either is a correct log
        EXPECT_LT(std::min((w_back - w).norm(), (w_back + w).norm()), 1e-13);
      } else {
        EXPECT_LT((w_back - w).norm(), 1e-13) << gap;
      }
    }
  }
}

TEST(So3, ExactPiFromSymmetricMatrix) {
  // R = 2uuᵀ − I is a rotation by π about u, built without exp
  std::mt19937 rng(7);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d u = random_unit(rng);
    const Eigen::Matrix3d R = 2.0 * u * u.transpose() - Eigen::Matrix3d::Identity();
    const Eigen::Vector3d w = log(R);
    EXPECT_NEAR(w.norm(), kPi, 1e-14);
    EXPECT_NEAR(std::fabs(w.normalized().dot(u)), 1.0, 1e-14);
    EXPECT_LT(max_abs(exp(w) - R), 1e-14);
  }
}

TEST(So3, LogIsEquivariant) {
  // log(Q R Qᵀ) = Q log(R)
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> angle_dist(0.0, 3.0);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Matrix3d Q = exp(angle_dist(rng) * random_unit(rng));
    const Eigen::Vector3d w = angle_dist(rng) * random_unit(rng);
    EXPECT_LT(max_abs(log(Q * exp(w) * Q.transpose()) - Q * w), 1e-13);
  }
}

}  // namespace
}  // namespace mjarm::so3
