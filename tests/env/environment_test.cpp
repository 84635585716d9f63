// Environment: dm_env's step types, rewards and discounts; the errors of the bad-input
// list; clipping; the control step as whole physics steps; hook order; determinism bit for bit;
// no allocation in step.

#include "mjarm/env/environment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "env/env_test_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::HookTask;
using test::reach_task;

std::vector<double> zeros(const Environment& env) {
  return std::vector<double>(static_cast<std::size_t>(env.action_spec().size()), 0.0);
}

TEST(Environment, ResetIsFirstWithoutRewardOrDiscount) {
  Environment env(reach_task());
  const TimeStep ts = env.reset(7);
  EXPECT_TRUE(ts.first());
  EXPECT_FALSE(ts.reward.has_value());
  EXPECT_FALSE(ts.discount.has_value());
  EXPECT_EQ(ts.end, EpisodeEnd::running);
  EXPECT_EQ(static_cast<int>(ts.observation.values().size()), env.observation_spec().size());
  EXPECT_EQ(env.episode_seed(), 7u);
  EXPECT_EQ(env.steps(), 0);
}

TEST(Environment, StepsAreMidThenLastWithDiscountOneAtTheTimeLimit) {
  EnvironmentOptions options;
  options.time_limit = 0.1;  // 5 steps of 20 ms
  Environment env(reach_task(), options);
  ASSERT_EQ(env.step_limit(), 5);
  env.reset(1);
  const std::vector<double> action = zeros(env);
  for (int k = 1; k <= 5; ++k) {
    const TimeStep ts = env.step(action);
    ASSERT_TRUE(ts.reward.has_value());
    ASSERT_TRUE(ts.discount.has_value());
    if (k < 5) {
      EXPECT_TRUE(ts.mid()) << k;
      EXPECT_EQ(*ts.discount, 1.0);
    } else {
      EXPECT_TRUE(ts.last());
      EXPECT_EQ(ts.end, EpisodeEnd::truncated);
      EXPECT_EQ(*ts.discount, 1.0);  // a truncation, not a termination
    }
  }
  // a time limit that is not a whole number of steps rounds up
  options.time_limit = 0.05;
  EXPECT_EQ(Environment(reach_task(), options).step_limit(), 3);
}

TEST(Environment, TerminationIsLastWithDiscountZero) {
  Environment env(std::make_unique<HookTask>(nullptr, 3));
  env.reset(0);
  const std::vector<double> action = zeros(env);
  EXPECT_TRUE(env.step(action).mid());
  EXPECT_TRUE(env.step(action).mid());
  const TimeStep ts = env.step(action);
  EXPECT_TRUE(ts.last());
  EXPECT_EQ(ts.end, EpisodeEnd::terminated);
  EXPECT_EQ(*ts.discount, 0.0);
  EXPECT_EQ(*ts.reward, 3.0);  // HookTask's reward is the step count
}

TEST(Environment, TerminationWinsOverTheTimeLimitOnTheSameStep) {
  EnvironmentOptions options;
  options.time_limit = 0.06;  // 3 steps
  Environment env(std::make_unique<HookTask>(nullptr, 3), options);
  env.reset(0);
  const std::vector<double> action = zeros(env);
  env.step(action);
  env.step(action);
  const TimeStep ts = env.step(action);
  EXPECT_EQ(ts.end, EpisodeEnd::terminated);
  EXPECT_EQ(*ts.discount, 0.0);
}

TEST(Environment, StepAfterLastWithoutResetIsAnError) {
  EnvironmentOptions options;
  options.time_limit = 0.02;
  Environment env(reach_task(), options);
  const std::vector<double> action = zeros(env);
  test::expect_error_containing([&] { env.step(action); }, {"before reset()", "reset()"});
  env.reset(1);
  ASSERT_TRUE(env.step(action).last());
  test::expect_error_containing([&] { env.step(action); },
                                {"after the last step", "truncated", "call reset()"});
  env.reset(2);  // and reset makes it usable again
  EXPECT_TRUE(env.step(action).last());
}

