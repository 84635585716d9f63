// The viewer's target filter on the jerk-limited generator: a jump becomes a motion within the
// limits at every tick, a target moved mid-motion continues from the current velocity, the twist
// is the derivative of the pose, nothing allocates, bad input is refused or ignored.
#include "mjarm/trajectory/target_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm {
namespace {

/// Largest |coordinate rate| / limit over the linear (first three) or angular coordinates.
struct Usage {
  double v = 0.0, a = 0.0;
};
Usage usage(const TargetFilter& f, bool angular) {
  const TargetFilterLimits& l = f.limits();
  Usage u;
  for (int i = angular ? 3 : 0; i < (angular ? 6 : 3); ++i) {
    const KinematicState& s = f.coordinates()[static_cast<std::size_t>(i)];
    u.v = std::max(u.v, std::abs(s.v) / (angular ? l.angular_velocity : l.velocity));
    u.a = std::max(u.a, std::abs(s.a) / (angular ? l.angular_acceleration : l.acceleration));
  }
  return u;
}

/// Runs @p f towards @p X_WT for at most @p seconds at @p dt, checking the limits at every tick:
/// coordinates within their velocity and acceleration limits, the change of acceleration per tick
/// within jerk·dt, the pose's twist equal to the change of pose (to first order), ‖ω‖ ≤ ‖φ̇‖.
/// Returns the ticks until settled (−1 if it never settled).
int run_checked(TargetFilter& f, const Pose& X_WT, double dt, double seconds, Usage& peak) {
  const TargetFilterLimits& l = f.limits();
  const int ticks = static_cast<int>(std::lround(seconds / dt));
  for (int k = 0; k < ticks; ++k) {
    const Pose before = f.pose();
    const Vector6d A_before = f.acceleration();
    f.update(X_WT, dt);
    EXPECT_NE(f.status(), OtgStatus::error_no_profile);
    for (const bool angular : {false, true}) {
      const Usage u = usage(f, angular);
      peak.v = std::max(peak.v, u.v);
      peak.a = std::max(peak.a, u.a);
      if (!angular) {
        EXPECT_LE(u.v, 1.0 + 1e-9) << "tick " << k;
        EXPECT_LE(u.a, 1.0 + 1e-9) << "tick " << k;
      }
    }
    // jerk: the acceleration of each coordinate moves by at most j_max·dt per tick
    const Vector6d dA = f.acceleration() - A_before;
    EXPECT_LE(dA.head<3>().cwiseAbs().maxCoeff(), l.jerk * dt * (1 + 1e-9)) << "tick " << k;
    // the mean velocity over the tick is within the limit (per axis)
    EXPECT_LE(((f.pose().p - before.p) / dt).cwiseAbs().maxCoeff(), l.velocity * (1 + 1e-9));
    // ‖ω‖ ≤ ‖φ̇‖
    Eigen::Vector3d phi_dot;
    for (int i = 0; i < 3; ++i) phi_dot[i] = f.coordinates()[static_cast<std::size_t>(i + 3)].v;
    EXPECT_LE(f.velocity().tail<3>().norm(), phi_dot.norm() * (1 + 1e-12) + 1e-15);
    if (f.settled()) return k + 1;
  }
  return -1;
}

TEST(TargetFilter, AJumpBecomesAMotionWithinTheLimitsThatLandsExactly) {
  TargetFilter filter;  // 0.5 m/s, 2 m/s², 20 m/s³; 1.5 rad/s, 6 rad/s², 60 rad/s³
  const Pose start = Pose::from_rotation_vector({0.3, 0.0, 0.5}, {3.0, 0.1, 0.0});
  const Pose goal = Pose::from_rotation_vector({0.55, 0.1, 0.35}, {2.6, -0.3, 0.7});
  filter.reset(start);
  EXPECT_TRUE(filter.settled());
  Usage peak;
  const double dt = 0.001;
  const int ticks = run_checked(filter, goal, dt, 5.0, peak);
  ASSERT_GT(ticks, 0);
  EXPECT_TRUE(filter.pose().is_approx(goal, 0.0));  // lands exactly
  EXPECT_EQ(filter.velocity().norm(), 0.0);
  EXPECT_EQ(filter.acceleration().norm(), 0.0);
  // the time-optimal synchronized motion uses a limit fully (to the tick)
  EXPECT_GT(peak.v, 0.95);
  EXPECT_NEAR(ticks * dt, filter.motion_duration(), dt);
  // on the angular coordinates the limits hold too when nothing re-anchors mid-motion
  EXPECT_LE(peak.v, 1.0 + 1e-9);
  EXPECT_LE(peak.a, 1.0 + 1e-9);
}

TEST(TargetFilter, TheTwistAndItsRateAreTheDerivativesOfThePose) {
  TargetFilterLimits limits;
  limits.angular_velocity = 3.0;
  TargetFilter a(limits), b(limits);
  const Pose start = Pose::from_rotation_vector({0.3, 0.0, 0.5}, {0.2, 0.1, -0.4});
  const Pose goal = Pose::from_rotation_vector({0.1, 0.2, 0.6}, {-0.9, 1.2, 1.5});
  a.reset(start);
  b.reset(start);
  // b runs h behind a: (pose_a − pose_b)/h is the twist at the middle
  const double dt = 0.004, h = 1e-6;
  a.update(goal, h);
  for (int k = 0; k < 150; ++k) {
    const Vector6d V_mid = 0.5 * (a.velocity() + b.velocity());
    Vector6d V;
    V.head<3>() = (a.pose().p - b.pose().p) / h;
    V.tail<3>() = so3::log(a.pose().R * b.pose().R.transpose()) / h;
    if (k > 0) {  // (the first pair straddles the start of the motion)
      EXPECT_LT((V - V_mid).norm(), 1e-6) << k;
      Vector6d A = (a.velocity() - b.velocity()) / h;
      EXPECT_LT((A - 0.5 * (a.acceleration() + b.acceleration())).norm(), 1e-3) << k;
    }
    a.update(goal, dt);
    b.update(goal, dt);
  }
}

TEST(TargetFilter, ATargetMovedMidMotionContinuesFromTheCurrentVelocity) {
  TargetFilter filter;
  const TargetFilterLimits& l = filter.limits();
  const Pose start = Pose::from_rotation_vector({0.3, 0.0, 0.5}, {3.0, 0.0, 0.0});
  filter.reset(start);
  const double dt = 0.002;
  Usage peak;
  // towards +x (and a turn); stop checking after 0.3 s, well into the motion
  const Pose first = Pose::from_rotation_vector({0.7, 0.0, 0.5}, {3.0, 0.0, 0.5});
  ASSERT_EQ(run_checked(filter, first, dt, 0.3, peak), -1);
  const Vector6d V_before = filter.velocity();
  const Vector6d A_before = filter.acceleration();
  ASSERT_GT(V_before[0], 0.3);  // moving fast along +x
  // the target jumps behind and to the side
  const Pose second = Pose::from_rotation_vector({0.2, 0.2, 0.45}, {2.9, 0.2, -0.3});
  filter.update(second, dt);
  const Vector6d V_after = filter.velocity();
  // continuous: the velocity changes by at most a_max·dt per coordinate, the acceleration by
  // at most j_max·dt; it still moves along +x (it has to brake first)
  EXPECT_LE((V_after - V_before).head<3>().cwiseAbs().maxCoeff(), l.acceleration * dt * (1 + 1e-9));
  EXPECT_LE((filter.acceleration() - A_before).head<3>().cwiseAbs().maxCoeff(),
            l.jerk * dt * (1 + 1e-9));
  EXPECT_LT((V_after - V_before).tail<3>().norm(), 2.0 * l.angular_acceleration * dt);
  EXPECT_GT(V_after[0], 0.3);
  // a filter started at rest at the same pose would not move at all this tick
  TargetFilter rest;
  rest.reset(filter.pose());
  rest.update(second, dt);
  EXPECT_LT(rest.velocity().head<3>().norm(), l.jerk * dt * dt);
  // and it gets there, within the limits all the way
  ASSERT_GT(run_checked(filter, second, dt, 5.0, peak), 0);
  EXPECT_TRUE(filter.pose().is_approx(second, 0.0));
  // re-anchoring the rotation vector may start it slightly beyond a per-component limit (ω is φ̇
  // turned by Jl), which the generator brakes; the norm bound ‖ω‖ ≤ ‖φ̇‖ ≤ √3·limit holds
  EXPECT_LE(peak.v, std::sqrt(3.0) * (1 + 1e-9));
}

TEST(TargetFilter, ADraggedTargetIsFollowedWithinTheLimitsWithoutAllocating) {
  // the target moves every tick, faster than the limits allow: the reference lags, stays within
  // the limits, recalculates every tick without allocating, and settles once the target stops
  TargetFilter filter;
  const Pose start = Pose::from_rotation_vector({0.3, 0.0, 0.5}, {3.0, 0.0, 0.0});
  filter.reset(start);
  const double dt = 0.01;
  Usage peak;
  Pose target = start;
  filter.update(Pose::from_rotation_vector({0.31, 0.0, 0.5}, {3.0, 0.0, 0.0}), dt);  // warm-up
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 60; ++k) {
    const double s = 0.02 * k;
    target = Pose::from_rotation_vector({0.3 + 0.8 * s, 0.2 * std::sin(5 * s), 0.5},
                                        {3.0, 0.0, 0.4 * s});
    ASSERT_EQ(run_checked(filter, target, dt, dt, peak), -1) << k;
  }
  const std::uint64_t after = test::malloc_calls();
  EXPECT_EQ(after - before, 0u);
  EXPECT_GT((filter.pose().p - target.p).norm(), 0.05);  // 1.3 m/s asked, 0.5 m/s allowed
  ASSERT_GT(run_checked(filter, target, dt, 10.0, peak), 0);
  EXPECT_TRUE(filter.pose().is_approx(target, 0.0));
}

