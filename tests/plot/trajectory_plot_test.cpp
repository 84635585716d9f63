#include "mjarm/plot/trajectory_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/error.hpp"
#include "plot/plot_test_support.hpp"
#include "support/error_message.hpp"
#include "support/file_size_limit.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

// a sine on two axes with its exact derivatives, limits on velocity and acceleration
TrajectorySeries sine_series() {
  TrajectorySeries s;
  s.title = "two sines";
  s.unit = "rad";
  s.axes = {"a", "b"};
  for (int k = 0; k <= 200; ++k) s.t.push_back(0.01 * k);
  for (auto& v : s.values) v.assign(2, {});
  for (std::size_t i = 0; i < 2; ++i) {
    const double w = 2.0 + static_cast<double>(i);
    for (double t : s.t) {
      s.values[0][i].push_back(std::sin(w * t));
      s.values[1][i].push_back(w * std::cos(w * t));
      s.values[2][i].push_back(-w * w * std::sin(w * t));
      s.values[3][i].push_back(-w * w * w * std::cos(w * t));
    }
  }
  s.limits[1] = {2.5, 3.5};
  s.limits[2] = {5.0, 10.0};
  return s;
}

TEST(TrajectoryPlot, DrawsFourPanelsAgainstTheLimits) {
  test::TempDir dir("trajectory-plot");
  const PlotInfo info = plot_trajectory(sine_series(), dir.path() / "out", {800, 900, 60.0});
  EXPECT_EQ(info.path, fs::absolute(dir.path() / "out" / "trajectory.png"));
  const test::PixelStats stats = test::pixel_stats(info.path);
  EXPECT_EQ(stats.width, 800);
  EXPECT_EQ(stats.height, 900);
  EXPECT_GT(stats.ink_fraction, 0.01);
  ASSERT_EQ(info.series.size(), 4u);
  EXPECT_EQ(info.series[0], "position");
  EXPECT_EQ(info.series[1], "velocity (dashed: ±limit)");
  EXPECT_EQ(info.series[3], "jerk");
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_EQ(info.notes[0], "no jerk limit given");
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "gnuplot" / "trajectory.gp"));
}

// issue 29: a figure gnuplot could not finish left its data file and script behind. A whole
// figure with its data, or nothing: here a disk with room for the data but not the picture
TEST(TrajectoryPlot, AFailedFigureLeavesNothing) {
  test::TempDir dir("trajectory-plot-full");
  const PlotInfo drawn = plot_trajectory(sine_series(), dir.path() / "roomy", {800, 900, 60.0});
  const std::uintmax_t data = fs::file_size(dir.path() / "roomy" / "gnuplot" / "trajectory.dat");
  ASSERT_LT(data + 4096, fs::file_size(drawn.path));
  const fs::path full = dir.path() / "full";
  const test::LimitedRun child = test::with_file_size_limit(data + 4096, [&] {
    plot_trajectory(sine_series(), full, {800, 900, 60.0});
    return std::string("drawn");
  });
  ASSERT_EQ(child.exit_code, 1) << child.out;
  EXPECT_NE(child.err.find("did not write"), std::string::npos) << child.err;
  EXPECT_FALSE(fs::exists(full));  // nor its gnuplot/ folder with the data and the script
}

TEST(TrajectoryPlot, InconsistentSeriesAreNamed) {
  test::TempDir dir("trajectory-plot-bad");
  TrajectorySeries s = sine_series();
  s.values[2][1].pop_back();
  EXPECT_NE(test::error_of([&] {
              plot_trajectory(s, dir.path(), {});
            }).find("axis 'b' derivative 2 has 200 samples, expected 201"),
            std::string::npos);
  s = sine_series();
  s.limits[1] = {1.0};
  EXPECT_THROW(plot_trajectory(s, dir.path(), {}), Error);
  s = sine_series();
  s.axes.clear();
  EXPECT_THROW(plot_trajectory(s, dir.path(), {}), Error);
  EXPECT_THROW(plot_trajectory(sine_series(), dir.path(), {100, 100, 60.0}), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "trajectory.png"));
}

// issue 16, item 3: every text that reaches a gnuplot script goes through gnuplot_string; the
// trajectory plot (`mjarm traj --plot DIR --unit U`) too: its folder, title, unit and axis names
TEST(TrajectoryPlot, NoTextReachesGnuplotAsACommand) {
  test::TempDir dir("trajectory-plot-injection");
  TrajectorySeries s = sine_series();
  s.title = test::injection_text();
  s.unit = test::injection_text();
  s.axes = {test::injection_text(), "b" + test::injection_text()};
  const fs::path out = dir.path() / ("out" + test::injection_text());
  // gnuplot's working folder is this process's: the scratch folder, where `touch` would write
  const fs::path saved = fs::current_path();
  fs::current_path(dir.path());
  std::string error;
  PlotInfo info;
  try {
    info = plot_trajectory(s, out, {800, 900, 60.0});
  } catch (const std::exception& e) {
    error = e.what();
  }
  fs::current_path(saved);
  ASSERT_EQ(error, "");
  EXPECT_EQ(test::pwned_files(dir.path()), std::vector<fs::path>{});
  EXPECT_EQ(info.path, fs::absolute(out / "trajectory.png"));
  EXPECT_GT(test::pixel_stats(info.path).ink_fraction, 0.01);
  const std::string script = test::read_text(out / "gnuplot" / "trajectory.gp");
  EXPECT_EQ(script.find("\nsystem"), std::string::npos);
}

}  // namespace
}  // namespace mjarm::plot