// issue 29, item 9: close() then reset() worked as if the environment had never been closed
TEST(Environment, AClosedEnvironmentStaysClosed) {
  for (const std::string& task : env_task_names()) {
    Environment env(task);
    const std::vector<double> action = zeros(env);
    env.reset(1);
    EXPECT_FALSE(env.closed());
    env.close();
    env.close();  // closing twice is allowed
    EXPECT_TRUE(env.closed());
    test::expect_error_containing([&] { env.reset(1); },
                                  {"environment '", "reset() after close()", "make a new one"});
    test::expect_error_containing([&] { env.reset(); }, {"reset() after close()"});
    test::expect_error_containing([&] { env.step(action); }, {"step() after close()"});
    EXPECT_EQ(env.steps(), 0) << task;  // nothing ran
  }
}

TEST(Environment, WrongActionSizesAreErrors) {
  Environment env(reach_task());
  env.reset(1);
  const std::vector<double> short_action(5, 0.0), long_action(7, 0.0);
  test::expect_error_containing([&] { env.step(short_action); },
                                {"ee_pose_deltas", "needs 6 values, got 5"});
  test::expect_error_containing([&] { env.step(long_action); }, {"needs 6 values, got 7"});
  test::expect_error_containing([&] { env.step({}); }, {"got 0"});
  EXPECT_EQ(env.steps(), 0);  // nothing was stepped
}

TEST(Environment, NanAndInfiniteActionsAreErrors) {
  Environment env(reach_task());
  env.reset(1);
  std::vector<double> action = zeros(env);
  action[2] = std::numeric_limits<double>::quiet_NaN();
  test::expect_error_containing([&] { env.step(action); }, {"action[2]", "nan", "finite"});
  action[2] = 0.0;
  action[4] = -std::numeric_limits<double>::infinity();
  test::expect_error_containing([&] { env.step(action); }, {"action[4]", "-inf"});
  EXPECT_EQ(env.steps(), 0);
}

TEST(Environment, OutOfBoundsActionsAreClippedAndCounted) {
  Environment a(reach_task());
  Environment b(reach_task());
  a.reset(3);
  b.reset(3);
  std::vector<double> wild = zeros(a);
  wild[0] = 5.0;   // bound 0.02 m
  wild[5] = -9.0;  // bound 0.1 rad
  std::vector<double> clipped = zeros(b);
  clipped[0] = a.action_spec().maximum[0];
  clipped[5] = a.action_spec().minimum[5];
  const TimeStep ta = a.step(wild);
  const TimeStep tb = b.step(clipped);
  // the clipped action is what ran
  ASSERT_EQ(ta.observation.values().size(), tb.observation.values().size());
  EXPECT_EQ(std::memcmp(ta.observation.values().data(), tb.observation.values().data(),
                        ta.observation.values().size_bytes()),
            0);
  EXPECT_EQ(a.episode_clips().steps, 1);
  EXPECT_EQ(a.episode_clips().values, 2);
  EXPECT_EQ(b.episode_clips().steps, 0);
  a.step(wild);
  EXPECT_EQ(a.episode_clips().steps, 2);
  a.reset(4);  // the episode's count restarts, the total does not
  EXPECT_EQ(a.episode_clips().steps, 0);
  EXPECT_EQ(a.total_clips().steps, 2);
  EXPECT_EQ(a.total_clips().values, 4);
}

TEST(Environment, OutOfBoundsActionsCanBeRefused) {
  EnvironmentOptions options;
  options.refuse_out_of_bounds = true;
  Environment env(reach_task(), options);
  env.reset(1);
  std::vector<double> action = zeros(env);
  action[1] = -0.5;
  test::expect_error_containing([&] { env.step(action); },
                                {"action[1]", "-0.5", "outside its bounds", "-0.02", "refuse"});
  EXPECT_EQ(env.steps(), 0);
  action[1] = -0.02;  // on the bound is inside
  EXPECT_NO_THROW(env.step(action));
}

TEST(Environment, ControlStepMustBeAWholeMultipleOfThePhysicsTimestep) {
  EnvironmentOptions options;
  options.control_period = 0.015;  // timestep 2 ms
  test::expect_error_containing([&] { Environment env(reach_task(), options); },
                                {"control_period", "0.015", "not a whole multiple",
                                 "physics timestep", "0.002", "nearest: 0.016"});
  options.control_period = 0.0;
  test::expect_error_containing([&] { Environment env(reach_task(), options); },
                                {"control_period", "positive"});
  options.control_period = 0.02;
  options.controller_period = 0.006;  // a multiple of 2 ms but not a divisor of 20 ms
  test::expect_error_containing([&] { Environment env(reach_task(), options); },
                                {"not a whole multiple of the controller period"});
  options.controller_period = 0.0;
  options.time_limit = 0.01;
  test::expect_error_containing([&] { Environment env(reach_task(), options); },
                                {"time_limit", "at least the control period"});
}

