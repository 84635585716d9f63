// `mjarm soak` (issue 29, "a soak"): a short soak reports every part and exits 0; a fault
// injected on purpose (a descriptor left open each round, a drift) exits 1 with the figures and
// the reason; Ctrl-C or SIGTERM stops it at once and prints the rounds done. Short soaks are
// bounded in rounds, not minutes: no verdict depends on the machine's speed.

#include <gtest/gtest.h>

#include <csignal>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_interrupt.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::run_cli;
using nlohmann::json;

// the smallest soak that runs every part, for @p rounds rounds, with @p extra options
std::vector<std::string> small_soak_args(int rounds, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"soak",       "--rounds", std::to_string(rounds),
                                "--tasks",    "reach",    "--episodes",
                                "1",          "--trials", "1",
                                "--warmup",   "1"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

bool has_text(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(SoakCli, AShortSoakReportsEveryPartAndExitsZero) {
  const CliRun run = run_cli(small_soak_args(2));
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  EXPECT_TRUE(has_text(run.out, "soak              ok (seed 1)")) << run.out;
  EXPECT_TRUE(has_text(run.out, "rounds            2 in ")) << run.out;
  EXPECT_TRUE(has_text(run.out, "environments      10 runs, 10 episodes, ")) << run.out;
  EXPECT_TRUE(has_text(run.out, "replays           2 of the bimanual lift (")) << run.out;
  EXPECT_TRUE(has_text(run.out, "trials            2 pick-and-place, ")) << run.out;
  EXPECT_TRUE(has_text(run.out, "heap in use       ")) << run.out;
  EXPECT_TRUE(has_text(run.out, "resident memory   ")) << run.out;
  EXPECT_TRUE(has_text(run.out, "RSS slope         not judged (1 rounds after the warm-up, 3 needed)"))
      << run.out;
  EXPECT_TRUE(has_text(run.out, "MuJoCo warnings   0 counted, 0 logged")) << run.out;
  EXPECT_TRUE(has_text(run.out, "divergences       0")) << run.out;
  EXPECT_TRUE(has_text(run.out, "drift             0 results differing from round 1's")) << run.out;
  EXPECT_FALSE(has_text(run.out, "failed:")) << run.out;
}

TEST(SoakCli, TheJsonFormHasEveryRoundsSample) {
  const CliRun run = run_cli(small_soak_args(2, {"--json"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["status"], "ok");
  EXPECT_EQ(doc["rounds"], 2);
  ASSERT_EQ(doc["samples"].size(), 2u);
  EXPECT_EQ(doc["samples"][1]["round"], 2);
  EXPECT_GT(doc["samples"][1]["rss_kib"].get<double>(), 0.0);
  EXPECT_GT(doc["samples"][1]["heap_kib"].get<double>(), 0.0);
  EXPECT_GE(doc["samples"][1]["fds"].get<int>(), 3);
  EXPECT_EQ(doc["counts"]["replays"], 2);
  EXPECT_EQ(doc["counts"]["trials"], 2);
  EXPECT_EQ(doc["drifts"], 0);
  EXPECT_EQ(doc["mujoco_warnings"], 0);
  EXPECT_EQ(doc["growth"]["judged"], false);  // 1 round after the warm-up
  EXPECT_TRUE(doc["growth"]["heap"]["slope_kib_per_hour"].is_null());
  EXPECT_TRUE(doc["growth"]["rss"]["slope_kib_per_hour"].is_null());
  EXPECT_EQ(doc["growth"]["fd_growth"], false);
  EXPECT_TRUE(doc["failures"].empty());
}

// two rounds: the second holds one descriptor more than the warm-up's round
TEST(SoakCli, ADescriptorLeftOpenFailsWithTheFigures) {
  const CliRun run = run_cli(small_soak_args(2, {"--inject-fds", "1"}));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_TRUE(has_text(run.err, "mjarm: error: soak failed: open file descriptors grow: "))
      << run.err;
  EXPECT_TRUE(has_text(run.out, "soak              failed (seed 1)")) << run.out;
  EXPECT_TRUE(has_text(run.out, "failed: open file descriptors grow")) << run.out;
}

TEST(SoakCli, ADriftFailsAndTheJsonSaysWhere) {
  const CliRun run = run_cli(small_soak_args(2, {"--inject-drift-from", "2", "--json"}));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_TRUE(has_text(run.err, "results drifted from round 1's")) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["status"], "failed");
  EXPECT_EQ(doc["drifts"], 9);  // 5 environment runs, the batch, the replay twice, the trial
  EXPECT_FALSE(doc["drift_notes"].empty());
}

TEST(SoakCli, ASignalStopsTheSoakAndPrintsTheRoundsDone) {
  for (const int signal : {SIGINT, SIGTERM}) {
    const auto cli = mjarm::test::start_cli_on_terminal(small_soak_args(1000, {"--json"}),
                                                        "soak_int");
    mjarm::test::interrupt_after_progress(cli, 1, signal);  // round 1 done
    const CliRun run = mjarm::test::finish_cli(cli);
    EXPECT_FALSE(run.signaled);
    EXPECT_EQ(run.exit_code, 128 + signal) << run.err;
    EXPECT_TRUE(has_text(run.err, "soak: interrupted in round ")) << run.err;
    ASSERT_TRUE(json::accept(run.out)) << run.out;
    const json doc = json::parse(run.out);
    EXPECT_EQ(doc["status"], "interrupted");
    EXPECT_GE(doc["rounds"].get<int>(), 1);
    EXPECT_LT(doc["rounds"].get<int>(), 1000);
    EXPECT_EQ(doc["samples"].size(), doc["rounds"].get<std::size_t>());
  }
}

TEST(SoakCli, BadOptionsAreCommandLineErrors) {
  CliRun run = run_cli({"soak", "--minutes", "0"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_TRUE(has_text(run.err, "--minutes")) << run.err;
  run = run_cli({"soak", "--tasks", "reech"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_TRUE(has_text(run.err, "reech")) << run.err;
  run = run_cli({"soak", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_TRUE(has_text(run.out, "--minutes")) << run.out;
  EXPECT_FALSE(has_text(run.out, "--inject")) << run.out;  // test hooks stay out of the help
}

}  // namespace
