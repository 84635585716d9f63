// Drives `mjarm run pick-place` through the built executable: one trial in --json, a batch's
// table and JSON, a diverging batch with its recordings, videos of several cameras, Ctrl-C, and
// every bad command line.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_interrupt.hpp"
#include "app/cli_runner.hpp"
#include "render/render_test_support.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using mjarm::test::run_json;
using mjarm::test::scratch;
using mjarm::test::slurp;
using nlohmann::json;

// the machine at four times the classic pace: same states and checks, seconds instead of tens
std::vector<std::string> brisk_pick_place(std::vector<std::string> args) {
  for (const char* a : {"--dwell", "0.15", "--grip-time", "0.3", "--release-time", "0.3",
                        "--settle-time", "0.6", "--max-speed", "0.25", "--max-accel", "2"})
    args.push_back(a);
  return args;
}

TEST(RunPickPlaceCli, HelpNamesTheOptions) {
  const CliRun run = run_cli({"run", "pick-place", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  for (const char* word :
       {"pick-place", "--grasp", "--mode", "--trials", "--threads", "--classic", "--object",
        "--target", "--cameras", "--video-per-camera", "--grasp-force", "--weld-solref", "--noslip",
        "--place-height", "--criteria.max-tilt", "--impratio",
        "--motion.limits.max-angular-velocity"})
    EXPECT_NE(run.out.find(word), std::string::npos) << word;
}

TEST(RunPickPlaceCli, OneTrialInJson) {
  const json doc =
      run_json(brisk_pick_place({"run", "pick-place", "--robot", "panda_hand", "--grasp", "weld",
                                 "--mode", "torque", "--seed", "4", "--json"}));
  EXPECT_EQ(doc["scenario"], "pick-place");
  EXPECT_EQ(doc["robot"], "panda_hand");
  EXPECT_EQ(doc["grasp"], "weld");
  EXPECT_EQ(doc["mode"], "torque");
  const json& t = doc["trial"];
  EXPECT_EQ(t["seed"], 4);
  EXPECT_EQ(t["success"], true) << t["reason"];
  EXPECT_EQ(t["failure"], "none");
  EXPECT_LT(t["placement_error"].get<double>(), 0.005);
  EXPECT_LT(t["weld_jump"].get<double>(), 0.05e-3);
  EXPECT_GT(t["grasp_force"].get<double>(), 1.0);
  EXPECT_TRUE(t["closed"].get<bool>());
  for (const char* key : {"object", "target", "tilt", "final_speed", "cycle_time", "max_slip",
                          "weld_settle", "status", "message"})
    EXPECT_TRUE(t.contains(key)) << key;
  EXPECT_TRUE(doc["recording"].is_null());
  EXPECT_TRUE(doc["video"].is_null());
}

TEST(RunPickPlaceCli, ABatchPrintsItsTableAndJson) {
  const std::vector<std::string> args =
      brisk_pick_place({"run", "pick-place", "--grasp", "friction", "--trials", "3", "--threads",
                        "2", "--seed", "7"});
  const CliRun text = run_cli(args);
  ASSERT_EQ(text.exit_code, 0) << text.err << text.out;
  for (const char* line : {"pick and place on arm6, friction grasp, position mode: 3 trials "
                           "(seeds 7–9) on 2 threads",
                           "success   3/3 (100.0 %)", "failures  none", "placement error [mm]",
                           "cycle time [s]", "grasp force [N]", "largest slip [mm]"})
    EXPECT_NE(text.out.find(line), std::string::npos) << line << "\n" << text.out;
  EXPECT_EQ(text.out.find("weld jump"), std::string::npos);  // friction: no weld
  std::vector<std::string> json_args = args;
  json_args.push_back("--json");
  const json doc = run_json(json_args);
  EXPECT_EQ(doc["first_seed"], 7);
  EXPECT_EQ(doc["threads"], 2);
  EXPECT_EQ(doc["summary"]["trials"], 3);
  EXPECT_EQ(doc["summary"]["successes"], 3);
  EXPECT_EQ(doc["summary"]["failures"]["dropped"], 0);
  ASSERT_EQ(doc["trials"].size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(doc["trials"][k]["seed"], 7 + k);
}

TEST(RunPickPlaceCli, FailedTrialsAreListedWithTheirReplayAndRecordings) {
  // this divergence bound trips mid-trial (tests/tasks/pick_place_test.cpp): every trial fails,
  // the batch goes on, each trial's recording is finalized
  const fs::path dir = scratch() / "pick_place_batch";
  const CliRun run =
      run_cli(brisk_pick_place({"run", "pick-place", "--seed", "3", "--trials", "2",
                                "--max-acceleration", "30", "--record", dir.string()}));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("2 of 2 trials failed"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("failures  diverged 2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("seed 3: diverged — t = "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("mjarm run pick-place --robot arm6 --grasp weld --mode position --seed 3 "
                         "--video seed_3.mp4"),
            std::string::npos)
      << run.out;
  for (const char* seed : {"seed_3", "seed_4"}) {
    const std::string summary = slurp(dir / seed / "summary.json");
    ASSERT_TRUE(json::accept(summary)) << seed;
    EXPECT_EQ(json::parse(summary)["status"], "diverged");
  }
}

TEST(RunPickPlaceCli, VideoOfSeveralCamerasTiledOrOneFileEach) {
  const fs::path tiled = scratch() / "pick_place_tiled.mp4";
  const CliRun one =
      run_cli(brisk_pick_place({"run", "pick-place", "--seed", "4", "--video", tiled.string(),
                                "--cameras", "front,top", "--size", "64x48", "--fps", "3"}));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("video"), std::string::npos);
  const auto size = mjarm::test::run_process({"/usr/bin/ffprobe", "-v", "error", "-select_streams",
                                              "v:0", "-show_entries", "stream=width,height", "-of",
                                              "csv=p=0", tiled.string()});
  EXPECT_NE(size.out.find("128,48"), std::string::npos) << size.out << size.err;  // two tiles
  const fs::path each = scratch() / "pick_place_each.mp4";
  const CliRun two = run_cli(brisk_pick_place(
      {"run", "pick-place", "--seed", "4", "--video", each.string(), "--cameras", "front,follow",
       "--video-per-camera", "--size", "64x48", "--fps", "3", "--json"}));
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_TRUE(fs::exists(scratch() / "pick_place_each_front.mp4"));
  EXPECT_TRUE(fs::exists(scratch() / "pick_place_each_follow.mp4"));
  const json doc = json::parse(two.out);
  EXPECT_EQ(doc["video"]["paths"].size(), 2u);
  EXPECT_GT(doc["video"]["frames"].get<int>(), 10);
}

TEST(RunPickPlaceCli, CtrlCStopsTheBatchWithTheTrialsDone) {
  const auto cli = mjarm::test::start_cli_on_terminal(
      {"run", "pick-place", "--trials", "400", "--threads", "2"}, "pick_place_interrupt");
  mjarm::test::interrupt_after_progress(cli);
  const CliRun run = mjarm::test::finish_cli(cli);
  EXPECT_FALSE(run.signaled);
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_NE(run.err.find("interrupted after"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("the figures above are of the trials done"), std::string::npos) << run.out;
}

TEST(RunPickPlaceCli, BadCommandLines) {
  expect_error({"run", "pick-place", "--robot", "panda"}, 2,
               "unknown robot 'panda' for the pick and place; choices: arm6, panda_hand");
  expect_error({"run", "pick-place", "--grasp", "glue"}, 2, "unknown grasp 'glue'");
  expect_error({"run", "pick-place", "--mode", "fast"}, 2, "choices: position, torque");
  expect_error({"run", "pick-place", "--trials", "2", "--video", "v.mp4"}, 2,
               "--video films one trial");
  expect_error({"run", "pick-place", "--video", "v.mp4", "--cameras", "front,back"}, 2,
               "unknown camera 'back'");
  expect_error({"run", "pick-place", "--cameras", "top"}, 2, "need --video FILE");
  expect_error({"run", "pick-place", "--controller", "osc"}, 2,
               "run pick-place: unknown option '--controller'");
  expect_error({"run", "shelf-pick", "--grasp", "weld"}, 2,
               "run shelf-pick: unknown option '--grasp'");
  expect_error({"run", "pick-place", "--impratio", "0.5"}, 2,
               "pick-place: impratio must be finite and ≥ 1, got 0.5");
  expect_error({"run", "pick-place", "--trials", "0"}, 2, "--trials");
  expect_error({"run", "pick-place", "--trials", "20000"}, 2, "--trials");
  expect_error({"run", "pick-place", "--object", "0.3"}, 2, "--object");
  expect_error({"run", "pick-place", "--video", "/proc/x/v.mp4"}, 2, "--video");
  // an object out of reach: a failure (exit 1) with the reach in the message
  expect_error({"run", "pick-place", "--object", "0.8", "0.1"}, 1, "out of reach of arm6");
  expect_error({"run", "pick-place", "--target", "0.1", "0.7"}, 1, "arm6 reaches");
}

}  // namespace
