#include "mjarm/trajectory/quintic_duration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <utility>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {
namespace {

using State = QuinticTrajectory::State;

State joint_state(std::initializer_list<double> q, std::initializer_list<double> qd,
                  std::initializer_list<double> qdd) {
  State s{Eigen::VectorXd(static_cast<Eigen::Index>(q.size())),
          Eigen::VectorXd(static_cast<Eigen::Index>(qd.size())),
          Eigen::VectorXd(static_cast<Eigen::Index>(qdd.size()))};
  Eigen::Index i = 0;
  for (double v : q) s.q[i++] = v;
  i = 0;
  for (double v : qd) s.qd[i++] = v;
  i = 0;
  for (double v : qdd) s.qdd[i++] = v;
  return s;
}

// Brute force, independent of the exact search: the limits checked on a dense grid of instants
// (no root finding), durations scanned upwards on a fine geometric grid.
bool sampled_feasible(const State& a, const State& b, const Eigen::VectorXd& v_max,
                      const Eigen::VectorXd& a_max, double T) {
  for (Eigen::Index i = 0; i < a.q.size(); ++i) {
    const Quintic q({a.q[i], a.qd[i], a.qdd[i]}, {b.q[i], b.qd[i], b.qdd[i]}, T);
    for (int k = 0; k <= 600; ++k) {
      const Quintic::Sample s = q.at(T * k / 600.0);
      // the slack of the exact search: boundary values may sit exactly at a limit
      if (std::abs(s.v) > v_max[i] * (1 + 1e-9) || std::abs(s.a) > a_max[i] * (1 + 1e-9))
        return false;
    }
  }
  return true;
}

double brute_force_shortest(const State& a, const State& b, const Eigen::VectorXd& v_max,
                            const Eigen::VectorXd& a_max) {
  for (double T = 1e-3; T < 200.0; T *= 1.0005)
    if (sampled_feasible(a, b, v_max, a_max, T)) return T;
  return std::numeric_limits<double>::infinity();
}

TEST(QuinticDuration, RestToRestMatchesTheClosedForm) {
  // rest to rest is the minimum-jerk profile: T = max(1.875·h/v, √(5.7735·h/a))
  const State a = joint_state({0.0, 1.0}, {0, 0}, {0, 0});
  const State b = joint_state({0.8, 0.9}, {0, 0}, {0, 0});
  const Eigen::Vector2d v_max(1.0, 1.0), a_max(4.0, 4.0);
  const QuinticDuration d = shortest_quintic_duration(a, b, v_max, a_max);
  ASSERT_EQ(d.status, QuinticDurationStatus::ok);
  EXPECT_NEAR(d.duration, SmoothRamp::duration_for(SmoothRamp::Kind::smootherstep, 0.8, 1.0, 4.0),
              1e-12);
  EXPECT_EQ(d.limiting_joint, 0);
  EXPECT_TRUE(d.velocity_limited);  // 1.5 s by velocity > 1.07 s by acceleration
  const QuinticDuration da = shortest_quintic_duration(a, b, Eigen::Vector2d(10, 10), a_max);
  EXPECT_NEAR(da.duration, std::sqrt(10.0 / std::sqrt(3.0) * 0.8 / 4.0), 1e-12);
  EXPECT_FALSE(da.velocity_limited);
}

TEST(QuinticDuration, MatchesABruteForceSearchFromMovingStarts) {
  mjarm::Random rng(2024);
  const auto u = [](mjarm::Random& r) { return mjarm::uniform(r, -1.0, 1.0); };
  const auto lim = [](mjarm::Random& r) { return mjarm::uniform(r, 0.5, 3.0); };
  // 12 cases in the suite; MJARM_QUINTIC_TRIALS=N runs N (docs/trajectory.md has the figures)
  const char* env = std::getenv("MJARM_QUINTIC_TRIALS");
  const int trials = env ? std::max(1, std::atoi(env)) : 12;
  int compared = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Index n = 1 + trial % 3;
    State a{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
    State b{Eigen::VectorXd(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
    Eigen::VectorXd v_max(n), a_max(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      v_max[i] = lim(rng);
      a_max[i] = lim(rng);
      a.q[i] = u(rng);
      b.q[i] = u(rng);
      a.qd[i] = 0.9 * v_max[i] * u(rng);
      a.qdd[i] = 0.9 * a_max[i] * u(rng);
      if (trial % 2 == 1) {  // arbitrary end states too
        b.qd[i] = 0.5 * v_max[i] * u(rng);
        b.qdd[i] = 0.5 * a_max[i] * u(rng);
      }
    }
    const QuinticDuration d = shortest_quintic_duration(a, b, v_max, a_max);
    const double brute = brute_force_shortest(a, b, v_max, a_max);
    if (d.status != QuinticDurationStatus::ok) {
      EXPECT_TRUE(std::isinf(brute)) << trial << ": " << to_string(d.status) << ", brute " << brute;
      continue;
    }
    ++compared;
    // the brute force's first feasible duration is within its grid step of the exact one
    EXPECT_NEAR(brute / d.duration, 1.0, 1.5e-3) << trial << ": exact " << d.duration;
    // the exact duration holds the limits at the exact peaks; a little shorter does not
    const QuinticTrajectory at_limit(a, b, d.duration);
    const QuinticTrajectory shorter(a, b, d.duration * (1 - 1e-6));
    bool shorter_breaks = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Quintic::Peaks p = at_limit.joint(i).peaks();
      EXPECT_LE(p.velocity, v_max[i] * (1 + 1e-9));
      EXPECT_LE(p.acceleration, a_max[i] * (1 + 1e-9));
      const Quintic::Peaks s = shorter.joint(i).peaks();
      shorter_breaks = shorter_breaks || s.velocity > v_max[i] || s.acceleration > a_max[i];
    }
    EXPECT_TRUE(shorter_breaks) << trial;
    const Quintic::Peaks limiting = at_limit.joint(d.limiting_joint).peaks();
    const double ratio = d.velocity_limited ? limiting.velocity / v_max[d.limiting_joint]
                                            : limiting.acceleration / a_max[d.limiting_joint];
    EXPECT_NEAR(ratio, 1.0, 1e-9);
  }
  EXPECT_GE(compared, trials * 2 / 3);
  std::printf(
      "%d of %d cases compared with the brute force (the rest: no feasible duration, and none "
      "found by the brute force)\n",
      compared, trials);
}

TEST(QuinticDuration, FeasibilityIsNotMonotoneAndTheSmallestIsFound) {
  // moving away from a goal just behind, and accelerating back: the durations that keep
  // |q̇| ≤ 1 and |q̈| ≤ 5 are about [0.2383, 0.268) and [0.3795, 5.862) — a gap, and an upper end
  // (long moves overshoot the speed limit) — so no bisection on T could find the smallest
  const State a = joint_state({0.0}, {-0.95}, {4.0});
  const State b = joint_state({-0.1}, {0.0}, {0.0});
  const Eigen::VectorXd v_max = Eigen::VectorXd::Constant(1, 1.0);
  const Eigen::VectorXd a_max = Eigen::VectorXd::Constant(1, 5.0);
  const auto feasible_at = [&](double T) {
    const Quintic::Peaks p = Quintic({0.0, -0.95, 4.0}, {-0.1, 0.0, 0.0}, T).peaks();
    return p.velocity <= 1.0 && p.acceleration <= 5.0;
  };
  EXPECT_TRUE(feasible_at(0.25));
  EXPECT_FALSE(feasible_at(0.3));
  EXPECT_TRUE(feasible_at(1.0));
  EXPECT_FALSE(feasible_at(10.0));
  const QuinticDuration d = shortest_quintic_duration(a, b, v_max, a_max);
  ASSERT_EQ(d.status, QuinticDurationStatus::ok);
  EXPECT_NEAR(d.duration, 0.2383, 1e-4);
  EXPECT_FALSE(d.velocity_limited);
  EXPECT_NEAR(brute_force_shortest(a, b, v_max, a_max) / d.duration, 1.0, 1.5e-3);
  // with a floor inside the gap, the next feasible stretch begins at its lower end
  const QuinticDuration later = shortest_quintic_duration(a, b, v_max, a_max, 0.3);
  ASSERT_EQ(later.status, QuinticDurationStatus::ok);
  EXPECT_NEAR(later.duration, 0.3795, 1e-3);
  EXPECT_TRUE(feasible_at(later.duration * (1 + 1e-9)));
  EXPECT_FALSE(feasible_at(later.duration * (1 - 1e-6)));
}

TEST(QuinticDuration, BoundaryValuesExactlyAtTheirLimits) {
  // a limit met at an end whatever T: the feasible durations begin where the first τ-derivative
  // there changes sign, not where an interior extremum touches (these came out 3–9 times too
  // long, or infeasible, before endpoint candidates were added)
  const Eigen::VectorXd v_max = Eigen::VectorXd::Constant(1, 1.0);
  const Eigen::VectorXd a_max = Eigen::VectorXd::Constant(1, 2.0);
  const std::vector<std::pair<State, State>> cases{
      {joint_state({0}, {1.0}, {-2.0}), joint_state({1.355}, {0}, {-2.0})},
      {joint_state({0}, {-0.491}, {2.0}), joint_state({0.022}, {0}, {0})},
      {joint_state({0}, {-1.0}, {2.0}), joint_state({-0.242}, {0}, {0})},
      {joint_state({0}, {0.356}, {-0.796}), joint_state({1.812}, {1.0}, {0})},
      {joint_state({0}, {-1.0}, {0.147}), joint_state({0.556}, {1.0}, {0})}};
  for (const auto& [a, b] : cases) {
    const QuinticDuration d = shortest_quintic_duration(a, b, v_max, a_max);
    ASSERT_EQ(d.status, QuinticDurationStatus::ok) << a.qd[0] << " " << a.qdd[0];
    EXPECT_NEAR(brute_force_shortest(a, b, v_max, a_max) / d.duration, 1.0, 1.5e-3)
        << a.qd[0] << " " << a.qdd[0] << ": exact " << d.duration;
  }
}

TEST(QuinticDuration, HonestStatusWhenNoDurationWorks) {
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(1);
  // a start beyond the velocity limit: no duration helps
  QuinticDuration d =
      shortest_quintic_duration(joint_state({0}, {1.5}, {0}), joint_state({1}, {0}, {0}), one, one);
  EXPECT_EQ(d.status, QuinticDurationStatus::start_beyond_limits);
  EXPECT_EQ(d.limiting_joint, 0);
  EXPECT_TRUE(d.velocity_limited);
  d = shortest_quintic_duration(joint_state({0}, {0}, {0}), joint_state({1}, {0}, {-2}), one, one);
  EXPECT_EQ(d.status, QuinticDurationStatus::end_beyond_limits);
  // at the speed limit and still accelerating: the speed exceeds it right after t = 0
  d = shortest_quintic_duration(joint_state({0}, {1.0}, {0.5}), joint_state({3}, {0}, {0}), one,
                                one);
  EXPECT_EQ(d.status, QuinticDurationStatus::infeasible);
  EXPECT_STREQ(to_string(d.status), "infeasible");
  // nothing to do: zero duration; with a floor: the floor
  d = shortest_quintic_duration(joint_state({0.4}, {0}, {0}), joint_state({0.4}, {0}, {0}), one,
                                one);
  EXPECT_EQ(d.status, QuinticDurationStatus::ok);
  EXPECT_EQ(d.duration, 0.0);
  d = shortest_quintic_duration(joint_state({0.4}, {0}, {0}), joint_state({0.4}, {0}, {0}), one,
                                one, 0.2);
  EXPECT_EQ(d.duration, 0.2);
  // a floor above the shortest duration
  d = shortest_quintic_duration(joint_state({0}, {0}, {0}), joint_state({0.1}, {0}, {0}), one,
                                Eigen::VectorXd::Constant(1, 100.0), 3.0);
  EXPECT_EQ(d.duration, 3.0);
}

TEST(QuinticDuration, RejectsBadInput) {
  const State a = joint_state({0, 0}, {0, 0}, {0, 0});
  const State b = joint_state({1, 1}, {0, 0}, {0, 0});
  const Eigen::Vector2d one(1, 1);
  EXPECT_THROW(shortest_quintic_duration(a, b, Eigen::Vector2d(1, 0), one), Error);
  EXPECT_THROW(shortest_quintic_duration(a, b, one, Eigen::Vector2d(1, -1)), Error);
  EXPECT_THROW(shortest_quintic_duration(a, b, Eigen::Vector3d(1, 1, 1), one), Error);
  EXPECT_THROW(shortest_quintic_duration(a, b, one, one, -1.0), Error);
  State nan_state = b;
  nan_state.qd[1] = std::nan("");
  EXPECT_THROW(shortest_quintic_duration(a, nan_state, one, one), Error);
  State inf_state = a;
  inf_state.q[0] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(shortest_quintic_duration(inf_state, b, one, one), Error);
}

}  // namespace
}  // namespace mjarm
