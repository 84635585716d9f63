#include "mjarm/trajectory/quintic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

TEST(Quintic, MeetsArbitraryBoundaryConditions) {
  mjarm::Random rng(5);
  const auto u = [](mjarm::Random& r) { return mjarm::uniform(r, -3.0, 3.0); };
  const auto dur = [](mjarm::Random& r) { return mjarm::uniform(r, 0.05, 4.0); };
  for (int trial = 0; trial < 200; ++trial) {
    const Quintic::State s0{u(rng), u(rng), u(rng)}, s1{u(rng), u(rng), u(rng)};
    const double T = dur(rng);
    const Quintic q(s0, s1, T);
    const Quintic::Sample a = q.at(0.0), b = q.at(T);
    const double scale = 1.0 + std::abs(s0.p) + std::abs(s1.p);
    EXPECT_NEAR(a.p, s0.p, 1e-14 * scale);
    EXPECT_NEAR(a.v, s0.v, 1e-13 * scale);
    EXPECT_NEAR(a.a, s0.a, 1e-13 * scale);
    EXPECT_NEAR(b.p, s1.p, 1e-11 * scale);
    EXPECT_NEAR(b.v, s1.v, 1e-10 * scale / std::min(T, 1.0));
    EXPECT_NEAR(b.a, s1.a, 1e-9 * scale / std::min(T * T, 1.0));
    // derivatives against finite differences inside
    const double h = 1e-6 * T;
    for (double f : {0.2, 0.5, 0.8}) {
      const double t = f * T;
      EXPECT_NEAR((q.at(t + h).p - q.at(t - h).p) / (2 * h), q.at(t).v,
                  1e-6 * (1 + std::abs(q.at(t).v)));
      EXPECT_NEAR((q.at(t + h).a - q.at(t - h).a) / (2 * h), q.at(t).j,
                  1e-5 * (1 + std::abs(q.at(t).j)));
    }
  }
}

TEST(Quintic, RestToRestIsTheMinimumJerkProfile) {
  const Quintic q({1.0, 0.0, 0.0}, {3.0, 0.0, 0.0}, 0.8);
  const SmoothRamp s(SmoothRamp::Kind::smootherstep, 0.8);  // the minimum-jerk scaling
  for (double t = -0.1; t <= 0.9; t += 0.05) {
    EXPECT_NEAR(q.at(t).p, 1.0 + 2.0 * s.at(t).s, 1e-14);
    EXPECT_NEAR(q.at(t).v, 2.0 * s.at(t).ds, 1e-12);
    EXPECT_NEAR(q.at(t).a, 2.0 * s.at(t).dds, 1e-10);
  }
  const Quintic::Peaks peaks = q.peaks();
  EXPECT_NEAR(peaks.velocity, 2.0 * 1.875 / 0.8, 1e-12);
  EXPECT_NEAR(peaks.acceleration, 2.0 * (10.0 / std::sqrt(3.0)) / 0.64, 1e-10);
  EXPECT_NEAR(peaks.jerk, 2.0 * 60.0 / (0.8 * 0.8 * 0.8), 1e-9);  // s‴(0) = 60
  // clamped outside, jerk 0 there
  EXPECT_EQ(q.at(5.0).p, 3.0);
  EXPECT_EQ(q.at(5.0).j, 0.0);
  EXPECT_EQ(q.at(std::nan("")).p, 1.0);
}

TEST(Quintic, PeaksAreExact) {
  const Quintic q({0.0, 1.5, -2.0}, {0.4, 0.0, 0.0}, 1.1);
  double v = 0.0, a = 0.0, j = 0.0;
  for (int k = 0; k <= 200000; ++k) {
    const Quintic::Sample s = q.at(1.1 * k / 200000.0);
    v = std::max(v, std::abs(s.v));
    a = std::max(a, std::abs(s.a));
    if (k > 0 && k < 200000) j = std::max(j, std::abs(s.j));
  }
  const Quintic::Peaks peaks = q.peaks();
  EXPECT_GE(peaks.velocity, v - 1e-12);
  EXPECT_NEAR(peaks.velocity, v, 1e-8);
  EXPECT_GE(peaks.acceleration, a - 1e-12);
  EXPECT_NEAR(peaks.acceleration, a, 1e-7);
  EXPECT_NEAR(peaks.jerk, j, 1e-3);
}

