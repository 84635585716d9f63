// Rates with intervals, rate heat maps and histograms (mjarm/plot/rate_plots.hpp): each drawn as a
// whole PNG of the size asked for with its script and data kept, the data holding what was given,
// and inconsistent figures refused by name before anything is drawn.
#include "mjarm/plot/rate_plots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "mjarm/error.hpp"
#include "plot/plot_test_support.hpp"
#include "support/error_message.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;
using test::error_of;

TEST(RatePlots, DrawRatesAHeatMapAndHistograms) {
  test::TempDir dir("rate-plots");
  RateFigure rates;
  rates.title = "success against grasp";
  rates.xlabel = "grasp";
  rates.points = {{"weld", 0.9, 0.74, 0.97, 30}, {"friction", 0.5, 0.33, 0.67, 30}};
  const PlotInfo r = plot_rates(rates, dir.path(), {800, 600, 60.0});
  const test::PixelStats stats = test::pixel_stats(r.path);
  EXPECT_EQ(stats.width, 800);
  EXPECT_GT(stats.ink_fraction, 0.01);
  EXPECT_EQ(test::read_text(dir.path() / "gnuplot" / "rates.dat"),
            "# index, rate, low, high, trials\n0 0.9 0.74 0.97 30\n1 0.5 0.33 0.67 30\n");

  HeatMapFigure heat;
  heat.title = "success";
  heat.xlabel = "object-size";
  heat.ylabel = "grasp";
  heat.columns = {"0.01", "0.02", "0.03"};
  heat.rows = {"weld", "friction"};
  heat.rates = {{1.0, 0.9, 0.8}, {0.6, std::nan(""), 0.2}};
  const PlotInfo h = plot_heat_map(heat, dir.path(), {800, 600, 60.0});
  EXPECT_GT(test::pixel_stats(h.path).variance, 10.0);

  HistogramFigure hist;
  hist.title = "metrics";
  hist.bins = 4;
  hist.histograms = {{"error [m]", {0.0, 0.1, 0.1, 0.2, 0.4, std::nan("")}}, {"empty", {}}};
  const PlotInfo d = plot_histograms(hist, dir.path(), {800, 600, 60.0});
  EXPECT_GT(test::pixel_stats(d.path).ink_fraction, 0.01);
  // the first block: bin centre, count, width; the NaN left out, the largest value in the last bin
  std::istringstream data(test::read_text(dir.path() / "gnuplot" / "distributions.dat"));
  std::string header;
  std::getline(data, header);
  EXPECT_EQ(header, "# error [m]");
  std::vector<int> counts;
  double centre = 0.0, width = 0.0;
  int count = 0;
  for (int b = 0; b < 4 && data >> centre >> count >> width; ++b) {
    counts.push_back(count);
    EXPECT_NEAR(centre, 0.05 + 0.1 * b, 1e-12);
    EXPECT_NEAR(width, 0.1, 1e-12);
  }
  EXPECT_EQ(counts, (std::vector<int>{1, 2, 1, 1}));
}

TEST(RatePlots, InconsistentFiguresAreRefusedByName) {
  test::TempDir dir("rate-plots-bad");
  RateFigure rates;
  EXPECT_NE(error_of([&] { plot_rates(rates, dir.path()); }).find("no points"), std::string::npos);
  rates.points = {{"weld", 0.9, 0.95, 1.0, 3}};
  EXPECT_NE(error_of([&] { plot_rates(rates, dir.path()); }).find("point 'weld'"),
            std::string::npos);
  HeatMapFigure heat;
  heat.columns = {"a"};
  heat.rows = {"x", "y"};
  heat.rates = {{0.5}};
  EXPECT_NE(error_of([&] { plot_heat_map(heat, dir.path()); }).find("does not match"),
            std::string::npos);
  HistogramFigure hist;
  EXPECT_NE(error_of([&] { plot_histograms(hist, dir.path()); }).find("1 … 12 panels"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir.path() / "rates.png"));
}

}  // namespace
}  // namespace mjarm::plot
