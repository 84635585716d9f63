// Ctrl-C in the long loops of the CLI: workspace sampling, the singularity scan, the control,
// otg, env, plan and traj benchmarks, `env run` and the demo's parts each stop, print what they
// did so far, and exit 130 (128 + SIGINT, as `run` does; 143 for SIGTERM) with a message that
// says so; a video cut short is not written and an old one is kept, and so is an old `--out` file
// of `render`, `plan` and `traj` when a signal comes while the new one is written. SIGINT is
// sent on an event: the progress line on the (pseudo-)terminal showing work done (see
// cli_interrupt.hpp), or the output's temporary file appearing.

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_interrupt.hpp"
#include "support/running_process.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::finish_cli;
using mjarm::test::interrupt_after_progress;
using mjarm::test::run_cli;
using mjarm::test::scratch;
using mjarm::test::slurp;
using mjarm::test::start_cli_on_terminal;
using nlohmann::json;

/// An interrupted run: exit 128 + SIGINT, no crash, the message on stderr.
void expect_interrupted(const CliRun& run, const std::string& message) {
  EXPECT_FALSE(run.signaled);
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_NE(run.err.find(message), std::string::npos) << message << " not in: " << run.err;
}

TEST(CliInterrupt, WorkspaceReportsTheSamplesDrawnAndWritesNoCsv) {
  const fs::path csv = scratch() / "interrupted.csv";
  const auto cli =
      start_cli_on_terminal({"workspace", "panda", "--samples", "5000000", "--out", csv.string(), "--json"},
                "workspace_int");
  interrupt_after_progress(cli);
  const CliRun run = finish_cli(cli);
  expect_interrupted(run, "of 5000000 samples; " + csv.string() + " was not written");
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["status"], "interrupted");
  EXPECT_GT(doc["samples"].get<std::size_t>(), 0u);
  EXPECT_LT(doc["samples"].get<std::size_t>(), 5000000u);
  EXPECT_TRUE(doc["csv"].is_null());
  EXPECT_FALSE(fs::exists(csv));
}