TEST(Environment, OneStepRunsItsPhysicsSubsteps) {
  EnvironmentOptions options;
  options.control_period = 0.02;
  Environment env(reach_task(), options);
  EXPECT_EQ(env.physics_steps_per_step(), 10);
  env.reset(1);
  const double t0 = env.simulation().time();
  env.step(zeros(env));
  EXPECT_EQ(env.simulation().physics_steps(), 10);
  EXPECT_EQ(env.simulation().ticks(), 1);  // the controller ran once, held over the step
  EXPECT_NEAR(env.simulation().time() - t0, 0.02, 1e-12);
  EXPECT_NEAR(env.context().time, 0.02, 1e-12);

  // a faster controller: several ticks per step on the same reference
  options.controller_period = 0.004;
  Environment fast(reach_task(), options);
  fast.reset(1);
  fast.step(zeros(fast));
  EXPECT_EQ(fast.simulation().physics_steps(), 10);
  EXPECT_EQ(fast.simulation().ticks(), 5);
}

TEST(Environment, HooksRunInOrder) {
  auto log = std::make_shared<std::vector<std::string>>();
  Environment env(std::make_unique<HookTask>(log), [] {
    EnvironmentOptions o;
    o.action_space = ActionSpace::joint_torques;
    o.observations = {"joint_positions", "object_pose"};
    return o;
  }());
  env.reset(5);
  EXPECT_EQ(*log, (std::vector<std::string>{"init", "observe"}));
  log->clear();
  const std::vector<double> action{1.0, -2.0};
  env.step(action);
  EXPECT_EQ(*log, (std::vector<std::string>{"before", "after", "reward", "terminated", "observe"}));
  const auto& task = static_cast<const HookTask&>(env.task());
  EXPECT_EQ(task.last_action, action);  // before_step saw the (clipped) action
}

TEST(Environment, TheTaskDrawsFromTheEpisodeSeed) {
  Environment env(std::make_unique<HookTask>());
  env.reset(11);
  const double first = static_cast<const HookTask&>(env.task()).drawn;
  env.reset(12);
  const double other = static_cast<const HookTask&>(env.task()).drawn;
  env.reset(11);
  EXPECT_EQ(static_cast<const HookTask&>(env.task()).drawn, first);
  EXPECT_NE(other, first);
  // reset() without a seed draws the episode seeds from EnvironmentOptions::seed
  EnvironmentOptions options;
  options.seed = 99;
  Environment a(std::make_unique<HookTask>(), options), b(std::make_unique<HookTask>(), options);
  for (int k = 0; k < 3; ++k) {
    a.reset();
    b.reset();
    EXPECT_EQ(a.episode_seed(), b.episode_seed());
  }
}

// every observation of two runs with the same seed and actions, bit for bit
std::vector<double> run_trace(ActionSpace space, std::uint64_t seed,
                              const std::vector<double>& actions) {
  EnvironmentOptions options;
  options.action_space = space;
  options.observations = {"joint_positions", "joint_velocities", "ee_pose",
                          "ee_twist",        "target",           "sensor:arm/ft_force"};
  Environment env(reach_task(), options);
  std::vector<double> trace;
  TimeStep ts = env.reset(seed);
  const std::size_t width = static_cast<std::size_t>(env.action_spec().size());
  for (std::size_t k = 0; k * width < actions.size(); ++k) {
    trace.insert(trace.end(), ts.observation.values().begin(), ts.observation.values().end());
    if (ts.reward) trace.push_back(*ts.reward);
    ts = ts.last() ? env.reset()
                   : env.step(std::span<const double>(actions).subspan(k * width, width));
  }
  return trace;
}

