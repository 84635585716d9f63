#include "mjarm/plot/plots.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "plot/plot_test_support.hpp"
#include "support/file_size_limit.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

struct PressRun {
  test::TempDir dir{"plot-figures"};
  fs::path recording = dir.path() / "rec";
  PressRun() { test::record_press(recording); }
};

const PlotInfo& find(const std::vector<PlotInfo>& plots, const std::string& name) {
  for (const PlotInfo& p : plots)
    if (p.name == name) return p;
  throw std::runtime_error("no figure " + name);
}

bool mentions(const std::vector<std::string>& notes, const std::string& text) {
  for (const std::string& n : notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

// PATH without gnuplot for the lifetime of the guard
struct PathWithoutGnuplot {
  std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
  PathWithoutGnuplot() { ::setenv("PATH", "/nonexistent-bin", 1); }
  ~PathWithoutGnuplot() { ::setenv("PATH", saved.c_str(), 1); }
};

TEST(Plots, FourFiguresOfTheAskedSizeThatAreNotBlank) {
  PressRun run;
  const std::vector<fs::path> paths = write_plots(run.recording, {}, {});
  ASSERT_EQ(paths.size(), 4u);
  for (const char* name : {"tracking_error", "joint_torques", "contact_force", "phases"}) {
    const fs::path png =
        run.recording / "plots" / (std::string(name) + ".png");  // the default folder
    EXPECT_TRUE(std::find(paths.begin(), paths.end(), fs::absolute(png)) != paths.end()) << name;
    const test::PixelStats s = test::pixel_stats(png);
    EXPECT_EQ(s.width, 1280) << name;
    EXPECT_EQ(s.height, 720) << name;
    // a white page with a frame and text has a little ink; curves, bands and labels much more
    EXPECT_GT(s.variance, 300.0) << name;
    EXPECT_GT(s.ink_fraction, 0.01) << name;
  }
  EXPECT_TRUE(fs::exists(run.recording / "plots" / "gnuplot" / "plots.gp"));
}

TEST(Plots, WhatWasDrawnIsReported) {
  PressRun run;
  PlotOptions options;
  options.width = 800;
  options.height = 450;
  const std::vector<PlotInfo> plots =
      make_plots(Recording::load(run.recording), run.dir.path() / "figs", options);
  ASSERT_EQ(plots.size(), 4u);
  EXPECT_EQ(test::pixel_stats(find(plots, "phases").path).width, 800);
  EXPECT_EQ(test::pixel_stats(find(plots, "contact_force").path).height, 450);
  // the motor pushes at its 50 N limit: normalized torque −1, saturated ticks marked
  const PlotInfo& torques = find(plots, "joint_torques");
  EXPECT_TRUE(mentions(torques.series, "slide (peak 100 %)"));
  EXPECT_TRUE(mentions(torques.series, "saturated tick"));
  EXPECT_FALSE(mentions(torques.notes, "no saturated ticks"));
  const PlotInfo& contact = find(plots, "contact_force");
  EXPECT_TRUE(mentions(contact.notes, "peak normal force")) << contact.notes.front();
  const PlotInfo& phases = find(plots, "phases");
  EXPECT_EQ(phases.series, (std::vector<std::string>{"descend", "press", "other events"}));
  const PlotInfo& error = find(plots, "tracking_error");
  EXPECT_TRUE(mentions(error.notes, "peak position error"));
  EXPECT_NE(error.title.find("tip"), std::string::npos);
}

TEST(Plots, AnUnwritableOutputFolderIsNamed) {
  PressRun run;
  test::write_file(run.dir.path() / "a-file", "x");
  try {
    write_plots(run.recording, run.dir.path() / "a-file" / "plots", {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create the plot folder"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("a-file/plots"), std::string::npos) << e.what();
  }
}

TEST(Plots, MissingGnuplotNamesTheDebianPackage) {
  PressRun run;
  PathWithoutGnuplot guard;
  EXPECT_THROW(find_gnuplot(), Error);
  try {
    write_plots(run.recording, run.dir.path() / "out", {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot-nox"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(run.dir.path() / "out"));  // refused before writing anything
}

TEST(Plots, AFullDiskLeavesNoCutFigure) {
  PressRun run;
  const Recording recording = Recording::load(run.recording);
  // with room: the sizes of the data files and of the figures
  const fs::path roomy = run.dir.path() / "roomy";
  const std::vector<PlotInfo> drawn = make_plots(recording, roomy);
  std::uintmax_t largest_data = 0, smallest_png = UINTMAX_MAX;
  for (const auto& entry : fs::directory_iterator(roomy / "gnuplot"))
    largest_data = std::max(largest_data, entry.file_size());
  for (const PlotInfo& info : drawn)
    smallest_png = std::min(smallest_png, fs::file_size(info.path));
  // a disk with room for the data and the script but not for a whole figure
  const std::size_t limit = static_cast<std::size_t>(largest_data) + 512;
  ASSERT_LT(limit, smallest_png);
  const fs::path full = run.dir.path() / "full";
  const test::LimitedRun child = test::with_file_size_limit(limit, [&] {
    make_plots(recording, full);
    return std::string("drawn");
  });
  ASSERT_EQ(child.exit_code, 1) << child.out;
  EXPECT_NE(child.err.find("gnuplot did not write"), std::string::npos) << child.err;
  EXPECT_NE(child.err.find("no PNG end chunk"), std::string::npos) << child.err;
  // a whole set of figures or none; and (issue 29) none of their data files and script either:
  // the folder the drawing made is gone
  for (const PlotInfo& info : drawn) EXPECT_FALSE(fs::exists(full / info.path.filename()));
  EXPECT_FALSE(fs::exists(full / "gnuplot" / "plots.gp"));
  EXPECT_FALSE(fs::exists(full));
}

// issue 29: gnuplot's data files and script stayed after a failure. Every failure path leaves
// nothing of the drawing: a disk full while the data is written, an interrupt (SIGINT/SIGTERM)
// before or while gnuplot draws; a folder that existed stays, emptied of what was written.
TEST(Plots, EveryFailureLeavesNothingOfTheDrawing) {
  PressRun run;
  const Recording recording = Recording::load(run.recording);
  const fs::path cut = run.dir.path() / "cut_data";
  const test::LimitedRun child = test::with_file_size_limit(256, [&] {
    make_plots(recording, cut);
    return std::string("drawn");
  });
  ASSERT_EQ(child.exit_code, 1) << child.out;
  EXPECT_NE(child.err.find("cannot write"), std::string::npos) << child.err;
  EXPECT_NE(child.err.find(".dat"), std::string::npos) << child.err;
  EXPECT_FALSE(fs::exists(cut));

  const fs::path existing = run.dir.path() / "existing";
  fs::create_directories(existing);
  test::write_file(existing / "notes.txt", "mine\n");
  const InterruptGuard interrupts;
  std::raise(SIGINT);  // pending: gnuplot is not started
  try {
    make_plots(recording, existing);
    FAIL() << "drawn despite the interrupt";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("interrupted"), std::string::npos) << e.what();
  }
  std::vector<std::string> left;
  for (const auto& entry : fs::recursive_directory_iterator(existing))
    left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"notes.txt"});
}

TEST(Plots, BadSizesAreRefused) {
  PressRun run;
  PlotOptions options;
  options.width = 10;
  EXPECT_THROW(write_plots(run.recording, {}, options), Error);
}

// Every text that reaches the gnuplot script, hostile: the recording's folder, the output
// folder, the model, frame and controller names in summary.json (titles), the actuators' joint
// names (curve titles), and events' kinds and phase names (labels). Each would run
// `touch PWNED…` if it were written raw.

// the press recording in @p dir, its names replaced by the injection text
void record_hostile_press(const fs::path& dir) {
  test::record_press(dir);
  nlohmann::json summary = nlohmann::json::parse(test::read_text(dir / "summary.json"));
  summary["model"] = test::injection_text();
  summary["frame"] = test::injection_text();
  summary["controllers"] = nlohmann::json::array({{{"name", test::injection_text()}}});
  for (auto& actuator : summary["actuators"]) actuator["joint"] = test::injection_text();
  test::write_file(dir / "summary.json", summary.dump());
  std::string csv_text = test::injection_text();  // a CSV cell: doubled quotes, in quotes
  for (std::size_t at = 0; (at = csv_text.find('"', at)) != std::string::npos; at += 2)
    csv_text.insert(at, 1, '"');
  std::string events = test::read_text(dir / "events.csv");
  events += "0.1,phase,\"" + csv_text + "\"\n0.2,\"" + csv_text + "\",message\n";
  test::write_file(dir / "events.csv", events);
}


TEST(Plots, NoTextReachesGnuplotAsACommand) {
  test::TempDir dir("plot-injection");
  // the folder names themselves hold the payload (a name may hold anything but '/')
  const fs::path recording = dir.path() / ("rec" + test::injection_text());
  record_hostile_press(recording);
  const fs::path out = dir.path() / ("out" + test::injection_text());
  // gnuplot's working folder is this process's: the scratch folder, where `touch` would write
  const fs::path saved = fs::current_path();
  fs::current_path(dir.path());
  std::vector<fs::path> default_paths, out_paths;
  std::string error;
  try {
    default_paths = write_plots(recording, {}, {});
    out_paths = write_plots(recording, out, {});
  } catch (const std::exception& e) {
    error = e.what();
  }
  fs::current_path(saved);
  ASSERT_EQ(error, "");
  EXPECT_EQ(test::pwned_files(dir.path()), std::vector<fs::path>{});
  // the figures came out where they were asked for, under the exact (hostile) names
  ASSERT_EQ(default_paths.size(), 4u);
  ASSERT_EQ(out_paths.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(default_paths[k].parent_path(), recording / "plots");
    EXPECT_EQ(out_paths[k].parent_path(), out);
    EXPECT_GT(test::pixel_stats(default_paths[k]).variance, 300.0) << default_paths[k];
    EXPECT_GT(test::pixel_stats(out_paths[k]).variance, 300.0) << out_paths[k];
  }
  // no line of the script starts with a command taken from the names
  const std::string script = test::read_text(out / "gnuplot" / "plots.gp");
  EXPECT_EQ(script.find("\nsystem"), std::string::npos);
}

}  // namespace
}  // namespace mjarm::plot
