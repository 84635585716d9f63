#include "mjarm/trajectory/path/jerk_waypoints.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/path/validation/topp_protocol.hpp"

namespace mjarm {
namespace {

// Seeded paths: the waypoints are passed in motion, every segment keeps v, a and j at its
// analytic extrema (the generator's profiles), the state is continuous from segment to segment,
// and not stopping beats stopping at every waypoint.
TEST(JerkWaypoints, PassesWaypointsInMotionWithinTheLimits) {
  Random rng(31);
  int faster = 0, moving_waypoints = 0;
  const int trials = 20;
  for (int trial = 0; trial < trials; ++trial) {
    const ToppCase c = random_topp_case(rng, 7);
    const JointPath path(c.waypoints);
    const TimeOptimalPath topp(path, c.max_velocity, c.max_acceleration);
    ASSERT_TRUE(topp.solved());
    const Eigen::VectorXd jerk = 10.0 * c.max_acceleration;
    const JerkWaypointTrajectory moving(topp, jerk);
    JerkWaypointOptions stop_options;
    stop_options.velocity_share = 0.0;
    const JerkWaypointTrajectory stopping(topp, jerk, stop_options);
    ASSERT_EQ(moving.segments(), path.waypoint_count() - 1);
    TrajectorySample before, after;
    for (int k = 0; k < moving.segments(); ++k) {
      const JerkLimitedGenerator& g = moving.segment(k);
      for (int j = 0; j < 7; ++j) {
        const JerkLimits limits{c.max_velocity[j], c.max_acceleration[j], jerk[j]};
        EXPECT_TRUE(g.profile(j).within(limits, 1e-9)) << "trial " << trial << " segment " << k;
      }
      const double t = moving.segment_start(k);
      moving.at(t, after);
      EXPECT_LT((after.position - c.waypoints[static_cast<std::size_t>(k)]).norm(), 1e-8);
      EXPECT_LT((after.velocity - moving.waypoint_velocities()[static_cast<std::size_t>(k)]).norm(),
                1e-8);
      if (k > 0) {
        moving.at(std::nextafter(t, 0.0), before);
        EXPECT_LT((after.position - before.position).norm(), 1e-8);
        EXPECT_LT((after.velocity - before.velocity).norm(), 1e-6);
        EXPECT_LT((after.acceleration - before.acceleration).norm(), 1e-6);
        if (after.velocity.norm() > 1e-3) ++moving_waypoints;
      }
    }
    moving.at(moving.duration(), after);
    EXPECT_LT((after.position - c.waypoints.back()).norm(), 1e-8);
    EXPECT_LT(after.velocity.norm(), 1e-8);
    if (moving.duration() < stopping.duration()) ++faster;
    // a stop is given where it shortens the two segments around it, so never much longer
    EXPECT_LE(moving.duration(), 1.1 * stopping.duration()) << "trial " << trial;
  }
  EXPECT_GE(faster, trials - 2);
  EXPECT_GT(moving_waypoints, trials);
}

TEST(JerkWaypoints, SamplingAllocatesNothing) {
  Random rng(4);
  const ToppCase c = random_topp_case(rng, 7);
  const TimeOptimalPath topp(JointPath(c.waypoints), c.max_velocity, c.max_acceleration);
  const JerkWaypointTrajectory trajectory(topp, 10.0 * c.max_acceleration);
  TrajectorySample sample(7);
  double sink = 0.0;
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k <= 100; ++k) {
    trajectory.at(trajectory.duration() * k / 100.0, sample);
    sink += sample.velocity.sum();
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_TRUE(std::isfinite(sink));
}

TEST(JerkWaypoints, RejectsBadJerkLimits) {
  Random rng(4);
  const ToppCase c = random_topp_case(rng, 7);
  const TimeOptimalPath topp(JointPath(c.waypoints), c.max_velocity, c.max_acceleration);
  Eigen::VectorXd jerk = Eigen::VectorXd::Ones(7);
  jerk[3] = 0.0;
  try {
    const JerkWaypointTrajectory trajectory(topp, jerk);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("max_jerk[3]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(JerkWaypointTrajectory(topp, Eigen::VectorXd::Ones(3)), Error);
}

}  // namespace
}  // namespace mjarm
