// Drives `mjarm bench traj` and `mjarm bench plan`: every case with its figures and target, no
// allocation per evaluation, the 5-waypoint plan, the text report, and clean failures for bad
// command lines. (Figures are not asserted against their targets: benchmarks are commands.)

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::run_cli;
using nlohmann::json;

TEST(BenchTraj, JsonHasEveryCaseWithItsTarget) {
  const CliRun run = run_cli(
      {"bench", "traj", "--calls", "1024", "--recalculations", "32", "--clock", "cpu", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["clock"], "cpu");
  ASSERT_EQ(j["cases"].size(), 7u);
  const char* calls[] = {"TrapezoidProfile::at", "SyncedTrapezoid::at", "QuinticTrajectory::at",
                         "Se3Interpolation::at", "SmoothRamp::at",      "TargetFilter::update",
                         "TargetFilter::update"};
  for (std::size_t i = 0; i < 7; ++i) {
    const json& c = j["cases"][i];
    EXPECT_EQ(c["call"], calls[i]);
    EXPECT_EQ(c["calls"], i == 6 ? 32 : 1024) << c["case"];
    EXPECT_GT(c["median_ns"].get<double>(), 0.0) << c["case"];
    EXPECT_LE(c["median_ns"].get<double>(), c["p99_ns"].get<double>()) << c["case"];
    EXPECT_GT(c["target_ns"].get<double>(), 0.0);
    EXPECT_EQ(c["within_target"].get<bool>(),
              c["median_ns"].get<double>() <= c["target_ns"].get<double>());
    EXPECT_EQ(c["allocations_per_call"], 0.0) << c["case"] << " allocates";
  }
}

TEST(BenchPlan, JsonAndTextReportTheFiveWaypointPlan) {
  const CliRun run = run_cli({"bench", "plan", "--plans", "1", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["model"], "panda_torque");
  EXPECT_EQ(j["waypoints"], 5);
  EXPECT_EQ(j["plans"], 1);
  EXPECT_NEAR(j["plan_duration"].get<double>(), 3.91, 0.05);  // docs/planning.md
  EXPECT_GT(j["samples"].get<int>(), 300);
  EXPECT_GT(j["median_ms"].get<double>(), 0.0);
  EXPECT_EQ(j["target_ms"], 100.0);
  const CliRun text = run_cli({"bench", "plan", "--plans", "1"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  for (const char* s : {"5 waypoints", "median [ms]", "target [ms]", "≤ 100"})
    EXPECT_NE(text.out.find(s), std::string::npos) << s << " not in:\n" << text.out;
}

TEST(BenchMotion, BadCommandLinesFailCleanly) {
  const CliRun few = run_cli({"bench", "traj", "--calls", "100"});  // fewer than a block
  EXPECT_EQ(few.exit_code, 2);
  EXPECT_NE(few.err.find("--block"), std::string::npos) << few.err;
  EXPECT_EQ(run_cli({"bench", "traj", "--calls", "0"}).exit_code, 2);
  EXPECT_EQ(run_cli({"bench", "traj", "--recalculations", "3"}).exit_code, 2);
  EXPECT_EQ(run_cli({"bench", "traj", "--clock", "sundial"}).exit_code, 2);
  EXPECT_EQ(run_cli({"bench", "plan", "--plans", "0"}).exit_code, 2);
  EXPECT_EQ(run_cli({"bench", "plan", "--plans", "1e9"}).exit_code, 2);
  mjarm::test::expect_error({"bench", "plan", "--clock", "sundial"}, 2,
                            "--clock: sundial not in {wall,cpu}");
}

}  // namespace
