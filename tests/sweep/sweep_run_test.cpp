// Running sweeps (mjarm/sweep/): shards written whole, the same rows whatever the number of
// workers, merging twice giving the same database, damaged and foreign shard files refused and
// run again by a resume, Ctrl-C keeping the finished shards, the trials that keep a recording,
// and the report's success rates and Wilson intervals.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/sweep/local_backend.hpp"
#include "mjarm/sweep/sweep_dashboard.hpp"
#include "mjarm/sweep/sweep_plots.hpp"
#include "mjarm/sweep/sweep_report.hpp"
#include "mjarm/web/replay_html.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;
using test::error_of;
using test::scratch;
using test::slurp;
using ::testing::HasSubstr;

// 2 controllers × 2 tolerances × 3 seeds of the planar arm's shelf pick: 12 trials in 5 shards
const char* const kSweep = R"(
scenario: shelf-pick
parameters: {robot: planar2}
axes:
  controller: [ct, osc]
  criteria.tolerance: {from: 0.0005, to: 0.001, num: 2}
seeds: 3
)";

SweepFolder prepared(const std::string& name, const std::string& text = kSweep,
                     std::int64_t shard_size = 3) {
  const SweepFolder folder{scratch() / name};
  prepare_sweep_folder(folder, make_sweep_plan(parse_sweep_file(text, "s.yaml"), shard_size), text);
  return folder;
}

LocalSweepResult run(const SweepFolder& folder, int jobs) {
  LocalSweepOptions options;
  options.jobs = jobs;
  return run_sweep_local(folder, read_sweep_plan(folder), options);
}

TEST(SweepRun, TheRowsAreTheSameOnOneWorkerOrTwoAndMergingTwiceChangesNothing) {
  const SweepFolder one = prepared("one"), two = prepared("two");
  const LocalSweepResult r1 = run(one, 1);
  const LocalSweepResult r2 = run(two, 2);
  EXPECT_EQ(r1.shards_run, 4);
  EXPECT_EQ(r2.trials_run, 12);
  EXPECT_EQ(r2.jobs, 2);
  EXPECT_FALSE(r2.interrupted);
  const SweepMerge m = merge_sweep(one);
  EXPECT_EQ(m.trials, 12);
  EXPECT_EQ(m.missing, 0);
  merge_sweep(two);
  const ResultTable a = read_trials(one), b = read_trials(two);
  ASSERT_EQ(a.rows.size(), 12u);
  EXPECT_EQ(a.columns, b.columns);
  EXPECT_EQ(a.rows, b.rows);
  EXPECT_EQ(a.columns[3], "controller");
  EXPECT_EQ(a.rows[11][3], "osc");
  EXPECT_EQ(a.rows[11][a.column("criteria.tolerance")], 0.001);
  EXPECT_EQ(a.rows[11][a.column("seed")], 3);
  EXPECT_EQ(a.rows[0][a.column("verdict")], "held");

  merge_sweep(one);  // again: the same rows, no partial file left
  EXPECT_EQ(read_trials(one).rows, a.rows);
  EXPECT_FALSE(fs::exists(one.dir / "results.sqlite.partial"));
  const nlohmann::ordered_json sweep = read_sweep_row(one);
  EXPECT_EQ(sweep["scenario"], "shelf-pick");
  EXPECT_EQ(sweep["shards_merged"], 4);
  EXPECT_EQ(table_csv(a).substr(0, 27), "trial,point,seed,controller");
  EXPECT_EQ(table_json(a)[5]["controller"], "ct");
}

TEST(SweepRun, AFolderOfAnotherSweepIsRefusedAndTheSameSweepIsTakenAsItIs) {
  const SweepFolder folder = prepared("same");
  EXPECT_NO_THROW(prepared("same"));
  const std::string other = std::string(kSweep) + "record: all\n";
  EXPECT_THAT(error_of([&] { prepared("same", other); }), HasSubstr("holds another sweep (plan "));
  fs::create_directories(scratch() / "busy");
  std::ofstream(scratch() / "busy" / "notes.txt") << "mine";
  EXPECT_THAT(error_of([&] { prepared("busy"); }), HasSubstr("is not empty and holds no sweep"));
  EXPECT_THAT(error_of([&] { merge_sweep(SweepFolder{scratch() / "none"}); }),
              HasSubstr("holds no sweep (no plan.json)"));
}

