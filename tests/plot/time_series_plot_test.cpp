#include "mjarm/plot/time_series_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/error.hpp"
#include "plot/plot_test_support.hpp"
#include "support/error_message.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

// a force that steps up and a stiffness that ramps down, with two phases
TimeSeriesFigure force_and_stiffness() {
  TimeSeriesFigure f;
  f.name = "force_stiffness";
  f.title = "a press, with 'quotes'";
  for (int k = 0; k <= 300; ++k) f.t.push_back(0.01 * k);
  TimePanel force{"force [N]", {{"true", {}, false}, {"measured", {}, true}}};
  TimePanel stiffness{"stiffness [N/m]", {{"x", {}, false}}};
  for (const double t : f.t) {
    force.series[0].values.push_back(t < 1.0 ? 0.0 : 5.0);
    force.series[1].values.push_back(t < 1.0 ? 0.0 : 5.0 * (1.0 - std::exp(-(t - 1.0) / 0.05)));
    stiffness.series[0].values.push_back(t < 1.0 ? 1000.0 : std::nan(""));
  }
  f.panels = {force, stiffness};
  f.bands = {{0.0, 1.0, "approach"}, {1.0, 3.0, "hold"}};
  return f;
}

TEST(TimeSeriesPlot, DrawsOnePanelPerGroupWithItsCurves) {
  test::TempDir dir("time-series-plot");
  const PlotInfo info =
      plot_time_series(force_and_stiffness(), dir.path() / "out", {800, 600, 60.0});
  EXPECT_EQ(info.path, fs::absolute(dir.path() / "out" / "force_stiffness.png"));
  EXPECT_EQ(info.name, "force_stiffness");
  const test::PixelStats stats = test::pixel_stats(info.path);
  EXPECT_EQ(stats.width, 800);
  EXPECT_EQ(stats.height, 600);
  EXPECT_GT(stats.ink_fraction, 0.01);
  ASSERT_EQ(info.series.size(), 3u);
  EXPECT_EQ(info.series[0], "force [N]: true");
  EXPECT_EQ(info.series[1], "force [N]: measured");
  EXPECT_EQ(info.series[2], "stiffness [N/m]: x");
  const fs::path data = dir.path() / "out" / "gnuplot" / "force_stiffness.dat";
  ASSERT_TRUE(fs::exists(data));
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "gnuplot" / "force_stiffness.gp"));
}

TEST(TimeSeriesPlot, InconsistentFiguresAreNamed) {
  test::TempDir dir("time-series-plot-bad");
  TimeSeriesFigure f = force_and_stiffness();
  f.panels[1].series[0].values.pop_back();
  EXPECT_NE(test::error_of([&] {
              plot_time_series(f, dir.path(), {});
            }).find("curve 'x' has 300 values, expected 301"),
            std::string::npos);
  f = force_and_stiffness();
  f.name = "../escape";
  EXPECT_NE(test::error_of([&] { plot_time_series(f, dir.path(), {}); }).find("plain file stem"),
            std::string::npos);
  f = force_and_stiffness();
  f.panels.clear();
  EXPECT_NE(test::error_of([&] { plot_time_series(f, dir.path(), {}); }).find("1 … 6 panels"),
            std::string::npos);
  f = force_and_stiffness();
  f.bands[0].end = -1.0;
  EXPECT_NE(test::error_of([&] { plot_time_series(f, dir.path(), {}); }).find("'approach'"),
            std::string::npos);
  f = force_and_stiffness();
  std::swap(f.t.front(), f.t.back());
  EXPECT_THROW(plot_time_series(f, dir.path(), {}), Error);
  EXPECT_THROW(plot_time_series(force_and_stiffness(), dir.path(), {100, 100, 60.0}), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "force_stiffness.png"));
}

}  // namespace
}  // namespace mjarm::plot