TEST(TargetFilter, BadInputIsRefusedOrIgnored) {
  const auto with = [](double TargetFilterLimits::*field, double value) {
    TargetFilterLimits l;
    l.*field = value;
    return l;
  };
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {0.0, -1.0, inf, std::nan("")}) {
    EXPECT_THROW(TargetFilter(with(&TargetFilterLimits::velocity, bad)), Error) << bad;
    EXPECT_THROW(TargetFilter(with(&TargetFilterLimits::acceleration, bad)), Error) << bad;
    EXPECT_THROW(TargetFilter(with(&TargetFilterLimits::jerk, bad)), Error) << bad;
    EXPECT_THROW(TargetFilter(with(&TargetFilterLimits::angular_velocity, bad)), Error) << bad;
    EXPECT_THROW(TargetFilter(with(&TargetFilterLimits::angular_acceleration, bad)), Error) << bad;
    EXPECT_THROW(TargetFilter(with(&TargetFilterLimits::angular_jerk, bad)), Error) << bad;
  }
  try {
    TargetFilter(with(&TargetFilterLimits::angular_jerk, -2.0));
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("angular_jerk"), std::string::npos) << e.what();
  }
  TargetFilter filter;
  const Pose start = Pose::from_rotation_vector({0.3, 0.0, 0.5}, {3.0, 0.0, 0.0});
  const Pose goal = Pose::from_rotation_vector({0.4, 0.0, 0.5}, {3.0, 0.0, 0.0});
  filter.reset(start);
  // a bad dt leaves the reference where it is
  for (double dt : {0.0, -0.01, std::nan(""), inf}) {
    filter.update(goal, dt);
    EXPECT_TRUE(filter.pose().is_approx(start, 0.0)) << dt;
  }
  // a target that is not finite is ignored: the last one is kept
  filter.update(goal, 0.01);
  Pose broken = goal;
  broken.p.x() = std::nan("");
  for (int k = 0; k < 100; ++k) filter.update(broken, 0.01);
  EXPECT_TRUE(filter.target().is_approx(goal, 0.0));
  EXPECT_TRUE(filter.pose().p.allFinite());
  EXPECT_TRUE(filter.settled());
  EXPECT_TRUE(filter.pose().is_approx(goal, 0.0));
}

}  // namespace
}  // namespace mjarm