TEST(SweepRun, ADamagedOrForeignShardIsRefusedByTheMergeAndRunAgainByAResume) {
  const SweepFolder folder = prepared("damaged");
  run(folder, 2);
  const SweepPlan plan = read_sweep_plan(folder);
  const std::string whole = slurp(folder.shard(1));
  std::ofstream(folder.shard(1), std::ios::trunc) << whole.substr(0, whole.size() / 2);
  std::string foreign = slurp(folder.shard(2));
  foreign.replace(foreign.find(plan.hash), plan.hash.size(), "0123456789abcdef");
  std::ofstream(folder.shard(2), std::ios::trunc) << foreign;
  const ShardStates states = shard_states(folder, plan);
  ASSERT_EQ(states.damaged.size(), 2u);
  EXPECT_THAT(states.damaged[0].second, HasSubstr("not valid JSON (truncated?)"));
  EXPECT_THAT(states.damaged[1].second, HasSubstr("of another plan"));
  EXPECT_THAT(error_of([&] { merge_sweep(folder); }), HasSubstr("2 damaged shard files"));
  fs::remove(folder.shard(3));
  const LocalSweepResult again = run(folder, 1);
  EXPECT_EQ(again.shards_run, 3);  // the damaged two and the missing one, nothing else
  EXPECT_EQ(merge_sweep(folder).trials, 12);
}

TEST(SweepRun, CtrlCKeepsTheFinishedShardsAndAResumeRunsTheRest) {
  const SweepFolder folder = prepared("interrupted", kSweep, 2);  // 6 shards of 2
  const SweepPlan plan = read_sweep_plan(folder);
  LocalSweepResult cut;
  {
    const InterruptGuard guard;
    LocalSweepOptions options;
    options.jobs = 1;
    options.progress = [](std::int64_t done, std::int64_t) {
      if (done == 5) std::raise(SIGINT);  // in the third shard
    };
    cut = run_sweep_local(folder, plan, options);
  }
  EXPECT_TRUE(cut.interrupted);
  EXPECT_EQ(cut.shards_run, 2);
  EXPECT_EQ(cut.shards_left, 4);
  const ShardStates states = shard_states(folder, plan);
  EXPECT_EQ(states.done.size(), 2u);
  EXPECT_TRUE(states.damaged.empty());  // the cut shard wrote nothing
  EXPECT_EQ(run(folder, 2).shards_run, 4);
  EXPECT_EQ(merge_sweep(folder).trials, 12);
}

TEST(SweepRun, FailedTrialsKeepARecordingAndAVideoAndTheReportCountsThem) {
  // a tolerance no run reaches in the time allowed: every trial fails and is recorded again
  const std::string text = R"(
scenario: shelf-pick
parameters: {robot: planar2, controller: ct, settle-time: 0.05, criteria.hold-time: 0.04,
             criteria.steady-window: 0.02}
axes:
  criteria.tolerance: [1.0e-9, 0.01]
record: failures
)";
  const SweepFolder folder = prepared("recorded", text, 2);
  run(folder, 1);
  merge_sweep(folder);
  const ResultTable t = read_trials(folder);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0][t.column("verdict")], "not_held");
  EXPECT_EQ(t.rows[0][t.column("recording")], "records/trial-00000000/recording");
  EXPECT_TRUE(fs::exists(folder.dir / "records/trial-00000000/recording/summary.json"));
  EXPECT_TRUE(fs::exists(folder.dir / "records/trial-00000000/video.mp4"));
  // its replay page, where the build holds the page (MJARM_WEB)
  EXPECT_EQ(fs::exists(folder.dir / "records/trial-00000000/replay.html"),
            mjarm::replay_html_available());
  EXPECT_EQ(t.rows[1][t.column("verdict")], "held");
  EXPECT_TRUE(t.rows[1][t.column("recording")].is_null());  // a success keeps nothing
  EXPECT_FALSE(fs::exists(folder.record(1)));

  const SweepReport r = sweep_report(folder);
  EXPECT_EQ(r.success.successes, 1);
  EXPECT_EQ(r.verdicts.at("not_held"), 1);
  ASSERT_EQ(r.groups.size(), 2u);
  EXPECT_EQ(r.groups[0].success.successes, 0);
  EXPECT_EQ(r.groups[1].success.trials, 1);
  EXPECT_EQ(sweep_report_json(r)["groups"][1]["success"]["rate"], 1.0);
}

