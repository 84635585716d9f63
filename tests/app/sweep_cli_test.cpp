// Drives `mjarm sweep` through the built executable: a sweep file run, merged and reported in
// --json, status, export as CSV and JSON, a second run of the same file finding nothing to do,
// and the exit codes and messages of bad input.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

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

fs::path sweep_file(const std::string& name, const std::string& text) {
  const fs::path path = scratch() / name;
  std::ofstream(path) << text;
  return path;
}

const char* const kSweep =
    "scenario: shelf-pick\nparameters: {robot: planar2}\naxes:\n  controller: [ct, osc]\n"
    "seeds: 3\n";

TEST(SweepCli, RunsMergesAndReportsASweepFile) {
  const fs::path file = sweep_file("run.yaml", kSweep);
  const fs::path out = scratch() / "run";
  const json doc = run_json({"sweep", "run", file.string(), "--out", out.string(), "--jobs", "2",
                             "--shard-size", "2", "--json"});
  EXPECT_EQ(doc["plan"]["trials"], 6);
  EXPECT_EQ(doc["plan"]["shards"], 3);
  EXPECT_EQ(doc["run"]["shards_run"], 3);
  EXPECT_EQ(doc["merge"]["trials"], 6);
  EXPECT_EQ(doc["success"]["successes"], 6);
  EXPECT_TRUE(fs::exists(out / "results.sqlite"));
  EXPECT_EQ(slurp(out / "sweep.yaml"), kSweep);

  const json status = run_json({"sweep", "status", out.string(), "--json"});
  EXPECT_EQ(status["done"], 3);
  EXPECT_TRUE(status["missing"].empty());
  const json report = run_json({"sweep", "report", out.string(), "--json"});
  EXPECT_EQ(report["groups"][1]["value"], "osc");
  EXPECT_EQ(report["groups"][1]["success"]["trials"], 3);
  const json plotted = run_json(
      {"sweep", "report", out.string(), "--plot", (scratch() / "figures").string(), "--json"});
  EXPECT_EQ(plotted["figures"].size(), 2u);  // success against the one axis, the metrics
  EXPECT_TRUE(fs::exists(scratch() / "figures" / "success_vs_controller.png"));
  const CliRun text = run_cli({"sweep", "report", out.string()});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("success 6/6"), std::string::npos) << text.out;

  const CliRun csv = run_cli({"sweep", "export", out.string(), "--csv"});
  EXPECT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(csv.out.rfind("trial,point,seed,controller,status,verdict,success", 0), 0u) << csv.out;
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 7);
  const fs::path exported = scratch() / "trials.json";
  EXPECT_EQ(run_cli({"sweep", "export", out.string(), "--json", "-o", exported.string()}).exit_code,
            0);
  EXPECT_EQ(json::parse(slurp(exported)).size(), 6u);

  // the same file again: the frozen plan is found, nothing is left to run
  const json again = run_json({"sweep", "run", file.string(), "--out", out.string(), "--json"});
  EXPECT_EQ(again["run"]["shards_run"], 0);
  EXPECT_EQ(again["merge"]["trials"], 6);
}

TEST(SweepCli, BadInputFailsCleanly) {
  const fs::path good = sweep_file("good.yaml", kSweep);
  const fs::path out = scratch() / "bad";
  expect_error({"sweep", "run", (scratch() / "missing.yaml").string(), "--out", out.string()}, 1,
               "missing.yaml");
  const fs::path bad = sweep_file("bad.yaml", "scenario: shelf-pick\naxes: {controler: [ct]}\n");
  expect_error({"sweep", "run", bad.string(), "--out", out.string()}, 1,
               "unknown parameter 'controler'; closest: controller");
  EXPECT_FALSE(fs::exists(out));  // refused before anything was written
  ASSERT_EQ(run_cli({"sweep", "run", good.string(), "--out", out.string(), "--shard-size", "3"})
                .exit_code,
            0);
  const fs::path other = sweep_file("other.yaml", std::string(kSweep) + "record: all\n");
  expect_error({"sweep", "run", other.string(), "--out", out.string()}, 1, "holds another sweep");
  expect_error({"sweep", "export", out.string()}, 2, "export needs --csv or --json");
  expect_error({"sweep", "shard", out.string(), "--index", "9"}, 1, "no shard 9; the plan has 2");
  expect_error({"sweep", "status", (scratch() / "nowhere").string()}, 1, "holds no sweep");
  expect_error({"sweep", "run", good.string(), "--out", out.string(), "--backend", "cloud"}, 2,
               "cloud");
}

}  // namespace