TEST(QuinticTrajectory, JointsMatchTheScalarQuinticsAndBlendToRest) {
  QuinticTrajectory::State start{Eigen::VectorXd(3), Eigen::VectorXd(3), Eigen::VectorXd(3)};
  start.q << 0.1, -0.5, 1.0;
  start.qd << 0.4, 0.0, -0.3;
  start.qdd << -1.0, 0.5, 0.0;
  const Eigen::Vector3d goal(0.5, -0.5, 0.2);
  const QuinticTrajectory traj = QuinticTrajectory::to_rest(start, goal, 0.9);
  EXPECT_EQ(traj.size(), 3);
  Eigen::VectorXd q(3), qd(3), qdd(3), qddd(3);
  traj.at(0.0, q, qd, qdd);
  EXPECT_TRUE(q.isApprox(start.q, 1e-15));
  EXPECT_TRUE(qd.isApprox(start.qd, 1e-15));
  EXPECT_TRUE(qdd.isApprox(start.qdd, 1e-15));
  traj.at(0.9, q, qd, qdd);
  EXPECT_LT((q - goal).norm(), 1e-12);
  EXPECT_LT(qd.norm(), 1e-12);
  EXPECT_LT(qdd.norm(), 1e-10);
  for (double t : {0.1, 0.37, 0.8}) {
    traj.at(t, q, qd, qdd, qddd);
    for (Eigen::Index i = 0; i < 3; ++i) {
      const Quintic scalar({start.q[i], start.qd[i], start.qdd[i]}, {goal[i], 0.0, 0.0}, 0.9);
      EXPECT_NEAR(q[i], scalar.at(t).p, 1e-14);
      EXPECT_NEAR(qd[i], scalar.at(t).v, 1e-13);
      EXPECT_NEAR(qdd[i], scalar.at(t).a, 1e-12);
      EXPECT_NEAR(qddd[i], scalar.at(t).j, 1e-11);
      EXPECT_NEAR(traj.joint(i).at(t).p, scalar.at(t).p, 1e-12);
    }
  }
  traj.at(2.0, q, qd, qdd, qddd);
  EXPECT_EQ(qddd.norm(), 0.0);
}

TEST(Quintic, ZeroDurationOnlyBetweenEqualPositionsAndVelocities) {
  const Quintic step({0.3, 0.0, 1.0}, {0.3, 0.0, -1.0}, 0.0);
  EXPECT_EQ(step.at(0.0).p, 0.3);
  EXPECT_EQ(step.at(0.0).a, -1.0);
  EXPECT_THROW(Quintic({0.3, 0.0, 0.0}, {0.4, 0.0, 0.0}, 0.0), Error);
  EXPECT_THROW(Quintic({0.3, 1.0, 0.0}, {0.3, 0.0, 0.0}, 0.0), Error);
}

TEST(Quintic, RejectsBadInput) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  constexpr double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Quintic({0, 0, 0}, {1, 0, 0}, -1.0), Error);
  EXPECT_THROW(Quintic({0, 0, 0}, {1, 0, 0}, inf), Error);
  EXPECT_THROW(Quintic({nan, 0, 0}, {1, 0, 0}, 1.0), Error);
  EXPECT_THROW(Quintic({0, inf, 0}, {1, 0, 0}, 1.0), Error);
  EXPECT_THROW(Quintic({0, 0, 0}, {1, 0, nan}, 1.0), Error);
  // durations out of scale with the move overflow the polynomial: an error, not NaN samples
  EXPECT_NE(test::error_of([] {
              Quintic({0, 0, 0}, {1, 0, 0}, 1e-300);
            }).find("out of scale"),
            std::string::npos);
  EXPECT_THROW(Quintic({0, 0, 1}, {1, 0, 0}, 1e300), Error);
  // while wide but representable scales still work
  const Quintic slow({0, 0, 0}, {1e-3, 0, 0}, 1e4);
  EXPECT_NEAR(slow.at(5e3).p, 5e-4, 1e-15);
  const Quintic fast({0, 0, 0}, {1e3, 0, 0}, 1e-3);
  EXPECT_NEAR(fast.at(1e-3).p, 1e3, 1e-9);
  const Eigen::VectorXd z2 = Eigen::VectorXd::Zero(2), z3 = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(QuinticTrajectory({z2, z2, z2}, {z3, z3, z3}, 1.0), Error);
  EXPECT_THROW(QuinticTrajectory({Eigen::VectorXd(), Eigen::VectorXd(), Eigen::VectorXd()},
                                 {Eigen::VectorXd(), Eigen::VectorXd(), Eigen::VectorXd()}, 1.0),
               Error);
  Eigen::VectorXd bad = z2;
  bad[1] = nan;
  EXPECT_NE(test::error_of([&] {
              QuinticTrajectory({z2, bad, z2}, {z2, z2, z2}, 1.0);
            }).find("joint 1"),
            std::string::npos);
  const QuinticTrajectory ok({z2, z2, z2}, {Eigen::VectorXd::Ones(2), z2, z2}, 1.0);
  Eigen::VectorXd q(2), qd(3), qdd(2);
  EXPECT_THROW(ok.at(0.5, q, qd, qdd), Error);
  EXPECT_THROW(ok.joint(2), Error);
}

}  // namespace
}  // namespace mjarm
