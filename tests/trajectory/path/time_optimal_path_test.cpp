#include "mjarm/trajectory/path/time_optimal_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/path/validation/topp_protocol.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {
namespace {

// A straight line q0 + s·d (‖d‖ = 1) is a scalar move in s under ṡ ≤ min_j v_j/|d_j| and
// |s̈| ≤ min_j a_j/|d_j|: the trapezoid (or triangle) of its length is the exact optimum. The
// grid profile can only be slower (x is piecewise linear in s and its corners need not fall on
// grid points), by O(Δ).
double topp_line_duration(double length, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                          const Eigen::VectorXd& a) {
  const double v_s = (v.array() / d.array().abs()).minCoeff();
  const double a_s = (a.array() / d.array().abs()).minCoeff();
  return TrapezoidProfile(length, v_s, a_s).duration();
}

TEST(TimeOptimalPath, StraightLineGivesTheTrapezoidAndTriangleDurations) {
  Eigen::VectorXd q0(3), d(3), v(3), a(3);
  q0 << 0.2, -0.1, 0.5;
  d << 2.0, -1.0, 2.0;
  d /= 3.0;
  v << 1.0, 0.5, 2.0;
  a << 2.0, 3.0, 1.5;
  for (const double length : {0.05, 0.3, 4.0}) {  // triangles, then a trapezoid
    const JointPath line({q0, q0 + length * d});
    const double exact = topp_line_duration(length, d, v, a);
    for (const int N : {50, 400}) {
      ToppOptions options;
      options.grid_intervals = N;
      const TimeOptimalPath topp(line, v, a, options);
      ASSERT_TRUE(topp.solved());
      EXPECT_GE(topp.duration(), exact * (1.0 - 1e-9)) << "L " << length << " N " << N;
      EXPECT_LE(topp.duration(), exact * (1.0 + 2.0 / N)) << "L " << length << " N " << N;
    }
  }
}

TEST(TimeOptimalPath, StartsAndEndsAtRestOnTheWaypoints) {
  Random rng(3);
  const ToppCase c = random_topp_case(rng, 7);
  const JointPath path(c.waypoints);
  const TimeOptimalPath topp(path, c.max_velocity, c.max_acceleration);
  ASSERT_TRUE(topp.solved());
  TrajectorySample sample;
  topp.at(0.0, sample);
  EXPECT_LT((sample.position - c.waypoints.front()).norm(), 1e-12);
  EXPECT_LT(sample.velocity.norm(), 1e-12);
  topp.at(topp.duration(), sample);
  EXPECT_LT((sample.position - c.waypoints.back()).norm(), 1e-12);
  EXPECT_LT(sample.velocity.norm(), 1e-12);
  // the waypoints are passed in order, in motion
  for (int k = 1; k + 1 < path.waypoint_count(); ++k) {
    double lo = 0.0, hi = topp.duration();
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      (topp.path_state(mid).s < path.knots()[k] ? lo : hi) = mid;
    }
    topp.at(hi, sample);
    EXPECT_LT((sample.position - c.waypoints[static_cast<std::size_t>(k)]).norm(), 1e-9);
    EXPECT_GT(topp.path_state(hi).ds, 0.0) << "stopped at waypoint " << k;
  }
}

// The paper's guarantee: the backward pass's K_0 holds 0, so the forward pass runs through, and
// every x_i lies in K_i.
TEST(TimeOptimalPath, ForwardPassStaysInTheControllableSets) {
  Random rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const ToppCase c = random_topp_case(rng, 7);
    const TimeOptimalPath topp(JointPath(c.waypoints), c.max_velocity, c.max_acceleration);
    ASSERT_TRUE(topp.solved()) << "trial " << trial;
    const Eigen::Matrix2Xd& K = topp.controllable_sets();
    EXPECT_LE(K(0, 0), 0.0);
    EXPECT_EQ(K(1, K.cols() - 1), 0.0);
    for (Eigen::Index i = 0; i < K.cols(); ++i) {
      const double x = topp.squared_speeds()[i];
      EXPECT_GE(x, K(0, i) - 1e-12 * (1.0 + K(1, i))) << "trial " << trial << " i " << i;
      EXPECT_LE(x, K(1, i) + 1e-12 * (1.0 + K(1, i))) << "trial " << trial << " i " << i;
    }
    EXPECT_GT(topp.duration(), 0.0);
  }
}

