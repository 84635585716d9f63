// Drives `mjarm plan` and `mjarm run plan` through the built executable: the per-waypoint checks
// in --json, the trajectory CSV, the tracking figures, exit codes and messages for bad input.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "app/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using mjarm::test::run_json;
using mjarm::test::scratch;
using mjarm::test::slurp;
using nlohmann::json;

/// Writes @p text into the scratch directory as @p name and returns the path.
std::string plan_file(const std::string& name, const std::string& text) {
  const fs::path path = scratch() / name;
  std::ofstream(path) << text;
  return path.string();
}

const char* kFive =
    R"({"waypoints": [{"position": [0.45, 0.0, 0.50]}, {"position": [0.45, 0.20, 0.40]},
  {"position": [0.35, 0.25, 0.35]}, {"position": [0.30, 0.10, 0.45]},
  {"position": [0.40, -0.15, 0.50]}]})";

TEST(PlanCli, HelpNamesTheOptions) {
  const CliRun run = run_cli({"plan", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  for (const char* option : {"--waypoints", "--site", "--q", "--key", "--velocity-limit",
                             "--acceleration-limit", "--torque-limit", "--min-sigma", "--planner",
                             "--out", "--rate", "--plot", "--size", "--json"})
    EXPECT_NE(run.out.find(option), std::string::npos) << option;
}

TEST(PlanCli, JsonReportsEveryWaypointAndCsvHoldsTheTrajectory) {
  const std::string csv = (scratch() / "plan_trajectory.csv").string();
  const json doc = run_json({"plan", "panda_torque", "--waypoints", plan_file("five.json", kFive),
                             "--out", csv, "--rate", "100", "--json"});
  EXPECT_EQ(doc["status"], "ok");
  EXPECT_EQ(doc["start"], "keyframe 'home'");
  ASSERT_EQ(doc["waypoints"].size(), 5u);
  for (const json& w : doc["waypoints"]) {
    EXPECT_EQ(w["check"], "none");
    EXPECT_LT(w["position_error"].get<double>(), 1e-4);
    EXPECT_GE(w["segment_min_sigma"].get<double>(), 0.02);
  }
  const double duration = doc["duration"].get<double>();
  EXPECT_GT(duration, 1.0);
  std::istringstream lines(slurp(csv));
  std::string line;
  int rows = -1;  // the header
  while (std::getline(lines, line)) ++rows;
  EXPECT_EQ(rows, static_cast<int>(std::ceil(duration * 100 - 1e-9)) + 1);
  // slower limits, longer plan
  const json slow = run_json({"plan", "panda_torque", "--waypoints", plan_file("five.json", kFive),
                              "--velocity-limit", "0.5", "--json"});
  EXPECT_GT(slow["duration"].get<double>(), 1.5 * duration);
}

TEST(PlanCli, PlotDrawsTheJointTrajectoryAgainstItsLimits) {
  const fs::path plots = scratch() / "plan_plot";
  const json doc =
      run_json({"plan", "panda_torque", "--waypoints", plan_file("five.json", kFive), "--plot",
                plots.string(), "--rate", "50", "--size", "640x800", "--json"});
  EXPECT_EQ(doc["status"], "ok");
  EXPECT_EQ(doc["plot"], (plots / "trajectory.png").string());
  const std::string png = slurp(plots / "trajectory.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  // the figure's data: 7 joints, the velocity limit of 1 rad/s dashed
  const std::string script = slurp(plots / "gnuplot" / "trajectory.gp");
  EXPECT_NE(script.find("joint7"), std::string::npos);
  EXPECT_NE(script.find("velocity"), std::string::npos);
  // an output that cannot be written is refused before the plan (exit 2)
  const std::string file = plan_file("not_a_folder", "x");
  expect_error({"plan", "panda_torque", "--waypoints", plan_file("five.json", kFive), "--plot",
                file + "/sub"},
               2, "--plot");
}

TEST(PlanCli, AFailedPlanPrintsTheChecksAndExitsOne) {
  const CliRun run = run_cli({"plan", "panda_torque", "--waypoints",
                              plan_file("far.csv", "x,y,z\n0.45,0,0.5\n1.6,0,0.5\n")});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("result: unreachable"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("waypoint 1: no IK solution"), std::string::npos) << run.err;
}

TEST(PlanCli, BadInputFailsClearly) {
  expect_error({"plan", "panda_torque"}, 2, "--waypoints is required");
  expect_error({"plan", "panda_torque", "--waypoints", "/nonexistent/w.json"}, 1,
               "waypoint file '/nonexistent/w.json' does not exist");
  expect_error({"plan", "panda_torque", "--waypoints", "/dev/zero"}, 1,
               "waypoint file '/dev/zero' is a character device, expected a regular file");
  expect_error({"plan", "panda_torque", "--waypoints", plan_file("nan.csv", "0.4,nan,0.5\n")}, 1,
               "'nan' is not a finite number");
  expect_error(
      {"plan", "panda_torque", "--waypoints", plan_file("empty.json", R"({"waypoints": []})")}, 1,
      "holds no waypoint");
  expect_error({"plan", "panda_torque", "--waypoints", plan_file("five.json", kFive),
                "--velocity-limit", "1", "2"},
               2, "--velocity-limit takes 1 value or 7");
  expect_error(
      {"plan", "panda_torque", "--waypoints", plan_file("five.json", kFive), "--rate", "0"}, 2,
      "--rate must be in (0, 100000] Hz");
  // issue 16, item 9's rule: the output path is checked before the plan is made
  expect_error({"plan", "panda_torque", "--waypoints", plan_file("five.json", kFive), "--out",
                "/proc/plan.csv"},
               2, "--out: cannot create '/proc/plan.csv'");
}

// issue 16, item 4's rule in `mjarm plan`: slow limits ran for minutes (--velocity-limit 0.0001)
// and --out --rate 100000 on a 5-minute plan built gigabytes in memory; both are bounded
TEST(PlanCli, AbsurdWorkIsRefusedNamingTheBound) {
  const std::string waypoints = plan_file("five.json", kFive);
  const CliRun slow =
      run_cli({"plan", "panda_torque", "--waypoints", waypoints, "--velocity-limit", "0.0001"});
  EXPECT_EQ(slow.exit_code, 1) << slow.err;
  EXPECT_NE(slow.err.find("samples a segment may have"), std::string::npos) << slow.err;
  // refused before any sample was checked, not after minutes of checks
  EXPECT_NE(slow.err.find("the plan had checked 0 before it"), std::string::npos) << slow.err;
  // 0.05 rad/s: a plan of about a minute, sampled at 100 kHz would be millions of CSV rows
  const fs::path csv = scratch() / "huge_plan.csv";
  const CliRun rows = run_cli({"plan", "panda_torque", "--waypoints", waypoints, "--velocity-limit",
                               "0.05", "--out", csv.string(), "--rate", "100000"});
  EXPECT_EQ(rows.exit_code, 2) << rows.err;
  EXPECT_NE(rows.err.find("rows, more than 10⁶: lower --rate"), std::string::npos) << rows.err;
  EXPECT_NE(rows.out.find("result: ok"), std::string::npos) << rows.out;  // the plan is shown
  EXPECT_FALSE(fs::exists(csv));
}

TEST(PlanCli, OmplPlansAroundAnObstacleOfASceneFile) {
  // a box in the way of joint 1's swing from home to a tool position on the left
  const std::string scene = plan_file("ompl_box.yaml", R"(name: ompl_box
robots:
  - {name: panda, model: panda}
fixtures:
  - {name: wall, shape: box, size: [0.08, 0.08, 0.08], mass: 1, pos: [0.22, 0.22, 0.55]}
)");
  const std::string left =
      plan_file("left.json", R"({"waypoints": [{"position": [-0.0089, 0.3067, 0.59]}]})");
  const json blocked = run_json({"plan", scene, "--site", "panda/attachment_site", "--waypoints",
                                 left, "--planner", "ompl:rrtconnect", "--json"});
  ASSERT_EQ(blocked["status"], "ok") << blocked.dump();
  ASSERT_EQ(blocked["waypoints"].size(), 1u);
  EXPECT_GE(blocked["waypoints"][0]["ompl_knots"].get<int>(), 1) << blocked.dump();
  EXPECT_TRUE(blocked["waypoints"][0]["detour"].get<bool>());
  expect_error(
      {"plan", scene, "--site", "panda/attachment_site", "--waypoints", left, "--planner", "rrt"},
      2, "--planner: 'rrt' is not waypoint, ompl:rrtconnect");
}

TEST(RunPlanCli, PlansAroundASceneFilesObstacleAndTracksWithoutAContact) {
  const std::string scene = plan_file("run_plan_wall.yaml", R"(name: run_plan_wall
fixtures:
  - {name: wall, shape: box, size: [0.08, 0.08, 0.08], mass: 1, pos: [0.22, 0.22, 0.55]}
)");
  const std::string left =
      plan_file("run_left.json", R"({"waypoints": [{"position": [-0.0089, 0.3067, 0.59]}]})");
  const json doc = run_json({"run", "plan", "panda", "--scene", scene, "--waypoints", left,
                             "--planner", "ompl:rrtconnect", "--controller", "ct", "--json"});
  EXPECT_EQ(doc["status"], "ok");
  EXPECT_EQ(doc["scene"], scene);
  EXPECT_EQ(doc["frame"], "panda/attachment_site");
  EXPECT_TRUE(doc["waypoints"][0]["detour"].get<bool>()) << doc.dump();
  EXPECT_EQ(doc["run"]["status"], "finished");
  EXPECT_EQ(doc["run"]["contacts"]["ticks"], 0);
  EXPECT_LT(doc["run"]["max_position_error"].get<double>(), 0.01);
  const CliRun text = run_cli({"run", "plan", "panda", "--scene", scene, "--waypoints", left,
                               "--planner", "ompl:rrtconnect", "--controller", "ct"});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("contacts                  none"), std::string::npos) << text.out;
  // a scene file holding the robot already: both named
  const std::string twice =
      plan_file("run_plan_twice.yaml", "name: twice\nrobots:\n  - {name: panda, model: panda}\n");
  expect_error({"run", "plan", "panda", "--scene", twice, "--waypoints", left}, 1,
               "cannot join the scene file " + twice);
}

TEST(RunPlanCli, TracksThePlanAndReportsTheError) {
  const json doc = run_json({"run", "plan", "panda", "--waypoints", plan_file("five.json", kFive),
                             "--controller", "osc", "--json"});
  EXPECT_EQ(doc["status"], "ok");
  EXPECT_EQ(doc["run"]["status"], "finished");
  EXPECT_LT(doc["run"]["max_position_error"].get<double>(), 0.01);
  EXPECT_LT(doc["run"]["final_position_error"].get<double>(), 0.002);
  EXPECT_LE(doc["run"]["rms_position_error"].get<double>(),
            doc["run"]["max_position_error"].get<double>());
  expect_error({"run", "plan", "panda", "--controller", "osc"}, 2, "run plan needs --waypoints");
  expect_error({"run", "plan", "panda", "--waypoints", plan_file("five.json", kFive),
                "--controller", "nope"},
               2, "unknown controller");
  expect_error({"run", "plan", "ur9", "--waypoints", plan_file("five.json", kFive)}, 2,
               "unknown robot");
  expect_error({"run", "plan", "panda", "--waypoints", plan_file("five.json", kFive), "--record",
                (scratch() / "rec").string()},
               2, "run plan: unknown option '--record'");
  expect_error({"run", "shelf-pick", "--waypoints", plan_file("five.json", kFive)}, 2,
               "run shelf-pick: unknown option '--waypoints'");
}

}  // namespace
