#include "mjarm/planning/joint_spline.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

TEST(JointSpline, SlopeHeuristicBlendsOnlyWhenNeighboursAgree) {
  const std::vector<Eigen::VectorXd> q{vec({0, 0}), vec({1, 1}), vec({3, 0})};
  const std::vector<Eigen::VectorXd> v =
      JointSpline::blend_velocities(q, {1.0, 2.0}, {0, 1, 0}, vec({10, 10}));
  EXPECT_DOUBLE_EQ(v[1][0], 0.5 * (1.0 + 1.0));  // slopes 1 and 1
  EXPECT_DOUBLE_EQ(v[1][1], 0.0);                // slopes 1 and −0.5: a turn stops
  EXPECT_TRUE(v[0].isZero());
  EXPECT_TRUE(v[2].isZero());
  // clipped to the limit; no blending where the flag says stop
  EXPECT_DOUBLE_EQ(JointSpline::blend_velocities(q, {1.0, 2.0}, {0, 1, 0}, vec({0.4, 1}))[1][0],
                   0.4);
  EXPECT_TRUE(JointSpline::blend_velocities(q, {1.0, 2.0}, {0, 0, 0}, vec({10, 10}))[1].isZero());
}

TEST(JointSpline, TimedPassesTheKnotsInMotionWithinTheLimits) {
  const std::vector<Eigen::VectorXd> q{vec({0, 0, 0}), vec({0.5, -0.2, 0.1}), vec({1.2, -0.6, 0.1}),
                                       vec({1.5, -0.4, -0.3})};
  const Eigen::VectorXd vmax = vec({1.0, 0.8, 0.5});
  const Eigen::VectorXd amax = vec({3.0, 2.0, 4.0});
  const JointSpline s = JointSpline::timed(q, vmax, amax, {0.05, 0.05, 0.05}, {0, 1, 1, 0});
  ASSERT_EQ(s.segments(), 3);
  Eigen::VectorXd p(3), v(3), a(3), p2(3), v2(3), a2(3);
  for (int k = 0; k <= 3; ++k) {
    s.at(s.knot_time(k), p, v, a);
    EXPECT_TRUE(p.isApprox(q[k], 1e-12) || (p - q[k]).norm() < 1e-12) << k;
  }
  s.at(s.knot_time(1), p, v, a);
  EXPECT_GT(std::abs(v[0]), 0.1);  // joint 0 keeps moving through knot 1
  s.at(0.0, p, v, a);
  EXPECT_TRUE(v.isZero());
  s.at(s.duration(), p, v, a);
  EXPECT_TRUE(v.isZero(1e-12));
  // C²: the two sides of each knot agree; limits hold at dense samples
  for (int k = 1; k < 3; ++k) {
    s.at(s.knot_time(k) - 1e-7, p, v, a);
    s.at(s.knot_time(k) + 1e-7, p2, v2, a2);
    EXPECT_LT((v - v2).norm(), 1e-4);
    EXPECT_LT((a - a2).norm(), 1e-3);
  }
  for (int j = 0; j <= 2000; ++j) {
    s.at(s.duration() * j / 2000.0, p, v, a);
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(std::abs(v[i]), vmax[i] * (1 + 1e-9));
      EXPECT_LE(std::abs(a[i]), amax[i] * (1 + 1e-9));
    }
  }
  // the jerk is the derivative of the acceleration, inside each segment
  Eigen::VectorXd j(3), p3(3), v3(3), a3(3), j3(3);
  for (double t : {0.1, 0.37, s.knot_time(1) + 0.05, s.knot_time(2) + 0.11}) {
    s.at(t, p, v, a, j);
    s.at(t - 1e-6, p2, v2, a2);
    s.at(t + 1e-6, p3, v3, a3);
    EXPECT_LT((j - (a3 - a2) / 2e-6).norm(), 1e-4 * (1 + j.norm())) << t;
    s.at(t, p2, v2, a2);
    EXPECT_EQ(p, p2);  // the same q, q̇, q̈ as without the jerk
    EXPECT_EQ(a, a2);
  }
  // slower limits, longer motion: durations come from the limits
  const JointSpline slow =
      JointSpline::timed(q, 0.5 * vmax, 0.5 * amax, {0.05, 0.05, 0.05}, {0, 1, 1, 0});
  EXPECT_GT(slow.duration(), 1.4 * s.duration());
}

TEST(JointSpline, EvaluationAllocatesNothing) {
  const JointSpline s = JointSpline::timed({vec({0, 0}), vec({1, 0.5}), vec({2, 0.2})}, vec({1, 1}),
                                           vec({2, 2}), {0.05, 0.05}, {0, 1, 0});
  Eigen::VectorXd q(2), qd(2), qdd(2), qddd(2);
  double sink = 0.0;
  const std::uint64_t before = test::malloc_calls();
  for (int j = 0; j <= 100; ++j) {
    s.at(s.duration() * j / 100.0, q, qd, qdd);
    sink += q[0] + qd[1] + qdd[0];
    s.at(s.duration() * j / 100.0, q, qd, qdd, qddd);
    sink += qddd[1];
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_TRUE(std::isfinite(sink));
}

TEST(JointSpline, BadInputIsAnError) {
  EXPECT_THROW(JointSpline({vec({0})}, {vec({0})}, {}), Error);
  EXPECT_THROW(JointSpline({vec({0}), vec({1})}, {vec({0}), vec({0})}, {0.0}), Error);
  EXPECT_THROW(JointSpline({vec({0}), vec({NAN})}, {vec({0}), vec({0})}, {1.0}), Error);
  EXPECT_THROW(JointSpline::timed({vec({0}), vec({1})}, vec({-1}), vec({1}), {0.1}, {0, 0}), Error);
  const JointSpline empty;
  Eigen::VectorXd x(1);
  EXPECT_THROW(empty.at(0.0, x, x, x), Error);
}

}  // namespace
}  // namespace mjarm
