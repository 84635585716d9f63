// The soak (soak/soak.hpp) on a few small rounds: a clean soak holds every check, and each fault
// injected on purpose — a leak, a descriptor left open, a drift in every part — fails it. Rounds
// are counted, not timed: no verdict depends on the machine's speed.

#include "mjarm/soak/soak.hpp"

#include <gtest/gtest.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/soak/process_sample.hpp"

namespace {

using mjarm::SoakOptions;
using mjarm::SoakResult;
using mjarm::SoakStatus;

// the smallest soak that still runs every part: one task, one episode, one trial
SoakOptions small_soak(int rounds) {
  SoakOptions o;
  o.rounds = rounds;
  o.tasks = {"reach"};
  o.episodes = 1;
  o.vector_envs = 2;
  o.trials = 1;
  o.trial_threads = 1;
  o.limits.warmup_rounds = 1;
  o.limits.warmup_fraction = 0.0;
  return o;
}

bool notes_mention(const std::vector<std::string>& notes, const std::string& text) {
  for (const std::string& n : notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

TEST(ProcessSample, ReadsThisProcess) {
  const mjarm::ProcessSample s = mjarm::sample_process();
  EXPECT_GT(s.rss_kib, 0.0);
  EXPECT_GT(s.heap_kib, 0.0);
  EXPECT_LT(s.heap_kib, s.rss_kib);
  EXPECT_GE(s.fds, 3);  // standard input, output, error
  EXPECT_GE(s.threads, 1);
}

TEST(Soak, ACleanSoakHoldsEveryCheckAndRepeatsItsResults) {
  const SoakResult r = mjarm::run_soak(small_soak(2));
  EXPECT_EQ(r.status, SoakStatus::ok) << (r.failures.empty() ? "" : r.failures.front());
  EXPECT_EQ(r.rounds, 2);
  ASSERT_EQ(r.samples.size(), 2u);
  EXPECT_EQ(r.samples[1].round, 2);
  EXPECT_EQ(r.counts.env_runs, 2 * 5);  // reach in each of the 5 action spaces
  EXPECT_EQ(r.counts.env_episodes, 2 * 5);
  EXPECT_GT(r.counts.env_steps, 0);
  EXPECT_GT(r.counts.vector_steps, 0);
  EXPECT_EQ(r.counts.replays, 2);
  EXPECT_EQ(r.counts.replay_ticks, 2 * r.recorded_ticks);
  EXPECT_EQ(r.counts.trials, 2);
  EXPECT_EQ(r.drifts, 0);
  EXPECT_EQ(r.mujoco_warnings, 0);
  EXPECT_EQ(r.logged_warnings, 0);
  EXPECT_EQ(r.divergences, 0);
  EXPECT_FALSE(r.growth.fd_growth);
  EXPECT_FALSE(r.growth.judged);  // 1 round after the warm-up
  EXPECT_TRUE(r.failures.empty());
}

TEST(Soak, AnInjectedLeakIsMemoryGrowth) {
  // the warm-up round and kMinJudgedRounds (3) judged rounds
  SoakOptions o = small_soak(4);
  o.inject.leak_kib_per_round = 32 * 1024;
  // any positive slope: the verdict does not depend on how long a round takes
  o.limits.max_heap_slope_kib_per_hour = 0.0;
  o.limits.heap_margin_kib = 48 * 1024;  // the leak adds 96 MiB after the warm-up
  o.limits.max_rss_slope_kib_per_hour = 0.0;
  o.limits.rss_margin_kib = 48 * 1024;
  const SoakResult r = mjarm::run_soak(o);
  EXPECT_EQ(r.status, SoakStatus::failed);
  EXPECT_TRUE(r.growth.judged);
  EXPECT_TRUE(r.growth.heap.growth);
  EXPECT_TRUE(r.growth.rss.growth);
  EXPECT_GT(r.growth.heap.last - r.growth.heap.warmup_max, 48 * 1024.0);
  EXPECT_GT(r.growth.rss.last - r.growth.rss.warmup_max, 48 * 1024.0);
  EXPECT_TRUE(notes_mention(r.failures, "heap in use grows"));
  EXPECT_TRUE(notes_mention(r.failures, "resident memory grows"));
}

TEST(Soak, ADescriptorLeftOpenEachRoundIsGrowthAndIsClosedAfterwards) {
  const int before = mjarm::sample_process().fds;
  SoakOptions o = small_soak(3);
  o.inject.fds_per_round = 1;
  const SoakResult r = mjarm::run_soak(o);
  EXPECT_EQ(r.status, SoakStatus::failed);
  EXPECT_TRUE(r.growth.fd_growth);
  EXPECT_EQ(r.growth.fds_last, r.growth.fds_first + 2);
  EXPECT_TRUE(notes_mention(r.failures, "open file descriptors grow"));
  EXPECT_EQ(mjarm::sample_process().fds, before);
}

TEST(Soak, ADriftInEveryPartIsCaught) {
  SoakOptions o = small_soak(2);
  o.inject.drift_from_round = 2;
  const SoakResult r = mjarm::run_soak(o);
  EXPECT_EQ(r.status, SoakStatus::failed);
  // 5 environment runs, the vectorized batch, the replay (twice: against the first replay and
  // the recorded digest), the trial
  EXPECT_EQ(r.drifts, 5 + 1 + 2 + 1);
  EXPECT_TRUE(notes_mention(r.drift_notes, "round 2, reach (joint_torques)"));
  EXPECT_TRUE(notes_mention(r.drift_notes, "round 2, vectorized reach"));
  EXPECT_TRUE(notes_mention(r.drift_notes, "differs from the first replay's"));
  EXPECT_TRUE(notes_mention(r.drift_notes, "round 2, pick-and-place seed 1"));
  EXPECT_TRUE(notes_mention(r.failures, "results drifted from round 1's"));
}

TEST(Soak, AStopEndsTheRoundUnderWayAndKeepsTheRoundsDone) {
  SoakOptions o = small_soak(100);
  int round_seen = 0;
  o.progress = [&](int round, double) { round_seen = round; };
  o.stop = [&] { return round_seen >= 2; };  // asked first in round 2
  const SoakResult r = mjarm::run_soak(o);
  EXPECT_EQ(r.status, SoakStatus::interrupted);
  EXPECT_EQ(r.rounds, 1);
  EXPECT_EQ(r.samples.size(), 1u);
  EXPECT_EQ(r.counts.replays, 1);
}

TEST(Soak, BadOptionsAreRefusedBeforeAnyWork) {
  SoakOptions o = small_soak(1);
  o.minutes = 0.0;
  EXPECT_THROW(mjarm::run_soak(o), mjarm::Error);
  o = small_soak(1);
  o.tasks = {"reech"};
  EXPECT_THROW(mjarm::run_soak(o), mjarm::Error);
  o = small_soak(1);
  o.trials = 0;
  EXPECT_THROW(mjarm::run_soak(o), mjarm::Error);
}

}  // namespace
