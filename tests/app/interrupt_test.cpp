// Ctrl-C in the long loops of the CLI: workspace sampling, the singularity scan, the control
// and otg benchmarks and the demo's parts each stop, print what they did so far, and exit 130 (128
// + SIGINT, as `run` does) with a message that says so. SIGINT is sent once the progress line on
// the (pseudo-)terminal shows work done (see cli_interrupt.hpp).

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_interrupt.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::finish_cli;
using mjarm::test::interrupt_after_progress;
using mjarm::test::scratch;
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

TEST(CliInterrupt, ControlBenchmarkStops) {
  const auto cli =
      start_cli_on_terminal({"bench", "control", "panda", "--steps", "200000", "--warmup", "0"}, "bench_int");
  interrupt_after_progress(cli);
  const CliRun run = finish_cli(cli);
  expect_interrupted(run, "bench control on model 'panda_torque': interrupted");
  EXPECT_TRUE(run.out.empty()) << run.out;
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

}  // namespace
