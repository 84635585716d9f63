// EnvironmentOptions::observation_noise and action_latency: the noise's statistics, its own
// stream (same seed, same noise; the task's draws unchanged), the unbounded spec; the delayed
// actions the task sees; the options' ranges.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "env/env_test_support.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::HookTask;

std::vector<double> observe_episode(double noise, std::uint64_t seed, int steps) {
  EnvironmentOptions o;
  o.action_space = ActionSpace::joint_torques;
  o.observation_noise = noise;
  Environment env(std::make_unique<HookTask>(), o);
  TimeStep ts = env.reset(seed);
  std::vector<double> trace(ts.observation.values().begin(), ts.observation.values().end());
  const std::vector<double> action(static_cast<std::size_t>(env.action_spec().size()), 0.5);
  for (int k = 0; k < steps; ++k) {
    ts = env.step(action);
    trace.insert(trace.end(), ts.observation.values().begin(), ts.observation.values().end());
  }
  return trace;
}

TEST(ObservationNoise, IsGaussianWithTheStandardDeviationAskedAndRepeatsWithTheSeed) {
  const std::vector<double> clean = observe_episode(0.0, 5, 60);
  const std::vector<double> noisy = observe_episode(0.01, 5, 60);
  ASSERT_EQ(clean.size(), noisy.size());
  double sum = 0.0, squares = 0.0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const double e = noisy[i] - clean[i];
    sum += e;
    squares += e * e;
  }
  const double n = static_cast<double>(clean.size());  // about 1,500 values
  const double mean = sum / n, sigma = std::sqrt(squares / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * 0.01 / std::sqrt(n));
  EXPECT_NEAR(sigma, 0.01, 0.1 * 0.01);
  EXPECT_EQ(observe_episode(0.01, 5, 60), noisy) << "the same seed, the same noise";
  EXPECT_NE(observe_episode(0.01, 6, 60), noisy);
}

TEST(ObservationNoise, LeavesTheTasksDrawsAndUnboundsTheSpec) {
  EnvironmentOptions noisy;
  noisy.observation_noise = 0.1;
  Environment with(std::make_unique<HookTask>(), noisy), without(std::make_unique<HookTask>());
  with.reset(3);
  without.reset(3);
  EXPECT_EQ(static_cast<const HookTask&>(with.task()).drawn,
            static_cast<const HookTask&>(without.task()).drawn);
  // the reach task's joint positions are bounded by the panda's limits; noisy, nothing is
  Environment bounded(test::reach_task()), unbounded(test::reach_task(), noisy);
  int finite = 0;
  for (const ArraySpec& a : bounded.observation_spec().arrays())
    finite += static_cast<int>(a.minimum.array().isFinite().count());
  EXPECT_GT(finite, 0);
  for (const ArraySpec& a : unbounded.observation_spec().arrays()) {
    EXPECT_TRUE((a.minimum.array() == -std::numeric_limits<double>::infinity()).all()) << a.name;
    EXPECT_TRUE((a.maximum.array() == std::numeric_limits<double>::infinity()).all()) << a.name;
  }
}

TEST(ActionLatency, StepKAppliesTheActionOfStepKMinusTheLatency) {
  EnvironmentOptions o;
  o.action_space = ActionSpace::joint_torques;
  o.action_latency = 2;
  auto task = std::make_unique<HookTask>();
  const HookTask& hooks = *task;
  Environment env(std::move(task), o);
  for (int episode = 0; episode < 2; ++episode) {  // the line starts again at each reset
    env.reset(1);
    std::vector<double> applied;
    for (int k = 1; k <= 5; ++k) {
      const double action[] = {static_cast<double>(k), -static_cast<double>(k)};
      env.step(action);
      applied.push_back(hooks.last_action[0]);
      EXPECT_EQ(hooks.last_action[1], -hooks.last_action[0]);
    }
    EXPECT_EQ(applied, (std::vector<double>{1, 1, 1, 2, 3})) << "episode " << episode;
  }
}

TEST(NoiseAndLatency, OutOfRangeOptionsAreRefused) {
  const auto refused = [](auto set, const char* name) {
    EnvironmentOptions o;
    set(o);
    test::expect_error_containing([&] { Environment env(std::make_unique<HookTask>(), o); },
                                  {name});
  };
  refused([](EnvironmentOptions& o) { o.observation_noise = -0.1; }, "observation_noise");
  refused([](EnvironmentOptions& o) { o.observation_noise = std::nan(""); }, "observation_noise");
  refused([](EnvironmentOptions& o) { o.action_latency = -1; }, "action_latency");
  refused([](EnvironmentOptions& o) { o.action_latency = 1001; }, "action_latency");
}

}  // namespace
}  // namespace mjarm
