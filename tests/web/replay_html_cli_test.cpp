// `mjarm replay-html` on the command line: the errors a user meets (a missing recording, another
// model, an unwritable file) exit non-zero naming what is wrong and write no file; a good run
// prints what it wrote (--json); `mjarm render` loads the recording's model.mjb.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::run_cli;
using mjarm::test::scratch;

// a short recorded run of the planar arm: `mjarm run shelf-pick` on planar2
fs::path planar_recording() {
  static const fs::path dir = [] {
    const fs::path d = scratch() / "replay_cli_rec";
    const mjarm::test::CliRun run = run_cli({"run", "shelf-pick", "--robot", "planar2",
                                             "--settle-time", "0.3", "--record", d.string()});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return d;
  }();
  return dir;
}

TEST(ReplayHtmlCli, WritesTheFileAndSaysWhat) {
  const fs::path out = scratch() / "replay_cli.html";
  const mjarm::test::CliRun run = run_cli(
      {"replay-html", planar_recording().string(), "-o", out.string(), "--rate", "30", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json doc = nlohmann::json::parse(run.out);
  EXPECT_EQ(doc["bytes"].get<std::uintmax_t>(), fs::file_size(out));
  EXPECT_NEAR(doc["rate"].get<double>(), 30.0, 3.0);
  EXPECT_GT(doc["drawn_geoms"].get<int>(), 0);
  const std::string html = mjarm::test::slurp(out);
  EXPECT_EQ(html.rfind("<!doctype html>", 0), 0u);
  EXPECT_NE(html.find("id=\"mjarm-replay-data\""), std::string::npos);
  // nothing loaded from elsewhere: one inline script, no src or href (the browser test watches
  // the page's requests)
  for (const char* link : {"<script src", "<link", "<img", "<iframe"})
    EXPECT_EQ(html.find(link), std::string::npos) << link;
}

TEST(ReplayHtmlCli, BadInputIsAClearErrorAndWritesNothing) {
  const fs::path out = scratch() / "replay_cli_bad.html";
  const mjarm::test::CliRun missing =
      run_cli({"replay-html", (scratch() / "no_such_recording").string(), "-o", out.string()});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("no_such_recording"), std::string::npos) << missing.err;

  const mjarm::test::CliRun other =
      run_cli({"replay-html", planar_recording().string(), "-o", out.string(), "--model", "arm6"});
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_NE(other.err.find("does not match the recording"), std::string::npos) << other.err;

  const mjarm::test::CliRun unwritable = run_cli({"replay-html", planar_recording().string(), "-o",
                                                  (scratch() / "no_folder" / "x.html").string()});
  EXPECT_NE(unwritable.exit_code, 0);
  EXPECT_NE(unwritable.err.find("no_folder"), std::string::npos) << unwritable.err;

  const mjarm::test::CliRun rate =
      run_cli({"replay-html", planar_recording().string(), "-o", out.string(), "--rate", "0"});
  EXPECT_EQ(rate.exit_code, 2) << rate.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ReplayHtmlCli, ARecordedRunWritesItsPageWithHtml) {
  const fs::path dir = scratch() / "replay_cli_run";
  const fs::path html = scratch() / "replay_cli_run.html";
  const mjarm::test::CliRun run =
      run_cli({"run", "shelf-pick", "--robot", "planar2", "--settle-time", "0.3", "--record",
               dir.string(), "--html", html.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(fs::exists(html));
  EXPECT_NE(mjarm::test::slurp(html).find("id=\"mjarm-replay-data\""), std::string::npos);
  // --html needs --record; an unwritable page is refused before the run
  const mjarm::test::CliRun alone =
      run_cli({"run", "pick-place", "--html", (scratch() / "alone.html").string()});
  EXPECT_EQ(alone.exit_code, 2) << alone.err;
  EXPECT_NE(alone.err.find("--record"), std::string::npos) << alone.err;
  const mjarm::test::CliRun nowhere =
      run_cli({"run", "shelf-pick", "--robot", "planar2", "--record", (scratch() / "r2").string(),
               "--html", (scratch() / "no_folder" / "x.html").string()});
  EXPECT_EQ(nowhere.exit_code, 2) << nowhere.err;
  EXPECT_FALSE(fs::exists(scratch() / "r2"));
}

TEST(ReplayHtmlCli, RenderLoadsTheRecordedModelAndDrawsASubtreeAlone) {
  const fs::path whole = scratch() / "replay_cli_whole.png";
  const fs::path alone = scratch() / "replay_cli_alone.png";
  const std::string model = (planar_recording() / "model.mjb").string();
  const mjarm::test::CliRun a =
      run_cli({"render", model, "--size", "64x48", "--out", whole.string()});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const mjarm::test::CliRun none =
      run_cli({"render", model, "--only-subtree", "no_such_body", "--out", alone.string()});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("no_such_body"), std::string::npos) << none.err;
}

}  // namespace
