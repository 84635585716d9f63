#include "mjarm/trajectory/se3_interpolation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

Vector6d six(double a, double b, double c, double d, double e, double f) {
  Vector6d v;
  v << a, b, c, d, e, f;
  return v;
}

// the world twist [ṗ; ω] of the pose path by central differences (the public helper, with the
// time as its one argument: the world-aligned column is (p₊ − p₋)/Δ, log(R₊·R₋ᵀ)/Δ)
Vector6d finite_twist(const Se3Interpolation& s, double t, double h) {
  const auto pose = [&](const Eigen::VectorXd& x) { return s.at(x[0]).X_WE; };
  return finite_difference_pose_jacobian(pose, Eigen::VectorXd::Constant(1, t),
                                         JacobianFrame::world_aligned, h)
      .col(0);
}

TEST(Se3Interpolation, StartsWithTheGivenTwistAndRateAndEndsAtRest) {
  // ω₀ far from parallel to the rotation axis of the move
  const Pose X0 = Pose::from_rotation_vector({0.4, -0.1, 0.6}, {0.3, -0.8, 0.2});
  const Pose X1 = Pose::from_rotation_vector({0.1, 0.3, 0.5}, {-1.2, 0.4, 1.9});
  const Vector6d V0 = six(0.2, -0.1, 0.05, 1.5, 0.7, -2.0);
  const Vector6d A0 = six(-1.0, 0.5, 2.0, 3.0, -4.0, 1.0);
  const Se3Interpolation s(X0, V0, A0, X1, 0.8);
  const Se3Interpolation::Sample a = s.at(0.0);
  EXPECT_TRUE(a.X_WE.is_approx(X0, 1e-15));
  EXPECT_LT((a.V_WE - V0).norm(), 1e-14);
  EXPECT_LT((a.A_WE - A0).norm(), 1e-13);
  const Se3Interpolation::Sample b = s.at(0.8);
  EXPECT_TRUE(b.X_WE.is_approx(X1, 1e-12));
  EXPECT_EQ(b.V_WE.norm(), 0.0);  // at rest exactly from T on
  EXPECT_EQ(b.A_WE.norm(), 0.0);
  EXPECT_EQ(b.X_WE.p, X1.p);
  EXPECT_TRUE(s.at(3.0).X_WE.is_approx(X1, 1e-12));
  // just before T the polynomials agree with the exact end (no visible step)
  const Se3Interpolation::Sample c = s.at(0.8 - 1e-9);
  EXPECT_TRUE(c.X_WE.is_approx(b.X_WE, 1e-12));
  EXPECT_LT(c.V_WE.norm(), 1e-9);
}

TEST(Se3Interpolation, TwistAndRateAreTheTrueDerivativesOfThePose) {
  mjarm::Random rng(7);
  const auto u = [](mjarm::Random& r) { return mjarm::uniform(r, -1.0, 1.0); };
  auto vec = [&](double scale) -> Eigen::Vector3d {
    return Eigen::Vector3d(u(rng), u(rng), u(rng)) * scale;
  };
  for (int trial = 0; trial < 20; ++trial) {
    const Pose X0 = Pose::from_rotation_vector(vec(0.5), vec(2.0));
    const Pose X1 = Pose::from_rotation_vector(vec(0.5), vec(2.0));
    Vector6d V0, A0;
    V0 << vec(0.5), vec(3.0);
    A0 << vec(2.0), vec(8.0);
    const double T = 0.4 + 0.5 * (1 + u(rng));
    const Se3Interpolation s(X0, V0, A0, X1, T);
    const double h = 1e-6;
    for (double f : {0.05, 0.3, 0.55, 0.9}) {
      const double t = f * T;
      const Se3Interpolation::Sample x = s.at(t);
      EXPECT_LT((finite_twist(s, t, h) - x.V_WE).norm(), 1e-6 * (1 + x.V_WE.norm()))
          << trial << " t " << t;
      const Vector6d rate = (s.at(t + h).V_WE - s.at(t - h).V_WE) / (2 * h);
      EXPECT_LT((rate - x.A_WE).norm(), 1e-5 * (1 + x.A_WE.norm())) << trial << " t " << t;
    }
  }
}

TEST(Se3Interpolation, TheParallelShortcutWouldBeWrongHere) {
  // ω(t) = R₀·Jl(θ)·θ̇; the shortcut R₀·θ̇ misses the turn of θ̇ around θ
  const Pose X0 = Pose::from_rotation_vector({0, 0, 0}, {0, 0, 0});
  const Pose X1 = Pose::from_rotation_vector({0, 0, 0}, {0, 0, 1.5});
  const Se3Interpolation s(X0, six(0, 0, 0, 2.0, 0, 0), Vector6d::Zero(), X1, 1.0);
  const double t = 0.5;
  Eigen::Vector3d theta, theta_dot, theta_ddot;
  s.rotation_vector(t, theta, theta_dot, theta_ddot);
  const Vector6d exact = s.at(t).V_WE;
  const Vector6d measured = finite_twist(s, t, 1e-6);
  EXPECT_LT((measured.tail<3>() - exact.tail<3>()).norm(), 1e-7);
  EXPECT_GT((measured.tail<3>() - X0.R * theta_dot).norm(), 0.05);  // the shortcut's error
}

TEST(Se3Interpolation, GoesTheShortWayNearAHalfTurn) {
  const Pose X0 = Pose::from_rotation_vector({0, 0, 0}, {0, 0, 0});
  const Pose X1 = Pose::from_rotation_vector({1, 0, 0}, {0, 3.1, 0});
  const Se3Interpolation s(X0, Vector6d::Zero(), Vector6d::Zero(), X1, 2.0);
  EXPECT_NEAR(s.rotation().norm(), 3.1, 1e-12);
  EXPECT_TRUE(s.at(2.0).X_WE.is_approx(X1, 1e-12));
  EXPECT_NEAR(so3::angle(s.at(1.0).X_WE.R), 1.55, 1e-12);  // half way at half time (at rest)
}

TEST(Se3Interpolation, RejectsBadInput) {
  const Pose X = Pose::from_rotation_vector({0, 0, 0}, {0.1, 0.2, 0.3});
  const Vector6d zero = Vector6d::Zero();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Se3Interpolation(X, zero, zero, X, 0.0), Error);
  EXPECT_THROW(Se3Interpolation(X, zero, zero, X, -1.0), Error);
  EXPECT_THROW(Se3Interpolation(X, zero, zero, X, std::numeric_limits<double>::infinity()), Error);
  EXPECT_THROW(Se3Interpolation(X, zero, zero, X, nan), Error);
  // a duration far out of scale with the move: an error, not NaN poses
  const Pose far = Pose::from_rotation_vector({1, 0, 0}, {0.1, 0.2, 0.3});
  EXPECT_THROW(Se3Interpolation(X, zero, zero, far, 1e-300), Error);
  EXPECT_THROW(Se3Interpolation(X, six(0, 0, nan, 0, 0, 0), zero, X, 1.0), Error);
  EXPECT_THROW(Se3Interpolation(X, zero, six(0, 0, 0, 0, 0, nan), X, 1.0), Error);
  Pose bad = X;
  bad.R(0, 0) = 2.0;
  EXPECT_THROW(Se3Interpolation(X, zero, zero, bad, 1.0), Error);
  bad = X;
  bad.p.x() = nan;
  EXPECT_THROW(Se3Interpolation(bad, zero, zero, X, 1.0), Error);
}

}  // namespace
}  // namespace mjarm
