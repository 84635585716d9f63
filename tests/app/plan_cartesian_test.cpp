// Drives `mjarm plan ROBOT --waypoints FILE --cartesian` through the built executable: the status,
// fraction and knots in text and --json, the exit code of a partial path, options that do not
// belong together.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using mjarm::test::run_json;
using mjarm::test::scratch;
using nlohmann::json;

/// Writes @p text into the scratch directory as @p name and returns the path.
std::string cartesian_file(const std::string& name, const std::string& text) {
  const std::filesystem::path path = scratch() / name;
  std::ofstream(path) << text;
  return path.string();
}

// from the panda's home tool position (0.307, 0, 0.590), pointing down
const char* kSideways = R"({"waypoints": [{"position": [0.307, 0.2, 0.59]}]})";
const char* kOutward = R"({"waypoints": [{"position": [1.2, 0.0, 0.59]}]})";

TEST(PlanCartesianCli, ALineIsFollowedWholeAndReportedInJson) {
  const json doc = run_json({"plan", "panda", "--waypoints",
                             cartesian_file("sideways.json", kSideways), "--cartesian", "--json"});
  EXPECT_EQ(doc["status"], "complete");
  EXPECT_EQ(doc["fraction"], 1.0);
  EXPECT_EQ(doc["stopped_at_step"], -1);
  const int steps = doc["steps"].get<int>();
  EXPECT_EQ(steps, 41);  // 0.2 m in steps of at most 5 mm
  EXPECT_EQ(doc["knot_count"], steps + 1);
  ASSERT_EQ(doc["knots"].size(), static_cast<std::size_t>(steps + 1));
  EXPECT_EQ(doc["knots"][0].size(), 7u);
  const json& last = doc["positions"].back();
  EXPECT_NEAR(last[1].get<double>(), 0.2, 1e-5);
  EXPECT_NEAR(last[2].get<double>(), 0.59, 1e-5);
  EXPECT_LT(doc["max_joint_step"].get<double>(), 0.05);
  EXPECT_EQ(doc["options"]["max_step"], 0.005);
  // twice the step, half the steps
  const json coarse =
      run_json({"plan", "panda", "--waypoints", cartesian_file("sideways.json", kSideways),
                "--cartesian", "--max-step", "0.01", "--json"});
  EXPECT_EQ(coarse["steps"], 21);
  const CliRun text = run_cli(
      {"plan", "panda", "--waypoints", cartesian_file("sideways.json", kSideways), "--cartesian"});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("result: complete — all 41 steps followed"), std::string::npos)
      << text.out;
}

TEST(PlanCartesianCli, APartialPathPrintsItsFractionAndExitsOne) {
  const CliRun run = run_cli(
      {"plan", "panda", "--waypoints", cartesian_file("outward.json", kOutward), "--cartesian"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("status              partial_ik_failure"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("fraction            0.447"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("mjarm: error: cartesian path partial_ik_failure at fraction 0.447"),
            std::string::npos)
      << run.err;
  const CliRun as_json =
      run_cli({"plan", "panda", "--waypoints", cartesian_file("outward.json", kOutward),
               "--cartesian", "--json"});
  EXPECT_EQ(as_json.exit_code, 1);
  ASSERT_TRUE(json::accept(as_json.out)) << as_json.out;
  const json doc = json::parse(as_json.out);
  EXPECT_EQ(doc["status"], "partial_ik_failure");
  EXPECT_GT(doc["fraction"].get<double>(), 0.4);
  EXPECT_LT(doc["fraction"].get<double>(), 0.5);
  EXPECT_EQ(doc["knots"].size(), doc["knot_count"].get<std::size_t>());
}

TEST(PlanCartesianCli, OptionsThatDoNotBelongTogetherAreUsageErrors) {
  const std::string file = cartesian_file("sideways.json", kSideways);
  expect_error({"plan", "panda", "--waypoints", file, "--cartesian", "--out", "x.csv"}, 2,
               "--out excludes --cartesian");
  expect_error({"plan", "panda", "--waypoints", file, "--cartesian", "--velocity-limit", "1"}, 2,
               "excludes --cartesian");
  expect_error({"plan", "panda", "--waypoints", file, "--max-step", "0.01"}, 2,
               "--max-step requires --cartesian");
  expect_error({"plan", "panda", "--waypoints", file, "--cartesian", "--max-step", "0"}, 2,
               "cartesian path: max_step must be positive and finite [m], got 0");
  expect_error({"plan", "panda", "--waypoints", file, "--cartesian", "--jump-factor", "0.5"}, 2,
               "jump_factor must be 0 (off) or ≥ 1");
  expect_error({"plan", "panda", "--waypoints", file, "--cartesian", "--max-step", "nan"}, 2,
               "--max-step");
  const CliRun help = run_cli({"plan", "--help"});
  for (const char* option : {"--cartesian", "--max-step", "--max-rotation-step", "--jump-factor",
                             "--jump-revolute", "--jump-prismatic", "--no-collisions"})
    EXPECT_NE(help.out.find(option), std::string::npos) << option;
}

}  // namespace
