// Drives `mjarm bench ompl`: the shelf benchmark's JSON and text report on a few pairs, and
// clean failures for a bad planner name or budget. (No figure is asserted: benchmarks are
// commands; their figures are in docs/planning.md.)

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::run_cli;
using nlohmann::json;

TEST(BenchOmpl, JsonReportsTheShelfPairs) {
  const CliRun run = run_cli({"bench", "ompl", "--pairs", "3", "--seed", "4", "--checker-states",
                              "200", "--budget", "10", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["planner"], "rrtconnect");
  EXPECT_EQ(j["pairs"], 3);
  EXPECT_FALSE(j["interrupted"].get<bool>());
  int counted = 0;
  for (const auto& [status, count] : j["statuses"].items()) counted += count.get<int>();
  EXPECT_EQ(counted, 3);
  EXPECT_EQ(j["successes"].get<int>(), j["statuses"].value("success", 0));
  EXPECT_NEAR(j["success_rate"].get<double>(), j["successes"].get<int>() / 3.0, 1e-12);
  EXPECT_GT(j["time_median_s"].get<double>(), 0.0);
  EXPECT_LE(j["time_median_s"].get<double>(), j["time_p95_s"].get<double>());
  EXPECT_GT(j["checks_median"].get<double>(), 0.0);
  EXPECT_GT(j["check_us"].get<double>(), 0.0);
  EXPECT_GT(j["forward_us"].get<double>(), 0.0);
  if (j["successes"].get<int>() > 0) {
    EXPECT_GT(j["length_median_rad"].get<double>(), 0.0);
    EXPECT_GE(j["knots_median"].get<double>(), 2.0);
    EXPECT_LE(j["time_optimal"].get<int>(), j["successes"].get<int>());
    if (j["time_optimal"].get<int>() > 0) {
      EXPECT_GT(j["time_optimal_median_s"].get<double>(), 0.0);
      EXPECT_LE(j["time_optimal_ratio_median"].get<double>(),
                j["time_optimal_ratio_max"].get<double>());
    }
  }
  EXPECT_GT(j["collision_share"].get<double>(), 0.0);  // the shelf is in the way of some states
}

TEST(BenchOmpl, TextReportAndBadCommandLines) {
  const CliRun text = run_cli({"bench", "ompl", "--pairs", "1", "--checker-states", "50"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  for (const char* s : {"panda_shelf", "success [%]", "time p95 [ms]", "validity check"})
    EXPECT_NE(text.out.find(s), std::string::npos) << s << " not in:\n" << text.out;
  const CliRun planner = run_cli({"bench", "ompl", "--planner", "rrt-connect"});
  EXPECT_NE(planner.exit_code, 0);
  EXPECT_NE(planner.err.find("rrtconnect"), std::string::npos) << planner.err;  // the closest
  const CliRun budget = run_cli({"bench", "ompl", "--budget", "1e9"});
  EXPECT_EQ(budget.exit_code, 2) << budget.err;
  EXPECT_NE(budget.err.find("--budget"), std::string::npos) << budget.err;
}

}  // namespace
