// Drives `mjarm bench otg-brake`: the generator from starts beyond the limits — JSON fields (no
// failure, no DoF longer than the best feasible duration, the standard brake longer on some),
// the text report, and clean failures for bad command lines.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::run_cli;
using nlohmann::json;

TEST(BenchOtgBrake, JsonComparesTheBrakesWithTheBestFeasibleDurations) {
  const CliRun run =
      run_cli({"bench", "otg-brake", "--cases", "20", "--family-members", "100",
               "--structure-cases", "3", "--structure-seeds", "4", "--seed", "2", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["cases"], 20);
  EXPECT_EQ(j["braking_dofs"], 140);
  EXPECT_EQ(j["failures"], 0) << j["first_failure"];
  EXPECT_EQ(j["check_failures"], 0) << j["first_failure"];
  EXPECT_EQ(j["optimal_longer"], 0) << j["first_failure"];
  EXPECT_GT(j["standard_longer"].get<int>(), 0);
  EXPECT_GT(j["standard_worst_ratio"].get<double>(), 1.0);
  EXPECT_EQ(j["structure_cases"], 3);
  // every solution of the search is an admissible motion: none shorter than the generator's
  EXPECT_EQ(j["structure_optimal_longer"], 0) << j["first_structure_mismatch"];
  EXPECT_LE(j["worst_limit_excess"].get<double>(), 1e-9);
}

TEST(BenchOtgBrake, TextReportAndBadCommandLines) {
  const CliRun run = run_cli({"bench", "otg-brake", "--cases", "5", "--family-members", "20"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* text : {"DoFs beyond their limits", "standard brake vs family best",
                           "generator vs family best", "generator vs structure search"}) {
    EXPECT_NE(run.out.find(text), std::string::npos) << text << " not in:\n" << run.out;
  }
  for (const auto& args :
       std::vector<std::vector<std::string>>{{"bench", "otg-brake", "--cases", "0"},
                                             {"bench", "otg-brake", "--family-members", "1"},
                                             {"bench", "otg-brake", "--structure-seeds", "0"}}) {
    const CliRun bad = run_cli(args);
    EXPECT_EQ(bad.exit_code, 2) << bad.err;
  }
}

}  // namespace
