// Trial batches: parallel trials equal the same trials run alone, the summary's figures, a batch
// whose trials diverge goes on and keeps every recording, bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "mjarm/error.hpp"
#include "mjarm/tasks/pick_place/trials.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

using test::error_of;
using test::scratch;
using test::slurp;

PickPlaceOptions brisk_trials() {
  PickPlaceOptions o;
  o.grasp = GraspKind::friction;
  o.mode = SimulationMode::torque;
  o.motion.dwell_time = 0.15;
  o.motion.grip_time = 0.3;
  o.motion.release_time = 0.3;
  o.motion.settle_time = 0.6;
  o.motion.limits.max_velocity = 0.25;
  o.motion.limits.max_acceleration = 2.0;
  o.motion.limits.max_angular_velocity = 1.5;
  o.seed = 40;
  return o;
}

TEST(PickPlaceTrials, ParallelTrialsAreTheTrialsRunAlone) {
  PickPlaceBatchOptions batch;
  batch.base = brisk_trials();
  batch.trials = 3;
  batch.threads = 2;
  std::vector<int> progress;
  batch.on_progress = [&progress](int done) { progress.push_back(done); };
  const PickPlaceBatch result = run_pick_place_trials(batch);
  ASSERT_EQ(result.reports.size(), 3u);
  EXPECT_EQ(progress, (std::vector<int>{1, 2, 3}));
  EXPECT_FALSE(result.interrupted);
  PickPlaceStat placement, force;
  int successes = 0;
  for (int k = 0; k < 3; ++k) {
    PickPlaceOptions alone = batch.base;
    alone.seed = batch.base.seed + static_cast<std::uint64_t>(k);
    const PickPlaceReport r = run_pick_place(alone);
    const PickPlaceReport& b = result.reports[static_cast<std::size_t>(k)];
    EXPECT_EQ(b.trial.seed, alone.seed);
    EXPECT_EQ(b.success, r.success);
    EXPECT_EQ(b.placement_error, r.placement_error);  // bit for bit
    EXPECT_EQ(b.trace.transport_force_mean, r.trace.transport_force_mean);
    EXPECT_EQ(b.cycle_time, r.cycle_time);
    if (r.success) {
      ++successes;
      placement.add(r.placement_error);
      force.add(r.trace.transport_force_mean);
    }
  }
  const PickPlaceSummary& s = result.summary;
  EXPECT_EQ(s.trials, 3);
  EXPECT_EQ(s.successes, successes);
  EXPECT_EQ(s.placement_error.count, successes);
  EXPECT_DOUBLE_EQ(s.placement_error.mean, placement.mean);
  EXPECT_DOUBLE_EQ(s.placement_error.max, placement.max);
  EXPECT_DOUBLE_EQ(s.grasp_force.mean, force.mean);
  EXPECT_EQ(s.weld_jump.count, 0);  // friction: no weld
  EXPECT_DOUBLE_EQ(s.success_rate(), successes / 3.0);
}

TEST(PickPlaceTrials, ABatchWhoseTrialsDivergeGoesOnAndKeepsEveryRecording) {
  PickPlaceBatchOptions batch;
  batch.base = brisk_trials();
  batch.base.grasp = GraspKind::weld;
  batch.base.mode = SimulationMode::position;
  batch.base.seed = 3;
  batch.base.max_acceleration = 30.0;  // trips mid-trial (tests/tasks/pick_place_test.cpp)
  batch.trials = 2;
  batch.threads = 1;
  batch.record = scratch() / "diverging_batch";
  const PickPlaceBatch result = run_pick_place_trials(batch);
  ASSERT_EQ(result.reports.size(), 2u);
  EXPECT_EQ(result.summary.failures[static_cast<std::size_t>(PickPlaceFailure::diverged)], 2);
  for (const PickPlaceReport& r : result.reports) {
    EXPECT_EQ(r.failure, PickPlaceFailure::diverged);
    EXPECT_NE(r.reason.find("acceleration"), std::string::npos) << r.reason;
    const std::filesystem::path dir = batch.record / ("seed_" + std::to_string(r.trial.seed));
    EXPECT_EQ(r.recording, dir);
    const nlohmann::json summary = nlohmann::json::parse(slurp(dir / "summary.json"));
    EXPECT_EQ(summary["status"], "diverged");
    EXPECT_GT(summary["counts"]["task_rows"].get<int>(), 100);
  }
}

TEST(PickPlaceTrials, StatAndBadInput) {
  PickPlaceStat stat;
  EXPECT_TRUE(std::isnan(stat.mean));
  for (double v : {1.0, std::nan(""), 3.0, 2.0}) stat.add(v);
  EXPECT_EQ(stat.count, 3);
  EXPECT_DOUBLE_EQ(stat.mean, 2.0);
  EXPECT_EQ(stat.max, 3.0);
  EXPECT_TRUE(std::isnan(PickPlaceSummary().success_rate()));

  PickPlaceBatchOptions batch;
  batch.trials = 0;
  EXPECT_NE(error_of([&] { run_pick_place_trials(batch); }).find("trials must be"),
            std::string::npos);
  batch.trials = 2;
  batch.threads = -1;
  EXPECT_NE(error_of([&] { run_pick_place_trials(batch); }).find("threads"), std::string::npos);
  batch.threads = 2;
  batch.base.robot = "planar2";
  EXPECT_NE(error_of([&] { run_pick_place_trials(batch); }).find("choices: arm6, panda_hand"),
            std::string::npos);
  // an error every trial would raise (out of reach) comes back once, after the workers stopped
  batch.base.robot = "arm6";
  batch.base.object_position = std::array<double, 2>{0.9, 0.0};
  EXPECT_NE(error_of([&] { run_pick_place_trials(batch); }).find("out of reach"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
