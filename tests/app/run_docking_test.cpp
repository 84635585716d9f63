// Drives `mjarm run docking` through the built executable: the figures in --json, the recording
// and the plot on disk, Ctrl-C, exit codes and messages for bad command lines.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_interrupt.hpp"
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

TEST(RunDockingCli, HelpNamesTheDockingOptions) {
  const CliRun run = run_cli({"run", "docking", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  // its own options, then every other parameter of the registry with unit, range and default
  for (const char* word : {"docking", "--sensorless", "--friction", "--offset", "--grid", "--gate",
                           "--plot", "--jobs", "cic | hqp-ac | se3", "--criteria.max-force",
                           "peak ‖f‖ of the contact force [N]; positive and finite (default 40.0)"})
    EXPECT_NE(run.out.find(word), std::string::npos) << word;
}

TEST(RunDockingCli, OneRunSeatsAndReportsEveryFigure) {
  const fs::path record = scratch() / "docking_record";
  const fs::path plot = scratch() / "docking_plot";
  const json doc =
      run_json({"run", "docking", "--offset", "-6", "6", "-15", "--insertion-speed", "0.02",
                "--record", record.string(), "--plot", plot.string(), "--json"});
  EXPECT_EQ(doc["scenario"], "docking");
  EXPECT_EQ(doc["controller"], "se3");
  EXPECT_EQ(doc["source"], "sensor");
  EXPECT_EQ(doc["joint_friction"], false);
  EXPECT_NEAR(doc["offset"]["dx"].get<double>(), -0.006, 1e-15);
  EXPECT_NEAR(doc["offset"]["dyaw"].get<double>(), -15.0 * 3.14159265358979323846 / 180.0, 1e-15);
  EXPECT_EQ(doc["outcome"], "seated");
  const json& m = doc["metrics"];
  EXPECT_TRUE(m["seated"].get<bool>());
  EXPECT_TRUE(m["failures"].empty());
  EXPECT_LE(m["peak_force"].get<double>(), 30.0);
  EXPECT_NEAR(m["steady_axial_force"].get<double>(), 5.0, 0.25);
  for (const char* key :
       {"peak_axial_force", "peak_wrench", "peak_axial_moment", "steady_wrench", "steady_lateral",
        "steady_tilt", "max_joint_position_percent", "max_joint_velocity_percent",
        "min_manipulability", "position_rms", "orientation_rms"})
    EXPECT_TRUE(m[key].is_number()) << key;
  // the recording, with the phases and the result, and the figure
  EXPECT_EQ(json::parse(slurp(record / "summary.json"))["status"], "finished");
  const std::string events = slurp(record / "events.csv");
  for (const char* word : {"approach", "insert", "hold", "result", "seated"})
    EXPECT_NE(events.find(word), std::string::npos) << word;
  EXPECT_NE(slurp(record / "task.csv").find("se3.wrench_z"), std::string::npos);
  EXPECT_TRUE(fs::exists(plot / "docking.png"));
  EXPECT_EQ(doc["plot"], (fs::absolute(plot) / "docking.png").string());
}

TEST(RunDockingCli, HqpAcReportsItsQpFallbacks) {
  const json doc = run_json({"run", "docking", "--controller", "hqp-ac", "--insertion-speed",
                             "0.02", "--sensorless", "--json"});
  EXPECT_EQ(doc["controller"], "hqp-ac");
  EXPECT_EQ(doc["source"], "observer");
  EXPECT_EQ(doc["outcome"], "seated");
  EXPECT_EQ(doc["qp_fallbacks"]["least_squares"], 0);
  EXPECT_EQ(doc["qp_fallbacks"]["null_space_dropped"], 0);
  const CliRun text = run_cli(
      {"run", "docking", "--controller", "hqp-ac", "--insertion-speed", "0.02", "--sensorless"});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("QP fallbacks"), std::string::npos) << text.out;
}

TEST(RunDockingCli, BadCommandLinesAreRefusedBeforeTheWork) {
  expect_error({"run", "docking", "--offset", "60", "0", "0"}, 2, "within ±50 mm");
  expect_error({"run", "docking", "--offset", "0", "0", "200"}, 2, "DYAW within ±180°");
  expect_error({"run", "docking", "--offset", "nan", "0", "0"}, 2, "--offset");
  expect_error({"run", "docking", "--offset", "1", "2"}, 2, "--offset");
  expect_error({"run", "docking", "--controller", "osc"}, 2, "controllers: cic, hqp-ac, se3");
  expect_error({"run", "docking", "--controller", "all"}, 2, "needs --grid, --gate or --map");
  expect_error({"run", "docking", "--map", "--offset", "1", "0", "0"}, 2, "not to --map");
  expect_error({"run", "docking", "--map", "--grid"}, 2, "excludes");
  expect_error({"run", "docking", "--map", "--map-step", "0"}, 2, "--map-step");
  expect_error({"run", "docking", "--offset", "8", "8", "20", "--motion.search.pitch", "0"}, 2,
               "motion.search.pitch must be positive");
  expect_error({"run", "docking", "--offset", "8", "8", "20", "--motion.search.speed", "nan"}, 2,
               "motion.search.speed");
  expect_error({"run", "docking", "--grid", "--offset", "1", "0", "0"}, 2, "single docking run");
  expect_error({"run", "docking", "--grid", "--gate"}, 2, "excludes");
  expect_error({"run", "docking", "--robot", "panda"}, 2, "run docking: unknown option '--robot'");
  expect_error({"run", "docking", "--seed", "3"}, 2, "run docking: unknown option '--seed'");
  expect_error({"run", "shelf-pick", "--sensorless"}, 2,
               "run shelf-pick: unknown option '--sensorless'");
  expect_error({"run", "docking", "--preloud", "3"}, 2, "closest: --preload");
  expect_error({"run", "docking", "--criteria.max-force", "-3"}, 2,
               "docking: criteria.max_force must be positive and finite [N], got -3");
  expect_error({"run", "docking", "--reference", "double"}, 2, "references: two-phase, single");
  expect_error({"run", "docking", "--jobs", "100"}, 2, "--jobs");
  expect_error({"run", "docking", "--insertion-speed", "0"}, 2, "--insertion-speed");
  expect_error({"run", "docking", "--preload", "-1"}, 2, "--preload");
  expect_error({"run", "docking", "--stiffness", "1", "2", "3", "4", "5"}, 2, "--stiffness");
  expect_error({"run", "docking", "--stiffness", "1000", "1000", "-1", "60", "60", "60"}, 2,
               "must be positive");
  const fs::path file = scratch() / "a_file";
  { std::ofstream(file) << "x"; }
  expect_error({"run", "docking", "--plot", (file / "sub").string()}, 2, "--plot");
  expect_error({"run", "docking", "--video", (file / "sub.mp4").string()}, 2, "--video");
  expect_error({"run", "docking", "--record", (file / "sub").string()}, 2, "--record");
  // a 58 s run (insertion at 1 mm/s) at 240 fps: 13 925 frames, refused before the work
  const fs::path mp4 = scratch() / "dock_bound.mp4";
  expect_error(
      {"run", "docking", "--video", mp4.string(), "--fps", "240", "--insertion-speed", "0.001"}, 2,
      "frames; at most 9000");
  EXPECT_FALSE(fs::exists(mp4));
}

TEST(RunDockingCli, CtrlCStopsTheGridAndSaysHowFarItGot) {
  const auto cli = mjarm::test::start_cli_on_terminal({"run", "docking", "--grid", "--jobs", "1"}, "dock_int");
  mjarm::test::interrupt_after_progress(cli);
  const CliRun run = mjarm::test::finish_cli(cli);
  EXPECT_FALSE(run.signaled);
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_NE(run.err.find(" of 27 docking runs"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("controller"), std::string::npos) << run.out;
}

}  // namespace
