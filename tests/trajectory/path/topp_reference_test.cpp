#include "mjarm/trajectory/path/validation/topp_reference.hpp"

#include <gtest/gtest.h>

#include "mjarm/random.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"
#include "mjarm/trajectory/path/validation/topp_protocol.hpp"

namespace mjarm {
namespace {

// The reference and TOPP-RA solve the same grid problem by unrelated methods: TOPP-RA's profile
// keeps the reference's rows, so it cannot be shorter than the reference's minimum; it is longer
// by the greedy forward pass's gap (on the grid, a higher speed at s_i can lower the highest
// reachable speed at s_{i+1}: worst 1.9 % at N = 50, 0.44 % at N = 100, 0.083 % at N = 200 in
// the bench, docs/trajectory.md), and the reference's answer does not depend on its start.
TEST(ToppReference, AgreesWithReachabilityOnSeededPaths) {
  Random rng(21);
  for (int trial = 0; trial < 15; ++trial) {
    const ToppCase c = random_topp_case(rng, 7);
    const JointPath path(c.waypoints);
    ToppOptions options;
    options.grid_intervals = 60;
    const TimeOptimalPath topp(path, c.max_velocity, c.max_acceleration, options);
    ASSERT_TRUE(topp.solved());
    const ToppReference ref =
        solve_topp_reference(path, c.max_velocity, c.max_acceleration, topp.grid());
    ASSERT_TRUE(ref.solved()) << "trial " << trial;
    EXPECT_GE(topp.duration(), ref.duration * (1.0 - 1e-9)) << "trial " << trial;
    EXPECT_LE(topp.duration(), ref.duration * 1.01) << "trial " << trial;
    const Eigen::VectorXd& x = topp.squared_speeds();
    EXPECT_LE(topp_grid_excess(path, c.max_velocity, c.max_acceleration, topp.grid(), x), 1e-9);
    EXPECT_LE(
        topp_grid_excess(path, c.max_velocity, c.max_acceleration, topp.grid(), ref.squared_speeds),
        1e-9);
    const ToppReference warm =
        solve_topp_reference(path, c.max_velocity, c.max_acceleration, topp.grid(), &x);
    ASSERT_TRUE(warm.solved());
    EXPECT_NEAR(warm.duration, ref.duration, 1e-8 * ref.duration) << "trial " << trial;
    EXPECT_NEAR(topp_grid_duration(topp.grid(), x), topp.duration(), 1e-12 * topp.duration());
  }
}

// The reference is not the same code: a profile it finds feasible TOPP-RA would call too slow,
// and a profile over the limits it reports as such.
TEST(ToppReference, GridExcessSeesAProfileOverTheLimits) {
  Random rng(2);
  const ToppCase c = random_topp_case(rng, 7);
  const JointPath path(c.waypoints);
  const TimeOptimalPath topp(path, c.max_velocity, c.max_acceleration);
  Eigen::VectorXd faster = topp.squared_speeds() * 1.05;
  EXPECT_GT(topp_grid_excess(path, c.max_velocity, c.max_acceleration, topp.grid(), faster), 1e-3);
  Eigen::VectorXd slower = topp.squared_speeds() * 0.9;
  EXPECT_LT(topp_grid_excess(path, c.max_velocity, c.max_acceleration, topp.grid(), slower), 0.0);
  EXPECT_GT(topp_grid_duration(topp.grid(), slower), topp.duration());
}

// The protocol of `mjarm bench topp` on 40 paths at N = 100: limits exact at the grid points,
// within the discretization's error between them (12 % the worst of the bench's 10 000 paths at
// N = 100), never shorter than the grid minimum, longer by less than 1 %.
TEST(ToppValidation, SeededBatchPassesEveryCheck) {
  ToppValidationOptions options;
  options.paths = 40;
  options.reference_paths = 20;
  options.refinement_paths = 10;
  options.grid_intervals = 100;
  const ToppValidationResult r = run_topp_validation(options);
  EXPECT_EQ(r.paths, 40);
  EXPECT_EQ(r.failures, 0) << r.first_failure;
  EXPECT_EQ(r.reference_failures, 0) << r.first_failure;
  EXPECT_LE(r.worst_grid_excess, 1e-9);
  EXPECT_LE(r.worst_excess, 0.15);
  EXPECT_LE(r.worst_shorter, 1e-9);
  EXPECT_LE(r.worst_longer, 0.01);
  EXPECT_LT(r.worst_refinement_change, 0.02);
  EXPECT_GT(r.median_us, 0.0);
  // the jerk-limited variant through the same waypoints: every segment within v, a and j, and
  // faster on average than stopping at every waypoint
  EXPECT_EQ(r.jerk_paths, 40);
  EXPECT_EQ(r.jerk_failures, 0) << r.first_failure;
  EXPECT_LE(r.jerk_worst_excess, 1e-9);
  EXPECT_LT(r.jerk_mean_over_stops, 1.0);
  EXPECT_GT(r.jerk_mean_over_topp, 1.0);  // a jerk limit only slows the motion down
}

}  // namespace
}  // namespace mjarm
