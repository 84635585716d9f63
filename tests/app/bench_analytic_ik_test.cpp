// Drives `mjarm bench analytic-ik`: its JSON on the ur5e (accuracy only: no time assertions) and
// the refusal of an arm the closed form cannot solve.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using nlohmann::json;

TEST(BenchAnalyticIk, JsonOnUr5eReachesEveryTargetWithEveryBranch) {
  const CliRun run =
      run_cli({"bench", "analytic-ik", "ur5e", "--samples", "200", "--seed", "4", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["model"], "ur5e");
  EXPECT_EQ(doc["family"], "parallel_shoulder");
  EXPECT_EQ(doc["samples"], 200);
  EXPECT_EQ(doc["seed"], 4);
  EXPECT_DOUBLE_EQ(doc["solved_fraction"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(doc["recovered_fraction"].get<double>(), 1.0);
  EXPECT_GT(doc["eight_branch_fraction"].get<double>(), 0.5);
  EXPECT_EQ(doc["dropped_branches"], 0);
  EXPECT_LT(doc["max_position_error_m"].get<double>(), 1e-10);
  EXPECT_LT(doc["max_orientation_error_rad"].get<double>(), 1e-10);
  EXPECT_LE(doc["time_us"]["median"].get<double>(), doc["time_us"]["max"].get<double>());
}

TEST(BenchAnalyticIk, RefusesThePandaWithTheReason) {
  expect_error({"bench", "analytic-ik", "panda", "--samples", "5"}, 1, "7 joints");
  expect_error({"bench", "analytic-ik", "ur5e", "--samples", "0"}, 2, "--samples");
}

}  // namespace
