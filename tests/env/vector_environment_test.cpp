// VectorEnvironment: the batch equals its environments run one by one, bit for bit, whatever
// the thread count; automatic resets; batch errors name the row; no allocation in step.

#include "mjarm/env/vector_environment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "env/env_test_support.hpp"
#include "ik/malloc_counter.hpp"

namespace mjarm {
namespace {

EnvironmentOptions short_episodes() {
  EnvironmentOptions o;
  o.time_limit = 0.1;  // 5 steps: resets happen within a test
  o.seed = 77;
  return o;
}

template <class T>
bool same_bits(std::span<const T> a, std::span<const T> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size_bytes()) == 0;
}

TEST(VectorEnvironment, MatchesItsEnvironmentsRunOneByOne) {
  const int count = 3;
  VectorEnvironment batch(test::reach_task(), short_episodes(), count, 2);
  const int width = batch.action_spec().size();
  const int obs = batch.observation_spec().size();
  const std::vector<double> actions = test::uniform_actions(batch.action_spec(), 12 * count, 9);
  // the same environments by hand: seed splitmix64(seed + i), reset after LAST
  std::vector<std::unique_ptr<Environment>> single;
  for (int i = 0; i < count; ++i) {
    EnvironmentOptions o = short_episodes();
    o.seed = splitmix64(77 + static_cast<std::uint64_t>(i));
    single.push_back(std::make_unique<Environment>(test::reach_task(), o));
  }
  std::vector<TimeStep> last(count);
  batch.reset();
  for (int i = 0; i < count; ++i) last[i] = single[i]->reset();
  for (int k = 0; k < 12; ++k) {
    if (k > 0) {
      const std::span<const double> row(actions.data() + k * count * width,
                                        static_cast<std::size_t>(count * width));
      batch.step(row);
      for (int i = 0; i < count; ++i)
        last[i] = last[i].last() ? single[i]->reset()
                                 : single[i]->step(row.subspan(static_cast<std::size_t>(i * width),
                                                               static_cast<std::size_t>(width)));
    }
    for (int i = 0; i < count; ++i) {
      EXPECT_EQ(batch.step_types()[i], last[i].step_type) << k << " " << i;
      EXPECT_TRUE(same_bits(batch.observation(i), last[i].observation.values())) << k << " " << i;
      if (last[i].first()) {
        EXPECT_TRUE(std::isnan(batch.rewards()[i]));  // none, as NaN
        EXPECT_TRUE(std::isnan(batch.discounts()[i]));
      } else {
        EXPECT_EQ(batch.rewards()[i], *last[i].reward);
        EXPECT_EQ(batch.discounts()[i], *last[i].discount);
      }
    }
  }
  EXPECT_EQ(static_cast<int>(batch.observations().size()), count * obs);
}

TEST(VectorEnvironment, AutoResetsAfterLast) {
  VectorEnvironment batch(test::reach_task(), short_episodes(), 2, 1);
  batch.reset();
  const std::vector<double> zero(static_cast<std::size_t>(2 * batch.action_spec().size()), 0.0);
  for (int k = 1; k <= 5; ++k) batch.step(zero);
  EXPECT_EQ(batch.step_types()[0], StepType::last);
  EXPECT_EQ(batch.ends()[1], EpisodeEnd::truncated);
  EXPECT_EQ(batch.discounts()[0], 1.0);
  const std::uint64_t first_seed = batch.environment(0).episode_seed();
  batch.step(zero);
  EXPECT_EQ(batch.step_types()[0], StepType::first);
  EXPECT_TRUE(std::isnan(batch.rewards()[0]));
  EXPECT_NE(batch.environment(0).episode_seed(), first_seed);  // the next seed of its sequence
  batch.step(zero);
  EXPECT_EQ(batch.step_types()[1], StepType::mid);
}

// issue 29, item 9: closed stays closed, for the batch and each of its environments
TEST(VectorEnvironment, AClosedBatchStaysClosed) {
  VectorEnvironment batch(test::reach_task(), short_episodes(), 2, 1);
  batch.reset();
  batch.close();
  batch.close();
  EXPECT_TRUE(batch.closed());
  EXPECT_TRUE(batch.environment(1).closed());
  const std::vector<double> zero(static_cast<std::size_t>(2 * batch.action_spec().size()), 0.0);
  test::expect_error_containing([&] { batch.reset(); },
                                {"vector environment 'reach'", "reset() after close()"});
  test::expect_error_containing([&] { batch.step(zero); }, {"step() after close()"});
}

TEST(VectorEnvironment, SameResultsWhateverTheThreadCount) {
  const int count = 5;
  std::vector<std::vector<double>> observations, rewards;
  for (int threads : {1, 2, 3}) {
    VectorEnvironment batch(test::reach_task(), short_episodes(), count, threads);
    EXPECT_EQ(batch.threads(), threads);
    const std::vector<double> actions =
        test::uniform_actions(batch.action_spec(), static_cast<std::size_t>(14 * count), 4);
    const std::size_t width = static_cast<std::size_t>(count * batch.action_spec().size());
    std::vector<double> obs, rew;
    batch.reset();
    for (int k = 0; k < 14; ++k) {
      batch.step(
          std::span<const double>(actions).subspan(static_cast<std::size_t>(k) * width, width));
      obs.insert(obs.end(), batch.observations().begin(), batch.observations().end());
      rew.insert(rew.end(), batch.rewards().begin(), batch.rewards().end());
    }
    observations.push_back(obs);
    rewards.push_back(rew);
  }
  for (std::size_t t = 1; t < observations.size(); ++t) {
    EXPECT_TRUE(same_bits<double>(observations[0], observations[t])) << t;
    EXPECT_TRUE(same_bits<double>(rewards[0], rewards[t])) << t;  // NaN rows too, bit for bit
  }
}

TEST(VectorEnvironment, BadBatchesAreErrorsAndStepNothing) {
  VectorEnvironment batch(test::reach_task(), short_episodes(), 2, 2);
  const std::vector<double> zero(12, 0.0);
  test::expect_error_containing([&] { batch.step(zero); }, {"before reset()"});
  batch.reset();
  test::expect_error_containing([&] { batch.step(std::vector<double>(11, 0.0)); },
                                {"2 rows × 6 values = 12, got 11"});
  std::vector<double> bad = zero;
  bad[8] = NAN;
  test::expect_error_containing([&] { batch.step(bad); }, {"row 1 entry 2", "nan"});
  EXPECT_EQ(batch.environment(0).steps(), 0);
  EnvironmentOptions refuse = short_episodes();
  refuse.refuse_out_of_bounds = true;
  VectorEnvironment strict(test::reach_task(), refuse, 2, 1);
  strict.reset();
  bad = zero;
  bad[3] = 0.5;
  test::expect_error_containing([&] { strict.step(bad); },
                                {"row 0 entry 3", "outside its bounds", "refuse"});
  EXPECT_EQ(strict.environment(1).steps(), 0);
  test::expect_error_containing([] { VectorEnvironment v(test::reach_task(), {}, 0, 1); },
                                {"from 1 to 4096, got 0"});
  test::expect_error_containing([] { VectorEnvironment v(test::reach_task(), {}, 1, 0); },
                                {"threads must be from 1 to 256"});
  test::expect_error_containing([&] { batch.observation(2); }, {"row 2 out of range"});
}

TEST(VectorEnvironment, StepAllocatesNothingResetsIncluded) {
  VectorEnvironment batch(test::reach_task(), short_episodes(), 4, 2);
  const std::vector<double> actions = test::uniform_actions(batch.action_spec(), 4 * 12, 2);
  const std::size_t width = static_cast<std::size_t>(4 * batch.action_spec().size());
  batch.reset();
  batch.step(std::span<const double>(actions).subspan(0, width));
  const std::uint64_t before = test::malloc_calls();
  for (std::size_t k = 1; k < 12; ++k)
    batch.step(std::span<const double>(actions).subspan(k * width, width));
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

}  // namespace
}  // namespace mjarm