TEST(SweepReport, TheFiguresAreDrawnPerAxisWithAHeatMapAndTheMetrics) {
  const SweepFolder folder = prepared("figures");
  run(folder, 2);
  merge_sweep(folder);
  const std::vector<plot::PlotInfo> figures = plot_sweep(folder, folder.dir / "figures");
  std::vector<std::string> names;
  for (const plot::PlotInfo& f : figures) {
    names.push_back(f.name);
    EXPECT_TRUE(fs::exists(f.path)) << f.path;
  }
  EXPECT_EQ(names,
            (std::vector<std::string>{"success_vs_controller", "success_vs_criteria_tolerance",
                                      "success_heat_map", "metric_distributions"}));
  SweepPlotOptions options;
  options.heat_map = {"controller", "criteria.tolerence"};
  EXPECT_THAT(error_of([&] { plot_sweep(folder, folder.dir / "figures", options); }),
              HasSubstr("unknown axis 'criteria.tolerence'; closest: criteria.tolerance"));
}

/// The data a dashboard page draws from (the JSON of its data element).
nlohmann::json dashboard_data(const std::string& page) {
  const std::string open = R"(<script type="application/json" id="data">)";
  const std::size_t start = page.find(open) + open.size();
  return nlohmann::json::parse(page.substr(start, page.find("</script>", start) - start));
}

TEST(SweepDashboard, HoldsEveryTrialAndTheReportAndFetchesNothing) {
  const SweepFolder folder = prepared("dashboard");
  run(folder, 2);
  merge_sweep(folder);
  const fs::path html = folder.dir / "dashboard.html";
  const SweepDashboard d = write_sweep_dashboard(folder, html);
  EXPECT_EQ(d.trials, 12);
  EXPECT_EQ(d.recorded, 0);
  const std::string page = slurp(html);
  EXPECT_EQ(d.bytes, page.size());
  const nlohmann::json data = dashboard_data(page);
  EXPECT_EQ(data["rows"].size(), 12u);
  EXPECT_EQ(data["parameters"], (nlohmann::json{"controller", "criteria.tolerance"}));
  EXPECT_EQ(data["report"]["success"]["trials"], 12);
  EXPECT_EQ(data["report"], nlohmann::json::parse(sweep_report_json(sweep_report(folder)).dump()));
  // one file: nothing loaded from elsewhere
  EXPECT_EQ(page.find("<script src"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_EQ(page.find("@DATA@"), std::string::npos);
  EXPECT_THAT(error_of([&] { write_sweep_dashboard(SweepFolder{scratch() / "none"}, html); }),
              HasSubstr("none"));
  EXPECT_EQ(slurp(html), page);  // a failed write leaves the last whole file
}

TEST(SweepDashboard, ARecordedTrialLinksItsReplayRecordingAndVideoFromWhereThePageIs) {
  const std::string text = R"(
scenario: shelf-pick
parameters: {robot: planar2, controller: ct, settle-time: 0.05, criteria.hold-time: 0.04,
             criteria.steady-window: 0.02}
axes:
  criteria.tolerance: [1.0e-9, 0.01]
record: failures
)";
  const SweepFolder folder = prepared("dashboard_recorded", text, 2);
  run(folder, 1);
  merge_sweep(folder);
  std::ofstream(folder.dir / "records/trial-00000000/replay.html") << "<p>replay</p>";
  fs::create_directories(scratch() / "pages");
  const fs::path html = scratch() / "pages" / "sweep.html";
  const SweepDashboard d = write_sweep_dashboard(folder, html);
  EXPECT_EQ(d.recorded, 1);
  const nlohmann::json links = dashboard_data(slurp(html))["links"];
  ASSERT_EQ(links.size(), 1u);
  EXPECT_EQ(links["0"]["recording"], "../dashboard_recorded/records/trial-00000000/recording");
  EXPECT_EQ(links["0"]["replay"], "../dashboard_recorded/records/trial-00000000/replay.html");
  EXPECT_EQ(links["0"]["video"], "../dashboard_recorded/records/trial-00000000/video.mp4");
  EXPECT_TRUE(fs::exists(html.parent_path() / links["0"]["video"].get<std::string>()));
}

TEST(SweepReport, WilsonIntervalsAreTheTextbooks) {
  const SuccessRate r = wilson_interval(8, 10);
  EXPECT_NEAR(r.low, 0.4901624714648082, 1e-12);
  EXPECT_NEAR(r.high, 0.9433178485609942, 1e-12);
  EXPECT_EQ(wilson_interval(0, 20).low, 0.0);
  EXPECT_NEAR(wilson_interval(0, 20).high, 0.16112515811625733, 1e-12);
  EXPECT_NEAR(wilson_interval(20, 20).low, 0.8388748418837426, 1e-12);
  EXPECT_EQ(wilson_interval(0, 0).high, 1.0);
}

}  // namespace
}  // namespace mjarm
