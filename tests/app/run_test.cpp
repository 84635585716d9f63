// Drives `mjarm run shelf-pick` and the demo's shelf pick through the built executable: figures
// in --json, recordings and videos on disk, exit codes and messages for every bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"
#include "mjarm/web/replay_html.hpp"
#include "render/render_test_support.hpp"
#include "support/file_size_limit.hpp"
#include "support/running_process.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using mjarm::test::run_json;
using mjarm::test::scratch;
using mjarm::test::slurp;
using nlohmann::json;

/// A finalized recording: the four files, no staging folder left, the summary's status.
void expect_recording(const fs::path& dir, const std::string& status) {
  for (const char* file : {"state.csv", "task.csv", "events.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(dir / file)) << dir / file;
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_NE(entry.path().filename().string().rfind(".partial", 0), 0u) << entry.path();
  const std::string summary = slurp(dir / "summary.json");
  ASSERT_TRUE(json::accept(summary)) << summary;
  EXPECT_EQ(json::parse(summary)["status"], status);
}

TEST(RunCli, HelpNamesTheScenarioAndOptions) {
  const CliRun scenarios = run_cli({"run", "--help"});
  EXPECT_EQ(scenarios.exit_code, 0);
  for (const char* word : {"shelf-pick", "pick-place", "docking", "plan", "--list"})
    EXPECT_NE(scenarios.out.find(word), std::string::npos) << word;
  const CliRun run = run_cli({"run", "shelf-pick", "--help"});
  EXPECT_EQ(run.exit_code, 0);
  for (const char* word : {"shelf-pick", "--robot", "--controller", "--pick", "--seed", "--record",
                           "--json", "--all", "--video", "--camera", "--size", "--fps",
                           "--criteria.tolerance", "[m]; positive and finite (default 0.001)"})
    EXPECT_NE(run.out.find(word), std::string::npos) << word;
  EXPECT_EQ(run.out.find("--grasp"), std::string::npos);  // another scenario's
}

TEST(RunCli, ListShowsTheScenariosOfTheRegistry) {
  const CliRun text = run_cli({"run", "--list"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  for (const char* name :
       {"shelf-pick", "pick-place", "docking", "plan", "bimanual-lift", "wiping"})
    EXPECT_NE(text.out.find(name), std::string::npos) << name;
  const json doc = run_json({"run", "--list", "--json"});
  ASSERT_EQ(doc["scenarios"].size(), 6u);
  const json& pick_place = doc["scenarios"][1];
  EXPECT_EQ(pick_place["name"], "pick-place");
  bool found = false;
  for (const json& p : pick_place["parameters"]) {
    if (p["name"] != "object-size") continue;
    found = true;
    EXPECT_EQ(p["unit"], "m");
    EXPECT_EQ(p["range"], "in [0.005, 0.05]");
    EXPECT_TRUE(p["default"].is_null());
    EXPECT_EQ(p["optional"], true);
  }
  EXPECT_TRUE(found);
  expect_error({"run", "--list", "docking"}, 2, "give no SCENARIO with it");
  expect_error({"run"}, 2,
               "run needs a SCENARIO (shelf-pick | pick-place | docking | plan | bimanual-lift | "
               "wiping)");
}

TEST(RunCli, AScenarioWithoutItsOwnSubcommandRunsFromItsParameters) {
  const CliRun help = run_cli({"run", "wiping", "--help"});
  ASSERT_EQ(help.exit_code, 0) << help.err;
  for (const char* word : {"--motion.force", "normal force to wipe with [N]; in [0.5, 60]",
                           "--control.law", "osc | cic", "--record", "--video", "--json"})
    EXPECT_NE(help.out.find(word), std::string::npos) << word;
  const json doc = run_json(
      {"run", "wiping", "--path.length", "0.1", "--motion.force", "8", "--seed", "4", "--json"});
  EXPECT_EQ(doc["scenario"], "wiping");
  EXPECT_EQ(doc["verdict"], "wiped");
  EXPECT_EQ(doc["parameters"]["motion.force"], 8.0);
  EXPECT_LT(doc["metrics"]["force_rms_error"].get<double>(), 1.0);
  const CliRun text = run_cli({"run", "wiping", "--path.length", "0.05"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("wiping: wiped"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("path_max_error"), std::string::npos) << text.out;
  expect_error({"run", "wiping", "--motion.force", "-1"}, 2,
               "wiping: motion.force must be in [0.5, 60] [N], got -1");
  expect_error({"run", "wiping", "--motion.forse", "3"}, 2,
               "run wiping: unknown option '--motion.forse'; closest: --motion.force");
}

TEST(RunCli, EveryParameterOfTheRegistryIsAnOption) {
  const json doc =
      run_json({"run", "shelf-pick", "--robot", "planar2", "--controller", "ct",
                "--criteria.tolerance", "0.002", "--criteria.hold-time", "0.1", "--json"});
  EXPECT_EQ(doc["tolerance"], 0.002);
  EXPECT_EQ(doc["hold_time"], 0.1);
  EXPECT_EQ(doc["outcome"], "held");
  expect_error({"run", "shelf-pick", "--criteria.tolerance", "-1"}, 2,
               "shelf-pick: criteria.tolerance must be positive and finite [m], got -1");
  expect_error({"run", "shelf-pick", "--criteria.tolerance", "wide"}, 2,
               "--criteria.tolerance: criteria.tolerance must be a number, got 'wide'");
}

TEST(RunCli, JsonHoldsEveryFigure) {
  const std::vector<std::string> args{"run", "shelf-pick", "--robot", "planar2", "--controller",
                                      "ct",  "--seed",     "5",       "--json"};
  const CliRun first = run_cli(args);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_TRUE(json::accept(first.out)) << first.out;
  const json doc = json::parse(first.out);
  EXPECT_EQ(doc["scenario"], "shelf-pick");
  EXPECT_EQ(doc["robot"], "planar2");
  EXPECT_EQ(doc["model"], "planar2_torque");
  EXPECT_EQ(doc["controller"], "ct");
  EXPECT_EQ(doc["seed"], 5);
  EXPECT_EQ(doc["outcome"], "held");
  EXPECT_EQ(doc["held"], true);
  EXPECT_EQ(doc["status"], "finished");
  EXPECT_EQ(doc["pick_drawn"], true);
  ASSERT_EQ(doc["pick"].size(), 3u);
  EXPECT_EQ(doc["pick"][1], 0.0);  // in planar2's plane
  EXPECT_EQ(doc["tolerance"], 0.001);
  EXPECT_EQ(doc["hold_time"], 0.2);
  EXPECT_EQ(doc["control_period"], 0.002);
  EXPECT_TRUE(doc["recording"].is_null());
  const json& m = doc["metrics"];
  for (const char* key :
       {"time_to_tolerance", "first_entry_time", "overshoot", "steady_state_mean",
        "steady_state_max", "hold_mean", "hold_max", "hold_end_time", "exits", "final_error"})
    EXPECT_TRUE(m.contains(key)) << key;
  EXPECT_LE(m["time_to_tolerance"].get<double>(), 0.4);
  EXPECT_LE(m["steady_state_mean"].get<double>(), 1e-4);
  EXPECT_LE(m["steady_state_max"].get<double>(), 1e-4);
  EXPECT_NEAR(m["hold_end_time"].get<double>() - m["time_to_tolerance"].get<double>(), 0.2, 1e-9);
  EXPECT_TRUE(m["orientation_error_max"].is_number());

  // the same seed gives the same document; a given pick point is used as is
  EXPECT_EQ(run_cli(args).out, first.out);
  const json given = run_json({"run", "shelf-pick", "--robot", "panda", "--controller", "accel",
                               "--pick", "0.45", "0.05", "0.4", "--json"});
  EXPECT_EQ(given["pick_drawn"], false);
  EXPECT_EQ(given["pick"], json::array({0.45, 0.05, 0.4}));
  EXPECT_EQ(given["outcome"], "held");
}

TEST(RunCli, TextReportsTheFigures) {
  const CliRun run = run_cli({"run", "shelf-pick", "--robot", "panda", "--controller", "task-pd"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  for (const char* text :
       {"shelf pick on panda", "task-space PD", "result: held", "time to 1 mm [s]",
        "overshoot [mm]", "steady state [mm]", "orientation [mrad]", "hold  "})
    EXPECT_NE(run.out.find(text), std::string::npos) << text << " not in:\n" << run.out;
}

TEST(RunCli, RecordWritesAFinalizedRecording) {
  const fs::path dir = scratch() / "rec";
  const json doc =
      run_json({"run", "shelf-pick", "--robot", "panda", "--record", dir.string(), "--json"});
  EXPECT_EQ(doc["recording"], dir.string());
  expect_recording(dir, "finished");
  const std::string events = slurp(dir / "events.csv");
  for (const char* phase : {",phase,approach", ",phase,hold", ",phase,release", ",result,held"})
    EXPECT_NE(events.find(phase), std::string::npos) << phase << " not in:\n" << events;
  // task rows: a header and one row per control tick up to the release
  const std::string task = slurp(dir / "task.csv");
  const auto rows = std::count(task.begin(), task.end(), '\n') - 1;
  EXPECT_NEAR(static_cast<double>(rows), doc["end_time"].get<double>() / 0.002, 1.5);
}

TEST(RunCli, AFullDiskStillPrintsTheReportAndNamesTheKeptRows) {
  const fs::path cwd = scratch() / "full_disk";
  fs::create_directories(cwd);
  // room for the CSV headers, not for the rows nor for the summary
  const mjarm::test::LimitedRun text = mjarm::test::run_with_file_size_limit(
      1024, MJARM_CLI, {"run", "shelf-pick", "--record", "rec"}, cwd);
  EXPECT_EQ(text.exit_code, 1);
  EXPECT_NE(text.out.find("result: held"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("not written"), std::string::npos) << text.out;
  EXPECT_NE(text.err.find("rec/.partial-"), std::string::npos) << text.err;
  EXPECT_NE(text.err.find("state.csv': File too large"), std::string::npos) << text.err;
  EXPECT_NE(text.err.find("nothing was moved into 'rec'"), std::string::npos) << text.err;
  EXPECT_FALSE(fs::exists(cwd / "rec" / "summary.json"));

  const mjarm::test::LimitedRun js = mjarm::test::run_with_file_size_limit(
      1024, MJARM_CLI, {"run", "shelf-pick", "--record", "rec_json", "--json"}, cwd);
  EXPECT_EQ(js.exit_code, 1);
  ASSERT_TRUE(json::accept(js.out)) << js.out;
  const json doc = json::parse(js.out);
  EXPECT_EQ(doc["outcome"], "held");
  ASSERT_TRUE(doc["recording_error"].is_string()) << js.out;
  EXPECT_NE(doc["recording_error"].get<std::string>().find("File too large"), std::string::npos);
}

// issue 16, item 8 ("check every write; on failure report it"): when the recording and the
// video both fail on a full disk, the error names both, and no cut MP4 is left behind
TEST(RunCli, AFullDiskNamesAFailedVideoBesideAFailedRecording) {
  const fs::path cwd = scratch() / "full_disk_video";
  fs::create_directories(cwd);
  const mjarm::test::LimitedRun run = mjarm::test::run_with_file_size_limit(
      1024, MJARM_CLI,
      {"run", "shelf-pick", "--record", "rec", "--video", "run.mp4", "--size", "64x48"}, cwd);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("result: held"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("state.csv': File too large"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("video 'run.mp4' is not a complete MP4"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("no video was written"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("run.mp4 (not written: see the error;"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(cwd / "run.mp4"));
}

// A folder holding a script called ffmpeg that reads every frame, then fails.
fs::path failing_ffmpeg_dir() {
  const fs::path dir = scratch() / "failing_ffmpeg";
  fs::create_directories(dir);
  std::ofstream(dir / "ffmpeg") << "#!/bin/sh\ncat > /dev/null\necho 'encoder broke' >&2\nexit 1\n";
  fs::permissions(dir / "ffmpeg", fs::perms::owner_all);
  return dir;
}

// issue 16, item 6 ("video ... reports success"), in the demo: a video that failed was only
// "stopped early" in the table and the demo exited 0 with an empty out/demo.mp4
TEST(RunCli, DemoFailsWhenItsVideoFails) {
  const fs::path cwd = scratch() / "demo_failing_video";
  fs::create_directories(cwd);
  const std::string saved = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  ::setenv("PATH", (failing_ffmpeg_dir().string() + ":" + saved).c_str(), 1);
  // without the replay page (the demo's other output, not this test's subject)
  const CliRun run = run_cli({"demo", "--samples", "1000", "--html", ""}, cwd);
  const CliRun json_run = run_cli({"demo", "--samples", "1000", "--html", "", "--json"}, cwd);
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_NE(run.out.find("result: held"), std::string::npos) << run.out;  // the report stands
  EXPECT_NE(run.err.find("out/demo.mp4"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("encoder broke"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(cwd / "out" / "demo.mp4"));
  EXPECT_EQ(json_run.exit_code, 1) << json_run.err;
  ASSERT_TRUE(json::accept(json_run.out)) << json_run.out;
  const json video = json::parse(json_run.out)["shelf_pick"]["video"];
  EXPECT_TRUE(video["error"].is_string()) << json_run.out;
  EXPECT_EQ(video["written"], false) << json_run.out;
}

TEST(RunCli, BadInputFailsClearly) {
  expect_error({"run", "shelf-pick", "--robot", "ur5"}, 2, "choices: planar2, panda");
  expect_error({"run", "shelf-pick", "--controller", "pid"}, 2, "choices: ct, osc, task-pd, accel");
  expect_error({"run", "shelf-place"}, 2, "unknown scenario 'shelf-place'; closest: shelf-pick");
  expect_error({"run", "shelf-pick", "--robot", "planar2", "--pick", "0.92", "0", "1"}, 1,
               "planar2 reaches 0.2");
  expect_error({"run", "shelf-pick", "--robot", "planar2", "--pick", "0.92", "0", "1"}, 1,
               "0.920 m from the shoulder");
  expect_error({"run", "shelf-pick", "--robot", "planar2", "--pick", "0.5", "0.2", "0.8"}, 1,
               "off the arm's plane");
  expect_error({"run", "shelf-pick", "--pick", "2", "0", "0.5"}, 1, "out of reach of panda");
  expect_error({"run", "shelf-pick", "--pick", "nan", "0", "0.5"}, 2, "--pick");
  expect_error({"run", "shelf-pick", "--control-period", "0.003"}, 1, "not a whole multiple");
  expect_error({"run", "shelf-pick", "--all", "--record", "x"}, 2, "excludes");
  expect_error({"run", "shelf-pick", "--seeds", "3"}, 2, "--seeds needs --all");

  // a recording directory that cannot be written: an error before anything runs
  const fs::path file = scratch() / "plain_file";
  std::ofstream(file) << "x";
  expect_error({"run", "shelf-pick", "--record", (file / "rec").string()}, 2,
               "--record: '" + file.string() + "' is not a folder");
  EXPECT_EQ(slurp(file), "x");
}

TEST(RunCli, ADivergingRunReportsHonestlyAndKeepsTheRecording) {
  const fs::path dir = scratch() / "diverged";
  const CliRun run =
      run_cli({"run", "shelf-pick", "--max-acceleration", "2", "--record", dir.string(), "--json"});
  EXPECT_FALSE(run.signaled);
  EXPECT_EQ(run.exit_code, 1);
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["outcome"], "diverged");
  EXPECT_EQ(doc["status"], "diverged");
  EXPECT_EQ(doc["held"], false);
  EXPECT_TRUE(doc["metrics"]["time_to_tolerance"].is_null());
  EXPECT_NE(run.err.find("diverged"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(dir.string()), std::string::npos) << run.err;
  expect_recording(dir, "diverged");
}

TEST(RunCli, AllSweepsEveryRobotAndController) {
  const json doc = run_json({"run", "shelf-pick", "--all", "--json"});
  ASSERT_EQ(doc["rows"].size(), 8u);
  for (const json& row : doc["rows"]) {
    EXPECT_EQ(row["held"], 1) << row;
    EXPECT_LE(row["worst_time_to_tolerance"].get<double>(), 0.4) << row;
    EXPECT_LE(row["worst_steady_state_max"].get<double>(), 1e-4) << row;
  }
  EXPECT_EQ(doc["rows"][0]["robot"], "planar2");
  EXPECT_EQ(doc["rows"][7]["controller"], "accel");
}

// issue 16, item 5: Ctrl-C (or SIGTERM) stops a long sweep at the next tick; the rows done so far
// are reported, the run is marked interrupted, and the exit status is 128 + the signal
TEST(RunCli, AllStopsAtCtrlCWithTheRowsDone) {
  for (const int signal : {SIGINT, SIGTERM}) {
    mjarm::test::RunningProcess run(
        {MJARM_CLI, "run", "shelf-pick", "--all", "--seeds", "10000", "--json"}, scratch());
    ASSERT_TRUE(run.started());
    // signalled once its handler is installed, not after a guessed delay
    ASSERT_TRUE(mjarm::test::eventually(
        [&] { return mjarm::test::catches_signal(run.pid(), signal) || run.wait(0); }, 60.0));
    run.signal(signal);
    ASSERT_TRUE(run.wait(60.0)) << "the sweep went on after the signal";
    EXPECT_FALSE(run.signaled());
    EXPECT_EQ(run.exit_code(), 128 + signal) << run.err();
    EXPECT_NE(run.err().find("interrupted after "), std::string::npos) << run.err();
    EXPECT_NE(run.err().find(" of 80000 shelf picks"), std::string::npos) << run.err();
    ASSERT_TRUE(json::accept(run.out())) << run.out();
    const json doc = json::parse(run.out());
    EXPECT_EQ(doc["interrupted"], true);
    int runs = 0;
    for (const json& row : doc["rows"]) {
      EXPECT_GT(row["runs"].get<int>(), 0) << row;
      EXPECT_EQ(row["held"], row["runs"]) << row;  // no interrupted run counted as a failure
      runs += row["runs"].get<int>();
    }
    EXPECT_EQ(doc["runs"], runs);
    EXPECT_LT(runs, 80000);
  }
}

TEST(RunCli, AllExitsOneWhenPicksFailWhateverTheFormat) {
  // every pick diverges at this acceleration bound: the JSON form fails like the text form
  const std::vector<std::string> args{"run", "shelf-pick", "--all", "--max-acceleration", "2"};
  const CliRun text = run_cli(args);
  std::vector<std::string> with_json = args;
  with_json.push_back("--json");
  const CliRun doc = run_cli(with_json);
  EXPECT_EQ(text.exit_code, 1) << text.err;
  EXPECT_EQ(doc.exit_code, 1) << doc.err;
  EXPECT_NE(doc.err.find("some shelf picks did not hold"), std::string::npos) << doc.err;
  ASSERT_TRUE(json::accept(doc.out)) << doc.out;  // the figures are still printed
  const json parsed = json::parse(doc.out);
  for (const json& row : parsed["rows"]) EXPECT_EQ(row["held"], 0) << row;
}

TEST(RunCli, DemoRunsTheShelfPickAndRecordsIntoOutDemo) {
  const fs::path cwd = scratch() / "demo_cwd";
  fs::create_directories(cwd);
  const CliRun run = run_cli({"demo", "--samples", "1000"}, cwd);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("== shelf pick =="), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("operational-space"), std::string::npos);
  EXPECT_NE(run.out.find("result: held"), std::string::npos);
  EXPECT_NE(run.out.find("out/demo (state.csv"), std::string::npos) << run.out;
  expect_recording(cwd / "out" / "demo", "finished");
  // the main job also films the pick and plots its recording, and says where they went
  EXPECT_NE(run.out.find("out/demo.mp4 ("), std::string::npos) << run.out;
  EXPECT_GT(fs::file_size(cwd / "out" / "demo.mp4"), 0u);
  // and writes its replay page next to the video, where this build holds the page (make test's
  // does: node and npm), or says why not
  if (mjarm::replay_html_available()) {
    EXPECT_NE(run.out.find("replay page"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("out/demo.html ("), std::string::npos) << run.out;
    EXPECT_NE(mjarm::test::slurp(cwd / "out" / "demo.html").find("id=\"mjarm-replay-data\""),
              std::string::npos);
  } else {
    EXPECT_NE(run.out.find("not written: this mjarm was built without the replay page"),
              std::string::npos)
        << run.out;
  }
  for (const char* plot :
       {"tracking_error.png", "joint_torques.png", "contact_force.png", "phases.png"}) {
    const fs::path path = cwd / "out" / "demo" / "plots" / plot;
    EXPECT_TRUE(fs::exists(path)) << path;
    EXPECT_NE(run.out.find(plot), std::string::npos) << plot;
  }

  const CliRun json_run =
      run_cli({"demo", "--samples", "1000", "--json", "--record", "elsewhere"}, cwd);
  ASSERT_TRUE(json::accept(json_run.out)) << json_run.out;
  const json doc = json::parse(json_run.out);
  EXPECT_EQ(doc["shelf_pick"]["robot"], "panda");
  EXPECT_EQ(doc["shelf_pick"]["controller"], "osc");
  EXPECT_EQ(doc["shelf_pick"]["outcome"], "held");
  EXPECT_EQ(doc["shelf_pick"]["recording"], "elsewhere");
  expect_recording(cwd / "elsewhere", "finished");
  EXPECT_EQ(doc["shelf_pick"]["video"]["path"], "out/demo.mp4");
  EXPECT_EQ(doc["plots"].size(), 4u);
  if (mjarm::replay_html_available()) {
    EXPECT_EQ(doc["replay"]["path"], "out/demo.html");
    EXPECT_EQ(doc["replay"]["recording"], "elsewhere");
    EXPECT_EQ(doc["replay"]["bytes"].get<std::uintmax_t>(),
              fs::file_size(cwd / "out" / "demo.html"));
  } else {
    EXPECT_TRUE(doc["replay"].is_null());
  }
  // --html FILE puts it elsewhere (its folder made), the video off
  const CliRun elsewhere = run_cli(
      {"demo", "--samples", "1000", "--json", "--video", "", "--html", "page/demo.html"}, cwd);
  if (mjarm::replay_html_available()) {
    EXPECT_EQ(elsewhere.exit_code, 0) << elsewhere.err;
    EXPECT_TRUE(fs::exists(cwd / "page" / "demo.html"));
  } else {  // asked for by name: refused before the shelf pick
    EXPECT_EQ(elsewhere.exit_code, 1) << elsewhere.err;
    EXPECT_NE(elsewhere.err.find("--html: this mjarm was built without the replay page"),
              std::string::npos)
        << elsewhere.err;
  }
}

// ---- --video ----

/// Frames in @p video counted by decoding them all (ffprobe, Debian package ffmpeg); -1 when the
/// file is not a valid video. Also its size.
struct Probe {
  int frames = -1;
  std::string size;
};

Probe probe(const fs::path& video) {
  std::string ffprobe;
  for (const char* dir : {"/usr/bin", "/usr/local/bin"})
    if (::access((std::string(dir) + "/ffprobe").c_str(), X_OK) == 0)
      ffprobe = dir + std::string("/ffprobe");
  EXPECT_FALSE(ffprobe.empty()) << "ffprobe (Debian package ffmpeg) is needed by this test";
  const auto run = mjarm::test::run_process(
      {ffprobe, "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
       "stream=nb_read_frames,width,height", "-of", "csv=p=0:s=x", video.string()});
  Probe p;
  if (run.exit_code != 0) return p;
  // "WIDTHxHEIGHTxFRAMES"
  const auto last = run.out.rfind('x');
  p.frames = std::atoi(run.out.substr(last + 1).c_str());
  p.size = run.out.substr(0, last);
  return p;
}

/// Frames of a video at @p fps of a run that ended at @p end_time [s] (frame k at k / fps).
int expected_frames(double end_time, double fps) {
  return static_cast<int>(std::floor(end_time * fps + 1e-9)) + 1;
}

TEST(RunVideo, HoldsDurationTimesFpsFramesAndLeavesTheFiguresAlone) {
  const std::vector<std::string> args{"run", "shelf-pick", "--robot", "planar2", "--controller",
                                      "ct",  "--seed",     "5",       "--json"};
  const json plain = run_json(args);
  const fs::path video = scratch() / "pick.mp4";
  std::vector<std::string> with_video = args;
  for (const char* a : {"--video", video.c_str(), "--size", "160x120", "--fps", "25"})
    with_video.emplace_back(a);
  json filmed = run_json(with_video);
  ASSERT_TRUE(filmed["video"].is_object()) << filmed;
  EXPECT_EQ(filmed["video"]["path"], video.string());
  EXPECT_TRUE(filmed["video"]["error"].is_null());
  EXPECT_NE(filmed["video"]["camera"].get<std::string>().find("free"), std::string::npos);
  const double end_time = filmed["end_time"].get<double>();
  const int frames = expected_frames(end_time, 25.0);
  EXPECT_NEAR(frames, end_time * 25.0, 1.0);
  EXPECT_EQ(filmed["video"]["frames"], frames);
  const Probe p = probe(video);
  EXPECT_EQ(p.frames, frames);
  EXPECT_EQ(p.size, "160x120");

  // rendering only reads the state: every figure is the same, bit for bit
  EXPECT_TRUE(plain["video"].is_null());
  filmed.erase("video");
  json without = plain;
  without.erase("video");
  EXPECT_EQ(filmed, without);
}

TEST(RunVideo, FollowCameraAndTextOutput) {
  const fs::path video = scratch() / "follow.mp4";
  const CliRun run = run_cli({"run", "shelf-pick", "--controller", "ct", "--video", video.string(),
                              "--camera", "follow", "--size", "160x120"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("video  "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(video.string()), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("follow 'attachment_site'"), std::string::npos) << run.out;
  EXPECT_GT(probe(video).frames, 1);
}

TEST(RunVideo, ADivergingRunLeavesAFinalizedVideo) {
  const fs::path video = scratch() / "diverged.mp4";
  const CliRun run = run_cli({"run", "shelf-pick", "--max-acceleration", "2", "--video",
                              video.string(), "--size", "160x120", "--json"});
  EXPECT_FALSE(run.signaled);
  EXPECT_EQ(run.exit_code, 1);
  ASSERT_TRUE(json::accept(run.out)) << run.out;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["outcome"], "diverged");
  EXPECT_NE(run.err.find("the video is in " + video.string()), std::string::npos)
      << run.err;
  const int frames = expected_frames(doc["end_time"].get<double>(), 30.0);
  EXPECT_EQ(doc["video"]["frames"], frames);
  EXPECT_EQ(probe(video).frames, frames);
}

TEST(RunVideo, BadInputFailsClearly) {
  const std::string out = (scratch() / "bad.mp4").string();
  // the camera is checked against the model before anything renders or runs
  expect_error({"run", "shelf-pick", "--video", out, "--camera", "top"}, 1,
               "video camera 'top' is not a camera of model 'panda_torque' (its cameras: none)");
  EXPECT_FALSE(fs::exists(out));
  expect_error({"run", "shelf-pick", "--video", out, "--size", "0x120"}, 2, "between 2x2");
  expect_error({"run", "shelf-pick", "--video", out, "--size", "161x120"}, 2,
               "must be even in both directions (the MP4's yuv420p), e.g. 162x120");
  expect_error({"run", "shelf-pick", "--video", out, "--size", "big"}, 2, "not a size");
  expect_error({"run", "shelf-pick", "--video", out, "--fps", "0"}, 2,
               "--fps: '0' is not a number from 1 to 240");
  expect_error({"run", "shelf-pick", "--all", "--video", out}, 2, "--video excludes --all");
  expect_error({"run", "shelf-pick", "--camera", "follow"}, 2, "--camera requires --video");
  const fs::path file = scratch() / "not_a_dir";
  std::ofstream(file) << "x";
  expect_error({"run", "shelf-pick", "--video", (file / "v.mp4").string(), "--size", "160x120"}, 2,
               "--video: '" + file.string() + "' is not a folder");

  // no ffmpeg on PATH: the message names Debian's package
  const auto run = mjarm::test::run_process(
      {MJARM_CLI, "run", "shelf-pick", "--video", out, "--size", "160x120"},
      {"PATH=/nonexistent", "HOME=" + scratch().string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("ffmpeg not found"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("package `ffmpeg`"), std::string::npos) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
}

}  // namespace
