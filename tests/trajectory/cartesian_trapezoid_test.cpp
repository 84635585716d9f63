#include "mjarm/trajectory/cartesian_trapezoid.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

Pose pose(const Eigen::Vector3d& p, const Eigen::Vector3d& rotation) {
  Pose X;
  X.p = p;
  X.R = so3::exp(rotation);
  return X;
}

TEST(CartesianTrapezoid, StraightLineUnderTheClassicLimits) {
  // 0.2 m at 0.07 m/s and 0.9 m/s²: t_acc = 0.0778 s, cruise (0.2 − 0.07²/0.9)/0.07 s
  const Pose A = pose({0.3, 0.0, 0.9}, {M_PI, 0.0, 0.0});
  Pose B = A;
  B.p += Eigen::Vector3d(0.12, -0.16, 0.0);
  const CartesianTrapezoid move(A, B);
  EXPECT_NEAR(move.distance(), 0.2, 1e-15);
  EXPECT_EQ(move.angle(), 0.0);
  const double t_acc = 0.07 / 0.9;
  EXPECT_NEAR(move.duration(), 2.0 * t_acc + (0.2 - 0.07 * t_acc) / 0.07, 1e-12);
  const Eigen::Vector3d u = (B.p - A.p) / 0.2;
  double peak_speed = 0.0, peak_accel = 0.0;
  for (double t = 0.0; t <= move.duration(); t += 0.001) {
    const CartesianTrapezoid::Sample s = move.at(t);
    // on the line, the orientation untouched
    const Eigen::Vector3d off = s.X_WE.p - A.p;
    EXPECT_LT((off - off.dot(u) * u).norm(), 1e-14);
    EXPECT_LT((s.X_WE.R - A.R).norm(), 1e-14);
    peak_speed = std::max(peak_speed, s.V_WE.head<3>().norm());
    peak_accel = std::max(peak_accel, s.A_WE.head<3>().norm());
    EXPECT_LT(s.V_WE.tail<3>().norm(), 1e-15);
  }
  EXPECT_NEAR(peak_speed, 0.07, 1e-12);
  EXPECT_NEAR(peak_accel, 0.9, 1e-12);
  EXPECT_TRUE(move.at(move.duration()).X_WE.is_approx(B, 0.0));  // exactly the goal
  EXPECT_TRUE(move.at(-1.0).X_WE.is_approx(A, 1e-15));
}

TEST(CartesianTrapezoid, TwistIsTheDerivativeOfThePose) {
  const Pose A = pose({0.3, 0.1, 0.9}, {M_PI, 0.0, 0.0});
  const Pose B = pose({0.35, -0.05, 0.82}, {0.2, -0.3, 0.9});
  CartesianLimits limits;
  limits.max_angular_velocity = 0.8;
  const CartesianTrapezoid move(A, B, limits);
  const double h = 1e-6;
  int samples = 0, rates_match = 0;
  for (double t = 0.01; t < move.duration(); t += move.duration() / 17.0) {
    const CartesianTrapezoid::Sample s = move.at(t);
    const CartesianTrapezoid::Sample before = move.at(t - h), after = move.at(t + h);
    const Eigen::Vector3d v = (after.X_WE.p - before.X_WE.p) / (2.0 * h);
    // ω from R(t+h)·R(t−h)ᵀ = Exp(2h·ω) (world axes)
    const Eigen::Vector3d w = so3::log(after.X_WE.R * before.X_WE.R.transpose()) / (2.0 * h);
    EXPECT_LT((v - s.V_WE.head<3>()).norm(), 1e-8) << t;
    EXPECT_LT((w - s.V_WE.tail<3>()).norm(), 1e-7) << t;
    const Eigen::Vector3d a = (after.V_WE.head<3>() - before.V_WE.head<3>()) / (2.0 * h);
    const Eigen::Vector3d alpha = (after.V_WE.tail<3>() - before.V_WE.tail<3>()) / (2.0 * h);
    // the rates, except within h of a switch of the piecewise-constant acceleration
    ++samples;
    rates_match += (a - s.A_WE.head<3>()).norm() < 1e-6 && (alpha - s.A_WE.tail<3>()).norm() < 1e-6;
  }
  EXPECT_GE(rates_match, samples - 1);
}

TEST(CartesianTrapezoid, TurnAndLineStartAndEndTogether) {
  // a short line with a large turn: the turn is the slower axis and stretches the line
  const Pose A = pose({0.3, 0.0, 0.9}, {M_PI, 0.0, 0.0});
  Pose B = pose({0.31, 0.0, 0.9}, Eigen::Vector3d::Zero());
  B.R = so3::exp(Eigen::Vector3d(0.0, 0.0, 1.2)) * A.R;
  const CartesianTrapezoid move(A, B);
  EXPECT_NEAR(move.angle(), 1.2, 1e-12);
  const TrapezoidProfile turn(1.2, 0.5, 3.0), line(0.01, 0.07, 0.9);
  EXPECT_NEAR(move.duration(), turn.duration(), 1e-12);
  EXPECT_GT(move.duration(), line.duration());
  // halfway through the time the turn is halfway (symmetric profile), and so is the line
  const CartesianTrapezoid::Sample half = move.at(0.5 * move.duration());
  EXPECT_NEAR(so3::log(half.X_WE.R * A.R.transpose()).norm(), 0.6, 1e-12);
  EXPECT_NEAR((half.X_WE.p - A.p).norm(), 0.005, 1e-12);
  EXPECT_LT(move.at(move.duration() - 1e-9).V_WE.norm(), 1e-6);
  // no motion at all: zero duration, the goal at once
  const CartesianTrapezoid still(A, A);
  EXPECT_EQ(still.duration(), 0.0);
  EXPECT_TRUE(still.at(0.0).X_WE.is_approx(A, 0.0));
}

TEST(CartesianTrapezoid, BadInput) {
  const Pose A = pose({0.3, 0.0, 0.9}, Eigen::Vector3d::Zero());
  Pose bad = A;
  bad.p.x() = NAN;
  EXPECT_NE(test::error_of([&] { CartesianTrapezoid(bad, A); }).find("start pose must be finite"),
            std::string::npos);
  Pose skew = A;
  skew.R(0, 1) = 0.3;
  EXPECT_NE(test::error_of([&] { CartesianTrapezoid(A, skew); }).find("goal rotation"),
            std::string::npos);
  CartesianLimits limits;
  limits.max_acceleration = 0.0;
  EXPECT_NE(test::error_of([&] { CartesianTrapezoid(A, A, limits); }).find("max_acceleration"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
