// ShelfPickEnvTask: the tasks room's shelf pick as an environment — the same start and pick for
// a seed as `plan_shelf_pick`, the reward, and the hold that terminates the episode.

#include "mjarm/env/shelf_pick_env_task.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "env/env_test_support.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm {
namespace {

const ShelfPickEnvTask& shelf(const Environment& env) {
  return static_cast<const ShelfPickEnvTask&>(env.task());
}

TEST(ShelfPickEnvTask, StartsWhereTheTasksRoomsShelfPickStarts) {
  Environment env("shelf-pick");
  for (std::uint64_t seed : {1, 7, 42}) {
    ShelfPickRequest request;
    request.robot = "panda";
    request.seed = seed;
    const ShelfPickPlan plan = plan_shelf_pick(request);
    const TimeStep ts = env.reset(seed);
    EXPECT_EQ(shelf(env).target().p, plan.pick) << seed;
    EXPECT_EQ(shelf(env).qpos_start(), plan.qpos_start) << seed;
    EXPECT_LT((shelf(env).target().R - plan.goal.X_WT.R).norm(), 1e-12);
    const std::span<const double> q = ts.observation["joint_positions"];
    for (int i = 0; i < plan.chain.size(); ++i)
      EXPECT_EQ(q[i], plan.qpos_start[static_cast<std::size_t>(plan.chain.qpos_address(i))]);
    const std::span<const double> target = ts.observation["target"];
    for (int k = 0; k < 3; ++k) EXPECT_EQ(target[k], plan.pick[k]);
  }
}

TEST(ShelfPickEnvTask, ARetargetingPolicyHoldsThePickAndTerminates) {
  Environment env("shelf-pick");
  TimeStep ts = env.reset(3);
  const Pose X_WT = shelf(env).target();
  while (!ts.last()) {
    // 0.3 × the pose error (a proportional policy on an integrating action, see the reach
    // test), clipped by the environment into one step's bounds
    const Vector6d e = 0.3 * task_error(env.context().X_WE, X_WT);
    ts = env.step(std::vector<double>(e.data(), e.data() + 6));
    const Vector6d after = task_error(env.context().X_WE, X_WT);
    EXPECT_DOUBLE_EQ(*ts.reward, -(after.head<3>().norm() + 0.1 * after.tail<3>().norm()));
  }
  EXPECT_EQ(ts.end, EpisodeEnd::terminated);
  EXPECT_EQ(*ts.discount, 0.0);
  const PickMetrics& metrics = shelf(env).monitor().metrics();
  EXPECT_TRUE(metrics.held);
  EXPECT_LE(metrics.hold_max, 1e-3);
  EXPECT_LT(env.steps(), 200);  // held well within the 10 s limit
}

TEST(ShelfPickEnvTask, BadOptionsAreErrors) {
  ShelfPickEnvOptions o;
  o.robot = "planar2";
  test::expect_error_containing([&] { ShelfPickEnvTask t(o); },
                                {"robot 'planar2'", "position-only", "panda"});
  o.robot = "ur5";
  test::expect_error_containing([&] { ShelfPickEnvTask t(o); }, {"unknown robot 'ur5'"});
  o = ShelfPickEnvOptions{};
  o.criteria.tolerance = 0.0;
  test::expect_error_containing([&] { ShelfPickEnvTask t(o); }, {"tolerance"});
  o = ShelfPickEnvOptions{};
  o.orientation_weight = -1.0;
  test::expect_error_containing([&] { ShelfPickEnvTask t(o); }, {"orientation_weight"});
}

}  // namespace
}  // namespace mjarm
