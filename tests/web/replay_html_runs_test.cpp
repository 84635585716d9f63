// `--html` on recorded runs through the CLI: a pick-and-place batch's trials each get their page
// beside their recording (failed trials too), one trial's page goes to FILE or beside its
// recording, any scenario's --html without FILE writes DIR.html, and the combinations that
// cannot work are refused before the run.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::run_cli;
using mjarm::test::scratch;
using mjarm::test::slurp;
using nlohmann::json;

// the pick and place at four times the classic pace, with a divergence bound that trips
// mid-trial (tests/app/run_pick_place_test.cpp): every trial fails in seconds, recorded
std::vector<std::string> diverging_pick_place(std::vector<std::string> args) {
  for (const char* a :
       {"--dwell", "0.15", "--grip-time", "0.3", "--release-time", "0.3", "--settle-time", "0.6",
        "--max-speed", "0.25", "--max-accel", "2", "--seed", "3", "--max-acceleration", "30"})
    args.push_back(a);
  return args;
}

void expect_page(const fs::path& page) {
  ASSERT_TRUE(fs::exists(page)) << page;
  const std::string html = slurp(page);
  EXPECT_EQ(html.rfind("<!doctype html>", 0), 0u) << page;
  EXPECT_NE(html.find("id=\"mjarm-replay-data\""), std::string::npos) << page;
}

TEST(ReplayHtmlRuns, EachTrialOfABatchGetsItsPageBesideItsRecording) {
  const fs::path dir = scratch() / "replay_runs_batch";
  fs::remove_all(dir);
  const CliRun run =
      run_cli(diverging_pick_place({"run", "pick-place", "--trials", "2", "--threads", "2",
                                    "--record", dir.string(), "--html", "--json"}));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("2 of 2 trials failed"), std::string::npos) << run.err;
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  ASSERT_EQ(doc["trials"].size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const std::string seed = "seed_" + std::to_string(3 + k);
    const fs::path page = dir / (seed + ".html");
    EXPECT_EQ(doc["trials"][k]["replay"], page.string());
    expect_page(page);
    // the page is of that trial: its recording's folder names the page
    EXPECT_NE(slurp(page).find("<title>" + seed), std::string::npos) << page;
  }

  const fs::path text_dir = scratch() / "replay_runs_batch_text";
  const CliRun text = run_cli(diverging_pick_place(
      {"run", "pick-place", "--trials", "2", "--record", text_dir.string(), "--html"}));
  EXPECT_EQ(text.exit_code, 1) << text.err;
  EXPECT_NE(text.out.find("replay pages: " + text_dir.string() + "/seed_K.html"), std::string::npos)
      << text.out;
  expect_page(text_dir / "seed_4.html");
}

TEST(ReplayHtmlRuns, OneTrialsPageGoesBesideItsRecordingOrToFile) {
  const fs::path dir = scratch() / "replay_runs_one";
  const CliRun run = run_cli(
      diverging_pick_place({"run", "pick-place", "--record", dir.string(), "--html", "--json"}));
  EXPECT_EQ(run.exit_code, 1) << run.err;  // the failed trial's page is written all the same
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  const fs::path beside = scratch() / "replay_runs_one.html";
  EXPECT_EQ(doc["replay"]["path"], beside.string());
  EXPECT_EQ(doc["replay"]["recording"], dir.string());
  EXPECT_EQ(doc["replay"]["bytes"].get<std::uintmax_t>(), fs::file_size(beside));
  EXPECT_GT(doc["replay"]["frames"].get<int>(), 1);
  EXPECT_TRUE(doc["replay_error"].is_null());
  expect_page(beside);

  // any scenario: --html without FILE beside the recording (a trailing slash names the same)
  const fs::path shelf = scratch() / "replay_runs_shelf";
  const CliRun other = run_cli({"run", "shelf-pick", "--robot", "planar2", "--settle-time", "0.3",
                                "--record", shelf.string() + "/", "--html"});
  EXPECT_EQ(other.exit_code, 0) << other.err;
  expect_page(scratch() / "replay_runs_shelf.html");
}

TEST(ReplayHtmlRuns, CombinationsThatCannotWorkAreRefusedBeforeTheRun) {
  const fs::path dir = scratch() / "replay_runs_refused";
  fs::remove_all(dir);
  const CliRun named = run_cli({"run", "pick-place", "--trials", "2", "--record", dir.string(),
                                "--html", (scratch() / "one.html").string()});
  EXPECT_EQ(named.exit_code, 2) << named.err;
  EXPECT_NE(named.err.find("names one page; with --trials each trial gets its own"),
            std::string::npos)
      << named.err;
  EXPECT_NE(named.err.find("give --html without FILE"), std::string::npos) << named.err;
  EXPECT_TRUE(named.out.empty()) << named.out;

  const CliRun no_record = run_cli({"run", "pick-place", "--trials", "2", "--html"});
  EXPECT_EQ(no_record.exit_code, 2) << no_record.err;
  EXPECT_NE(no_record.err.find("--html requires --record"), std::string::npos) << no_record.err;

  const CliRun nowhere = run_cli({"run", "pick-place", "--record", dir.string(), "--html",
                                  (scratch() / "no_folder" / "x.html").string()});
  EXPECT_EQ(nowhere.exit_code, 2) << nowhere.err;
  EXPECT_NE(nowhere.err.find("--html"), std::string::npos) << nowhere.err;
  EXPECT_FALSE(fs::exists(dir));  // nothing ran
}

}  // namespace