TEST(CliInterrupt, SingularityScanStopsAndPrintsItsCounts) {
  const auto cli = start_cli_on_terminal({"singularities", "panda", "--samples", "100000000"}, "sing_int");
  interrupt_after_progress(cli);
  const CliRun run = finish_cli(cli);
  expect_interrupted(run, "interrupted after ");
  EXPECT_NE(run.err.find(" of 100000000 samples"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("; interrupted): "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("lowest σmin among the samples"), std::string::npos) << run.out;
}

// issue 29, item 13's class: the controllers measured before Ctrl-C were lost (nothing on
// stdout); their rows are printed, the real-time factor is marked as not measured
TEST(CliInterrupt, ControlBenchmarkPrintsTheControllersDone) {
  const auto cli =
      start_cli_on_terminal({"bench", "control", "panda", "--steps", "200000", "--warmup", "0"}, "bench_int");
  interrupt_after_progress(cli);
  const CliRun run = finish_cli(cli);
  expect_interrupted(run, "bench control on model 'panda_torque': interrupted after ");
  EXPECT_NE(run.err.find(" controller runs; the real-time factor was not measured"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.out.find("joint-pd"), std::string::npos) << run.out;  // the first one done
  EXPECT_NE(run.out.find("real-time factor: not measured (interrupted)"), std::string::npos)
      << run.out;
}

// issue 29, item 12: `bench env --steps 1000000` went on for minutes after SIGINT or SIGTERM
// (the stop was asked only between runs of a million steps); it stops within a chunk of
// steps and prints the figures of the steps done. The progress counts environment steps, so
// the signal comes while the first round is under way.
TEST(CliInterrupt, EnvBenchmarkStopsWithinARunAndPrintsTheStepsDone) {
  for (const int signal : {SIGINT, SIGTERM}) {
    const auto cli = start_cli_on_terminal(
        {"bench", "env", "--steps", "1000000", "--rounds", "1", "--warmup", "0", "--json"},
        "env_int");
    interrupt_after_progress(cli, 1, signal);
    const CliRun run = finish_cli(cli);
    EXPECT_FALSE(run.signaled);
    EXPECT_EQ(run.exit_code, 128 + signal) << run.err;
    EXPECT_NE(run.err.find("bench env: interrupted after "), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(" of 1 overhead rounds (1000000 steps each)"), std::string::npos)
        << run.err;
    ASSERT_TRUE(json::accept(run.out)) << run.out;
    const json doc = json::parse(run.out);
    EXPECT_EQ(doc["status"], "interrupted");
    ASSERT_EQ(doc["rounds"].size(), 1u) << run.out;
    EXPECT_GT(doc["rounds"][0]["steps"].get<int>(), 0);
    EXPECT_LT(doc["rounds"][0]["steps"].get<int>(), 1000000);
    EXPECT_GT(doc["env_us_per_step"].get<double>(), 0.0);
    EXPECT_TRUE(doc["vector_runs"].empty());
  }
}

// issue 29, item 13: Ctrl-C during `bench plan` or `bench traj` exited 130 with nothing on
// stdout; the figures measured so far are printed first, marked interrupted
TEST(CliInterrupt, PlanAndTrajBenchmarksPrintTheFiguresMeasuredSoFar) {
  {
    const auto cli =
        start_cli_on_terminal({"bench", "plan", "--plans", "100000", "--json"}, "plan_int");
    interrupt_after_progress(cli);
    const CliRun run = finish_cli(cli);
    expect_interrupted(run, "bench plan: interrupted after ");
    EXPECT_NE(run.err.find(" of 100000 plans"), std::string::npos) << run.err;
    ASSERT_TRUE(json::accept(run.out)) << run.out;
    const json doc = json::parse(run.out);
    EXPECT_EQ(doc["interrupted"], true);
    EXPECT_GT(doc["plans"].get<int>(), 0);
    EXPECT_LT(doc["plans"].get<int>(), 100000);
    EXPECT_GT(doc["median_ms"].get<double>(), 0.0);
  }
  {
    const auto cli = start_cli_on_terminal({"bench", "traj", "--calls", "1000000000"}, "traj_int");
    interrupt_after_progress(cli);
    const CliRun run = finish_cli(cli);
    expect_interrupted(run, "bench traj: interrupted in case ");
    EXPECT_NE(run.err.find(" of 1000000000 calls"), std::string::npos) << run.err;
    EXPECT_NE(run.out.find("TrapezoidProfile::at"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("interrupted: the last case timed "), std::string::npos) << run.out;
  }
}

// issue 16, item 4's rule in `mjarm bench otg` (added after the fixes): Ctrl-C killed it with
// nothing printed; it stops and prints the figures of the cases done
TEST(CliInterrupt, OtgBenchmarkPrintsTheCasesDone) {
  const auto cli = start_cli_on_terminal(
      {"bench", "otg", "--cases", "10000000", "--reference-cases", "0", "--json"}, "otg_int");
  interrupt_after_progress(cli);
  const CliRun run = finish_cli(cli);
  expect_interrupted(run, "bench otg: interrupted after ");
  EXPECT_NE(run.err.find(" of 10000000 cases"), std::string::npos) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["interrupted"], true);
  EXPECT_GT(doc["cases"].get<int>(), 0);
  EXPECT_LT(doc["cases"].get<int>(), 10000000);
  EXPECT_GT(doc["mean_us"].get<double>(), 0.0);
}

TEST(CliInterrupt, IkBenchmarkPrintsTheSamplesDone) {
  const auto cli = start_cli_on_terminal({"bench", "ik", "panda", "--samples", "10000000"}, "ik_int");
  interrupt_after_progress(cli);
  const CliRun run = finish_cli(cli);
  expect_interrupted(run, "bench ik: interrupted after ");
  EXPECT_NE(run.err.find(" of 10000000 samples (mid_range seeds)"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("done)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("success [%]"), std::string::npos) << run.out;
}

TEST(CliInterrupt, DemoKeepsTheReportsOfTheFinishedParts) {
  const fs::path cwd = scratch() / "demo_interrupt";
  fs::create_directories(cwd);
  // no video (faster); a workspace part long enough to be interrupted in
  const auto cli = start_cli_on_terminal({"demo", "--video", "", "--samples", "100000000"}, "demo_int", cwd);
  // the workspace part is the first with a progress line: interrupted once it has samples
  interrupt_after_progress(cli);
  const CliRun run = finish_cli(cli);
  expect_interrupted(run, "interrupted after ");
  EXPECT_NE(run.err.find(" of 100000000 workspace samples"), std::string::npos) << run.err;
  for (const char* part : {"== shelf pick ==", "result: held", "tracking_error.png",
                           "== forward kinematics ==", "== workspace ==", "interrupted)"})
    EXPECT_NE(run.out.find(part), std::string::npos) << part << " not in:\n" << run.out;
  EXPECT_EQ(run.out.find("== inverse kinematics"), std::string::npos) << run.out;
}

// issue 29, items 7 and 14: Ctrl-C during `replay … --video F` or `bimanual --video F` left F
// with the few frames done (an existing F replaced by them), and the message did not mention
// the video. No video is written, the old F is kept, and the message says so.
TEST(CliInterrupt, AVideoCutByCtrlCIsNotWrittenAndTheOldFileIsKept) {
  const fs::path dir = scratch() / "video_interrupt";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path session = dir / "lift.session";
  const CliRun recorded = run_cli({"bimanual", "--record-session", session.string()});
  ASSERT_EQ(recorded.exit_code, 0) << recorded.err;
  const fs::path video = dir / "old.mp4";
  std::ofstream(video) << "the old video\n";
  const std::vector<std::vector<std::string>> commands{
      {"replay", session.string(), "--video", video.string(), "--size", "64x48"},
      {"bimanual", "--video", video.string(), "--size", "64x48", "--record-session",
       (dir / "new.session").string()}};
  for (const auto& command : commands) {
    const auto cli = start_cli_on_terminal(command, command[0] + "_video_int");
    interrupt_after_progress(cli);
    const CliRun run = finish_cli(cli);
    expect_interrupted(run, "video '" + video.string() + "' was not written: interrupted after ");
    EXPECT_NE(run.err.find("(the file already at '" + video.string() + "' is kept)"),
              std::string::npos)
        << run.err;
    EXPECT_EQ(slurp(video), "the old video\n") << command[0];
    // nothing else beside it: no partial video, no session of the cut lift
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"lift.session", "old.mp4"})) << command[0];
  }
}

// issue 29's bad-input matrix, a gap: `env run` installs the guard, no test signalled it
TEST(CliInterrupt, EnvRunStopsAndReportsTheEpisodesDone) {
  for (const int signal : {SIGINT, SIGTERM}) {
    const auto cli = start_cli_on_terminal(
        {"env", "run", "reach", "--episodes", "100000", "--time-limit", "0.1", "--json"},
        "env_run_int");
    interrupt_after_progress(cli, 1, signal);
    const CliRun run = finish_cli(cli);
    EXPECT_FALSE(run.signaled);
    EXPECT_EQ(run.exit_code, 128 + signal) << run.err;
    EXPECT_NE(run.err.find("env run: interrupted after "), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(" of 100000 episodes"), std::string::npos) << run.err;
    ASSERT_TRUE(json::accept(run.out)) << run.out;
    const json doc = json::parse(run.out);
    EXPECT_EQ(doc["interrupted"], true);
    EXPECT_GE(doc["episodes"].size(), 1u);
    EXPECT_LT(doc["episodes"].size(), 100000u);
  }
}

// issue 29's bad-input matrix, a gap: `render`, `plan` and `traj --out` had no handler, so a
// signal while the file was written ended the process at once and left the hidden
// `.NAME.partial-…` beside the old file, nothing said. They now stop, remove it, keep the old
// file, and say which file was not written (130; 143 for SIGTERM). The signal is sent once the
// temporary file appears (the event); a signal that comes after the file was moved into place
// still ends the command with 130, its message saying the file was written.
TEST(CliInterrupt, RenderPlanAndTrajStoppedWhileWritingKeepTheOldFile) {
  const fs::path dir = scratch() / "write_interrupt";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path waypoints = scratch() / "write_interrupt_five.json";
  std::ofstream(waypoints)
      << R"({"waypoints": [{"position": [0.45, 0.0, 0.50]}, {"position": [0.45, 0.20, 0.40]},
  {"position": [0.35, 0.25, 0.35]}, {"position": [0.30, 0.10, 0.45]},
  {"position": [0.40, -0.15, 0.50]}]})";
  struct Case {
    std::vector<std::string> args;  // the file is the last argument
    int signal;
  };
  // outputs large enough that the write is under way when the signal comes: 10⁶ rows, 9 Mpixels
  const std::vector<Case> cases{
      {{"traj", "quintic", "--start", "0", "0", "0", "--target", "1", "1", "1", "--rate",
        "100000", "--duration", "9.9", "--allow-violation", "--out", "traj.csv"},
       SIGINT},
      {{"plan", "panda_torque", "--waypoints", waypoints.string(), "--rate", "100000", "--out",
        "plan.csv"},
       SIGTERM},
      {{"render", "panda", "--size", "3000x3000", "--out", "still.png"}, SIGINT}};
  for (const Case& c : cases) {
    const std::string command = c.args.front();
    const std::string file = c.args.back();
    std::ofstream(dir / file) << "the old file\n";
    std::vector<std::string> argv{MJARM_CLI};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    // Mesa's JIT allocations are no leak of mjarm's (tests/CMakeLists.txt)
    mjarm::test::RunningProcess cli(argv, dir, {"ASAN_OPTIONS=detect_leaks=0"});
    ASSERT_TRUE(cli.started());
    const auto writing = [&] {
      for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().rfind("." + file + ".partial-", 0) == 0) return true;
      return !mjarm::test::process_alive(cli.pid());
    };
    ASSERT_TRUE(mjarm::test::eventually(writing, 600)) << command;
    cli.signal(c.signal);
    ASSERT_TRUE(cli.wait(600)) << command << " did not end";
    EXPECT_FALSE(cli.signaled()) << command << " was killed by the signal";
    EXPECT_EQ(cli.exit_code(), 128 + c.signal) << command << ": " << cli.err();
    // nothing beside the file: the temporary file was removed
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
      names.push_back(entry.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{file}) << command;
    if (cli.err().find("was not written") != std::string::npos) {
      EXPECT_NE(cli.err().find(command + ": interrupted; '" + file +
                               "' was not written (the file already there is kept)"),
                std::string::npos)
          << cli.err();
      EXPECT_EQ(slurp(dir / file), "the old file\n") << command;
    } else {
      EXPECT_NE(cli.err().find(command + ": interrupted after '" + file + "' was written"),
                std::string::npos)
          << cli.err();
      EXPECT_NE(slurp(dir / file), "the old file\n") << command;
    }
    fs::remove(dir / file);
  }
}

}  // namespace