TEST(Environment, SameSeedAndActionsGiveTheSameObservationsBitForBit) {
  for (ActionSpace space : {ActionSpace::ee_pose_deltas, ActionSpace::joint_positions}) {
    Environment probe(reach_task(), [&] {
      EnvironmentOptions o;
      o.action_space = space;
      return o;
    }());
    const std::vector<double> actions = test::uniform_actions(probe.action_spec(), 40, 5);
    const std::vector<double> a = run_trace(space, 21, actions);
    const std::vector<double> b = run_trace(space, 21, actions);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << to_string(space);
    const std::vector<double> c = run_trace(space, 22, actions);
    EXPECT_NE(std::memcmp(a.data(), c.data(), std::min(a.size(), c.size()) * sizeof(double)), 0);
  }
}

// reset(seed) starts the same episode on an environment that has run others before (nothing
// carries over: the QP's warm start, the controller's state, MuJoCo's warm start)
TEST(Environment, AnEpisodeRepeatsWhateverRanBeforeIt) {
  for (ActionSpace space : {ActionSpace::ee_pose_deltas, ActionSpace::ee_velocities,
                            ActionSpace::joint_deltas, ActionSpace::joint_torques}) {
    EnvironmentOptions o;
    o.action_space = space;
    Environment env(reach_task(), o);
    const std::vector<double> actions = test::uniform_actions(env.action_spec(), 30, 9);
    const std::size_t width = static_cast<std::size_t>(env.action_spec().size());
    auto episode = [&](std::uint64_t seed) {
      std::vector<double> trace;
      TimeStep ts = env.reset(seed);
      for (std::size_t k = 0; k * width < actions.size() && !ts.last(); ++k) {
        ts = env.step(std::span<const double>(actions).subspan(k * width, width));
        trace.insert(trace.end(), ts.observation.values().begin(), ts.observation.values().end());
      }
      return trace;
    };
    const std::vector<double> first = episode(4);
    episode(5);
    const std::vector<double> again = episode(4);
    ASSERT_EQ(first.size(), again.size());
    EXPECT_EQ(std::memcmp(first.data(), again.data(), first.size() * sizeof(double)), 0)
        << to_string(space);
  }
}

TEST(Environment, StepAllocatesNothing) {
  for (ActionSpace space : action_spaces()) {
    EnvironmentOptions options;
    options.action_space = space;
    options.observation_noise = 0.01;  // the noise and the delay line allocate nothing either
    options.action_latency = 2;
    options.observations = {
        "joint_positions", "joint_velocities", "ee_pose",        "ee_twist",
        "target",          "target_offset",    "contact_forces", "sensor:arm/ft_torque"};
    Environment env(reach_task(), options);
    const std::vector<double> actions = test::uniform_actions(env.action_spec(), 20, 3);
    const std::size_t width = static_cast<std::size_t>(env.action_spec().size());
    env.reset(1);
    env.step(std::span<const double>(actions).subspan(0, width));  // first use of every path
    const std::uint64_t before = test::malloc_calls();
    for (std::size_t k = 1; k < 20; ++k)
      env.step(std::span<const double>(actions).subspan(k * width, width));
    EXPECT_EQ(test::malloc_calls() - before, 0u) << to_string(space);
  }
}

TEST(Environment, DivergenceEndsTheEpisodeWithDiscountZero) {
  EnvironmentOptions options;
  options.action_space = ActionSpace::joint_torques;
  options.max_acceleration = 1.0;  // any real push trips the divergence bound
  Environment env(reach_task(), options);
  env.reset(1);
  std::vector<double> action = zeros(env);
  action[0] = 80.0;
  const TimeStep ts = env.step(action);
  EXPECT_TRUE(ts.last());
  EXPECT_EQ(ts.end, EpisodeEnd::diverged);
  EXPECT_EQ(*ts.discount, 0.0);
  EXPECT_FALSE(env.simulation().fault().ok());
  for (double v : ts.observation.values()) EXPECT_TRUE(std::isfinite(v));
  env.reset(2);  // a reset clears the fault
  EXPECT_TRUE(env.simulation().fault().ok());
}

TEST(Environment, UnknownTasksAreErrors) {
  test::expect_error_containing([] { Environment env("reahc"); },
                                {"unknown task 'reahc'", "did you mean 'reach'", "shelf-pick"});
  test::expect_error_containing([] { Environment env(std::unique_ptr<EnvTask>{}); }, {"no task"});
}

}  // namespace
}  // namespace mjarm
