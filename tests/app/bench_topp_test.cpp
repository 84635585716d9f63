// Drives `mjarm bench topp`: JSON fields of the time-optimal path parameterization's validation
// (no failure, limits exact at the grid points, never shorter than the grid minimum, the
// jerk-limited variant within its limits, no allocation per sample), the cases file for a peer,
// and clean failures for bad command lines.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::run_cli;
using mjarm::test::scratch;
using mjarm::test::slurp;
using nlohmann::json;

TEST(BenchTopp, JsonReportsTheValidationAndWritesTheCases) {
  const std::string cases = (scratch() / "bench_topp_cases.jsonl").string();
  const CliRun run =
      run_cli({"bench", "topp", "--paths", "12", "--reference-paths", "3", "--refinement-paths",
               "2", "--seed", "5", "--cases-out", cases, "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["paths"], 12);
  EXPECT_EQ(j["seed"], 5);
  EXPECT_EQ(j["failures"], 0) << j["first_failure"];
  EXPECT_LE(j["worst_grid_excess"].get<double>(), 1e-9);
  EXPECT_EQ(j["reference_paths"], 3);
  EXPECT_EQ(j["reference_failures"], 0);
  EXPECT_LE(j["worst_shorter_than_reference"].get<double>(), 1e-9);
  EXPECT_EQ(j["jerk_failures"], 0);
  EXPECT_LE(j["jerk_worst_excess"].get<double>(), 1e-9);
  EXPECT_EQ(j["allocations_per_sample"], 0.0);
  EXPECT_GT(j["median_us"].get<double>(), 0.0);
  // one JSON line per path, as bench/peers/toppra_side_by_side.py reads them
  std::istringstream lines(slurp(cases));
  std::string line;
  int count = 0;
  for (; std::getline(lines, line); ++count) {
    const json c = json::parse(line);
    EXPECT_EQ(c["path"], count);
    EXPECT_EQ(c["status"], "solved");
    EXPECT_GE(c["waypoints"].size(), 5u);
    EXPECT_GT(c["duration"].get<double>(), 0.0);
  }
  EXPECT_EQ(count, 12);
}

TEST(BenchTopp, BadCommandLines) {
  const CliRun zero = run_cli({"bench", "topp", "--paths", "0"});
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("--paths"), std::string::npos) << zero.err;
  const CliRun grid = run_cli({"bench", "topp", "--grid", "1"});
  EXPECT_EQ(grid.exit_code, 2);
  const CliRun folder = run_cli({"bench", "topp", "--paths", "1", "--cases-out", "/nonexistent/x"});
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_NE(folder.err.find("cannot write TOPP cases"), std::string::npos) << folder.err;
}

}  // namespace