// Sampled q̇ and q̈ against the limits: at the grid points exactly (1e-9 relative), everywhere
// within the discretization's error: 15 % at N = 100 and 3 % at N = 400 (the worst of the bench's
// 10 000 paths at N = 100 is 12 %, of 1000 at N = 400 1.9 %: docs/trajectory.md). And q̇, q̈ and q⃛
// are the time derivatives of q, q̇ and q̈ (central differences inside a step, where s̈ is constant).
TEST(TimeOptimalPath, SamplesKeepTheLimitsAndAreConsistent) {
  Random rng(5);
  TrajectorySample sample, plus, minus;
  for (int trial = 0; trial < 10; ++trial) {
    const ToppCase c = random_topp_case(rng, 7);
    ToppOptions options;
    options.grid_intervals = trial % 2 == 0 ? 100 : 400;
    const TimeOptimalPath topp(JointPath(c.waypoints), c.max_velocity, c.max_acceleration, options);
    ASSERT_TRUE(topp.solved());
    const Eigen::VectorXd& times = topp.grid_times();
    double worst_grid = 0.0, worst = 0.0;
    for (Eigen::Index i = 0; i + 1 < times.size(); ++i) {
      const double t0 = times[i], t1 = times[i + 1];
      for (const double f : {1e-12, 0.25, 0.5, 0.75, 1.0 - 1e-12}) {
        const double t = t0 + f * (t1 - t0);
        topp.at(t, sample);
        const double excess =
            std::max(
                (sample.velocity.cwiseAbs().array() / c.max_velocity.array()).maxCoeff(),
                (sample.acceleration.cwiseAbs().array() / c.max_acceleration.array()).maxCoeff()) -
            1.0;
        (f < 1e-6 || f > 1.0 - 1e-6 ? worst_grid : worst) =
            std::max(f < 1e-6 || f > 1.0 - 1e-6 ? worst_grid : worst, excess);
      }
      const double t = 0.5 * (t0 + t1), h = 1e-4 * (t1 - t0);
      topp.at(t, sample);
      topp.at(t + h, plus);
      topp.at(t - h, minus);
      const double scale = 1.0 + sample.velocity.norm() + sample.acceleration.norm();
      EXPECT_LT((sample.velocity - (plus.position - minus.position) / (2 * h)).norm(),
                1e-5 * scale);
      EXPECT_LT((sample.acceleration - (plus.velocity - minus.velocity) / (2 * h)).norm(),
                1e-5 * scale);
      EXPECT_LT((sample.jerk - (plus.acceleration - minus.acceleration) / (2 * h)).norm(),
                1e-4 * (scale + sample.jerk.norm()));
    }
    EXPECT_LE(worst_grid, 1e-9) << "trial " << trial;
    EXPECT_LE(worst, trial % 2 == 0 ? 0.15 : 0.03) << "trial " << trial;
  }
}

TEST(TimeOptimalPath, FinerGridsConverge) {
  Random rng(9);
  const ToppCase c = random_topp_case(rng, 7);
  const JointPath path(c.waypoints);
  double previous = 0.0;
  for (const int N : {50, 200, 800, 3200}) {
    ToppOptions options;
    options.grid_intervals = N;
    const TimeOptimalPath topp(path, c.max_velocity, c.max_acceleration, options);
    ASSERT_TRUE(topp.solved());
    if (N > 50) EXPECT_LT(std::abs(topp.duration() - previous), 0.02 * previous) << "N " << N;
    if (N == 3200) EXPECT_LT(std::abs(topp.duration() - previous), 1e-3 * previous);
    previous = topp.duration();
  }
}

TEST(TimeOptimalPath, SamplingAllocatesNothing) {
  Random rng(1);
  const ToppCase c = random_topp_case(rng, 7);
  const TimeOptimalPath topp =
      parameterize(JointPath(c.waypoints), c.max_velocity, c.max_acceleration);
  TrajectorySample sample(7);
  double sink = 0.0;
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k <= 200; ++k) {
    topp.at(topp.duration() * k / 200.0, sample);
    sink += sample.position.sum() + sample.jerk.sum() + topp.path_state(0.01 * k).s;
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_TRUE(std::isfinite(sink));
}

std::string topp_error(const Eigen::VectorXd& v, const Eigen::VectorXd& a, int N = 100) {
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(2), q1 = Eigen::VectorXd::Ones(2);
  ToppOptions options;
  options.grid_intervals = N;
  try {
    const TimeOptimalPath topp(JointPath({q0, q1}), v, a, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(TimeOptimalPath, RejectsBadLimitsNamingThem) {
  const Eigen::Vector2d ok(1.0, 2.0);
  EXPECT_NE(topp_error(Eigen::Vector2d(1.0, 0.0), ok).find("max_velocity[1] must be positive"),
            std::string::npos);
  EXPECT_NE(topp_error(ok, Eigen::Vector2d(-1.0, 1.0)).find("max_acceleration[0] must be positive"),
            std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(topp_error(Eigen::Vector2d(nan, 1.0), ok).find("max_velocity[0]"), std::string::npos);
  EXPECT_NE(topp_error(ok, Eigen::Vector2d(1.0, std::numeric_limits<double>::infinity()))
                .find("max_acceleration[1]"),
            std::string::npos);
  EXPECT_NE(topp_error(Eigen::Vector3d::Ones(), ok).find("max_velocity has 3 entries"),
            std::string::npos);
  EXPECT_NE(topp_error(ok, ok, 1).find("grid_intervals"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
