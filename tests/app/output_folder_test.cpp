// Output folders through the built executable (issue 29, item 15): one writer at a time — a run
// whose --record folder (or a plot whose --out folder) another writer holds is refused before
// the work, naming the folder and the holder's PID — and a summary.json that says whose
// recording it is (command line, seed, mjarm and MuJoCo versions).

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/version.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::run_cli;
using mjarm::test::scratch;
using mjarm::test::slurp;
using nlohmann::json;

// Before: both runs reported success and the last one's files won; summary.json held neither
// the seed nor the command line.
TEST(OutputFolders, ASecondWriterIsRefusedAndTheSummarySaysWhoseItIs) {
  const fs::path dir = scratch() / "held_folder";
  fs::remove_all(dir);
  // this test process holds the folder, as a run recording into it would
  const mjarm::Robot robot = mjarm::Robot::bundled("planar2_torque");
  mjarm::Simulation sim(robot);
  std::optional<mjarm::Recorder> holder(std::in_place, sim, dir);
  const std::string held_by =
      "is being written by another mjarm (PID " + std::to_string(::getpid()) + ", since ";

  const CliRun run = run_cli({"run", "shelf-pick", "--record", dir.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("recording folder '" + dir.string() + "' " + held_by), std::string::npos)
      << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;  // refused before the run

  // a recording to plot, into the held folder
  const fs::path rec = scratch() / "invoked";
  fs::remove_all(rec);
  const std::vector<std::string> args{"run", "shelf-pick", "--record", rec.string(), "--seed", "5"};
  ASSERT_EQ(run_cli(args).exit_code, 0);
  const CliRun plot = run_cli({"plot", rec.string(), "--out", dir.string()});
  EXPECT_EQ(plot.exit_code, 1) << plot.err;
  EXPECT_NE(plot.err.find("plot folder '" + dir.string() + "' " + held_by), std::string::npos)
      << plot.err;
  EXPECT_FALSE(fs::exists(dir / "gnuplot"));  // nothing of it left

  const json summary = json::parse(slurp(rec / "summary.json"));
  const json& in = summary["invocation"];
  std::vector<std::string> command_line{MJARM_CLI};
  command_line.insert(command_line.end(), args.begin(), args.end());
  EXPECT_EQ(in["command_line"].get<std::vector<std::string>>(), command_line) << in;
  EXPECT_EQ(in["seed"], 5) << in;
  EXPECT_EQ(in["mjarm_version"], mjarm::version());
  EXPECT_EQ(in["mujoco_version"], mj_versionString());
  EXPECT_EQ(in["working_directory"], scratch().string());
  EXPECT_GT(in["pid"].get<long>(), 0);

  // released: the folder takes a recording again
  holder->finalize("aborted");
  EXPECT_EQ(run_cli({"run", "shelf-pick", "--record", dir.string()}).exit_code, 0);
  EXPECT_EQ(json::parse(slurp(dir / "summary.json"))["invocation"]["seed"], 1);
}

}  // namespace
