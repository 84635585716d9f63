// Drives `mjarm env list`, `mjarm env run` and `mjarm bench env`: the tasks and their specs, the
// returns of seeded episodes (the same on every thread count), the benchmark's JSON, and clean
// failures for bad command lines.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using mjarm::test::run_json;
using nlohmann::json;

TEST(EnvCommand, ListsTheTasksWithTheirSpecs) {
  const json j = run_json({"env", "list", "--json"});
  const std::vector<std::string> names{"reach", "shelf-pick", "pick-place", "docking"};
  ASSERT_EQ(j["tasks"].size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const json& task = j["tasks"][i];
    EXPECT_EQ(task["name"], names[i]);
    EXPECT_EQ(task["physics_steps_per_step"], 10);
    ASSERT_EQ(task["action_spaces"].size(), 5u);
    // pick-place's action ends with the gripper command in [0, 1]
    const int gripper = names[i] == "pick-place" ? 1 : 0;
    const json& ee = task["action_spaces"][3];
    EXPECT_EQ(ee["action_space"], "ee_pose_deltas");
    EXPECT_EQ(ee["spec"]["shape"], json::array({6 + gripper}));
    EXPECT_DOUBLE_EQ(ee["spec"]["maximum"][0].get<double>(), 0.02);
    EXPECT_EQ(task["action_spaces"][0]["spec"]["shape"], json::array({7 + gripper}));
    if (gripper) {
      EXPECT_DOUBLE_EQ(ee["spec"]["maximum"][6].get<double>(), 1.0);
    }
  }
  // unbounded sides are null in JSON
  EXPECT_TRUE(j["tasks"][0]["default_observations"][1]["maximum"][0].is_null());
  const CliRun text = run_cli({"env", "list"});
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("ee_pose_deltas: action: float64[6]"), std::string::npos) << text.out;
}

TEST(EnvCommand, EachTaskTakesItsOwnOptions) {
  const CliRun help = run_cli({"env", "run", "docking", "--help"});
  ASSERT_EQ(help.exit_code, 0) << help.err;
  for (const char* word : {"--criteria.max-force", "--scene.geometry.chamfer", "[N]"})
    EXPECT_NE(help.out.find(word), std::string::npos) << word;
  const json listed = run_json({"env", "list", "--json"});
  EXPECT_EQ(listed["tasks"][0]["options"].back()["name"], "success-distance");
  // within 0.9 m of any target: the reach succeeds on its first step
  const json j = run_json({"env", "run", "reach", "--success-distance", "0.9", "--episodes", "1",
                           "--policy", "zero", "--json"});
  EXPECT_EQ(j["task_options"]["success-distance"], 0.9);
  ASSERT_EQ(j["episodes"].size(), 1u);
  EXPECT_EQ(j["episodes"][0]["end"], "terminated");
  EXPECT_EQ(j["episodes"][0]["steps"], 1);
  expect_error({"env", "run", "reach", "--success-distance", "-1"}, 2,
               "env reach: success_distance must be");
  expect_error({"env", "run", "reach", "--sucess-distance", "1"}, 2,
               "env run reach: unexpected '--sucess-distance'; closest: --success-distance");
  expect_error({"env", "run"}, 2,
               "env run needs a TASK (reach | shelf-pick | pick-place | docking)");
}

TEST(EnvCommand, RunsSeededEpisodesTheSameOnAnyThreadCount) {
  auto run = [](const std::string& threads) {
    return run_json({"env", "run", "reach", "--episodes", "3", "--envs", "2", "--threads", threads,
                     "--time-limit", "0.2", "--seed", "5", "--json"});
  };
  const json one = run("1"), two = run("2");
  ASSERT_EQ(one["episodes"].size(), 3u);
  EXPECT_EQ(one["episodes"], two["episodes"]);
  for (const json& e : one["episodes"]) {
    EXPECT_EQ(e["steps"], 10);
    EXPECT_EQ(e["end"], "truncated");
    EXPECT_LT(e["return"].get<double>(), 0.0);
  }
  EXPECT_GT(one["steps_per_second"].get<double>(), 0.0);
  const json zero = run_json({"env", "run", "shelf-pick", "--policy", "zero", "--episodes", "1",
                              "--time-limit", "0.1", "--json"});
  EXPECT_EQ(zero["episodes"][0]["steps"], 5);
  for (const char* task : {"pick-place", "docking"}) {
    const json tasks_room = run_json(
        {"env", "run", task, "--episodes", "1", "--time-limit", "0.1", "--seed", "3", "--json"});
    EXPECT_EQ(tasks_room["task"], task);
    EXPECT_EQ(tasks_room["episodes"].size(), 1u);
    EXPECT_LE(tasks_room["episodes"][0]["steps"].get<int>(), 5);
    EXPECT_LT(tasks_room["episodes"][0]["return"].get<double>(), 0.0);
  }
}

TEST(EnvCommand, BenchReportsOverheadAndScaling) {
  const json j = run_json({"bench", "env", "--steps", "60", "--warmup", "2", "--rounds", "1",
                           "--envs", "2", "--batch-steps", "3", "--json"});
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["physics_steps_per_step"], 10);
  EXPECT_TRUE(j["replay_identical"].get<bool>());
  EXPECT_TRUE(j["threads_identical"].get<bool>());
  EXPECT_GT(j["bare_us_per_step"].get<double>(), 0.0);
  EXPECT_EQ(j["vector_runs"].size(), 2u);
  EXPECT_GE(j["speedup_cpu"].get<double>(), 1.0);
}

TEST(EnvCommand, BadCommandLinesAreUsageErrors) {
  expect_error({"env", "run", "reachh"}, 2, "reachh");
  expect_error({"env", "run", "reach", "--episodes", "0"}, 2, "--episodes");
  expect_error({"env", "run", "reach", "--action-space", "ee_pose_delta"}, 2, "ee_pose_delta");
  expect_error({"env", "run", "reach", "--time-limit", "nan"}, 2, "--time-limit");
  expect_error({"env", "run", "reach", "--episodes", "1e12"}, 2,
               "--episodes: '1e12' is not a whole number from 1 to 100000");
  expect_error({"env", "run", "reach", "--envs", "100000"}, 2, "from 1 to 4096");
  expect_error({"bench", "env", "--threads", "0"}, 2, "--threads");
  // names and counts of `bench env` itself, not only through the shared checker
  expect_error({"bench", "env", "--task", "reachh"}, 2, "--task: reachh not in {reach,");
  expect_error({"bench", "env", "--action-space", "ee_pose_delta"}, 2,
               "--action-space: unknown action space 'ee_pose_delta'; closest: ee_pose_deltas");
  expect_error({"bench", "env", "--steps", "1e12"}, 2,
               "--steps: '1e12' is not a whole number from 1 to 1000000");
  expect_error({"bench", "env", "--envs", "100000"}, 2, "--envs: '100000' is not a whole number");
  expect_error({"bench", "env", "--batch-steps", "1e12"}, 2,
               "--batch-steps: '1e12' is not a whole number from 1 to 100000");
  expect_error({"env"}, 2, "subcommand");
}

}  // namespace
