// The polar heat map (mjarm/plot/polar_heat_map.hpp): one PNG of the size asked for, its data
// the cell centres with their values, NaN cells left out, inconsistent figures refused by name.
#include "mjarm/plot/polar_heat_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/error.hpp"
#include "plot/plot_test_support.hpp"
#include "support/error_message.hpp"

namespace mjarm::plot {
namespace {

using test::error_of;

PolarHeatMapFigure two_rings() {
  PolarHeatMapFigure f;
  f.name = "capture";
  f.title = "capture region";
  f.axis_label = "offset [mm]";
  f.ring_edges = {0.0, 1.0, 2.0};
  f.sectors = 4;
  f.values = {{1.0, 1.0, 1.0, 1.0}, {0.5, std::nan(""), 0.0, 0.25}};
  return f;
}

TEST(PolarHeatMap, DrawsTheCellsAndKeepsTheirCentres) {
  test::TempDir dir("polar-heat-map");
  const PlotInfo info = plot_polar_heat_map(two_rings(), dir.path(), {800, 600, 60.0});
  const test::PixelStats stats = test::pixel_stats(info.path);
  EXPECT_EQ(stats.width, 800);
  EXPECT_GT(stats.variance, 10.0);
  const std::string data = test::read_text(dir.path() / "gnuplot" / "capture.dat");
  // 7 cells drawn (one NaN), centres at radius 0.5 and 1.5; sector 0 along +x, sector 1 along +y
  int lines = 0;
  for (char c : data) lines += c == '\n';
  EXPECT_EQ(lines, 1 + 7);
  EXPECT_NE(data.find("0.5 0 1\n"), std::string::npos) << data;
  EXPECT_NE(data.find("1.5 0 0.5\n"), std::string::npos) << data;
}

TEST(PolarHeatMap, InconsistentFiguresAreRefused) {
  test::TempDir dir("polar-heat-map-bad");
  PolarHeatMapFigure f = two_rings();
  f.ring_edges = {0.0, 2.0, 1.0};
  EXPECT_NE(error_of([&] { plot_polar_heat_map(f, dir.path()); }).find("increasing"),
            std::string::npos);
  f = two_rings();
  f.values[1].pop_back();
  EXPECT_NE(error_of([&] { plot_polar_heat_map(f, dir.path()); }).find("sectors"),
            std::string::npos);
  f = two_rings();
  f.low = 1.0;
  EXPECT_NE(error_of([&] { plot_polar_heat_map(f, dir.path()); }).find("low < high"),
            std::string::npos);
  f = two_rings();
  f.name = "a/b";
  EXPECT_NE(error_of([&] { plot_polar_heat_map(f, dir.path()); }).find("file stem"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm::plot
