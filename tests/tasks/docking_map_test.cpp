#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mjarm/tasks/docking/capture_map.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

TEST(DockingMap, TheIssuesAxesGive768OffsetsRadiusFirst) {
  const DockingMapAxes axes = default_docking_map_axes();
  const std::vector<DockingOffset> offsets = docking_map_offsets(axes);
  ASSERT_EQ(offsets.size(), 16u * 8u * 6u);
  // radius slowest, then direction, then yaw
  EXPECT_DOUBLE_EQ(offsets[6 * 8 * 12 + 6 * 2 + 5].dx, std::cos(std::numbers::pi / 2) * 0.012);
  EXPECT_NEAR(offsets[6 * 8 * 12 + 6 * 2 + 5].dy, 0.012, 1e-15);
  EXPECT_NEAR(offsets[6 * 8 * 12 + 6 * 2 + 5].dyaw, 25.0 * kDockingDeg, 1e-15);
  for (const DockingOffset& o : offsets) EXPECT_LE(std::hypot(o.dx, o.dy), 0.015 + 1e-15);
  DockingMapAxes bad = axes;
  bad.radii = {0.0, 0.002, 0.001};
  EXPECT_TRUE(contains(error_of([&] { docking_map_offsets(bad); }), "increasing"));
}

TEST(DockingMap, ACoarseMapSeatsInsideAndSearchesOutsideTheChamfer) {
  // two rings (on the axis, and 12 mm off: on the top face) × 2 directions × one yaw
  DockingMapAxes axes;
  axes.radii = {0.0, 0.012};
  axes.directions = 2;
  axes.yaws = {0.0};
  DockingGridOptions grid;
  grid.base.motion.start_height = 0.03;
  grid.base.motion.approach_time = 0.6;
  grid.base.motion.hold_time = 1.2;
  grid.offsets = docking_map_offsets(axes);
  grid.jobs = 2;
  const DockingGridResult result = run_docking_grid(grid);
  ASSERT_EQ(result.runs.size(), 4u);
  const std::vector<DockingMapCell> cells = docking_map_cells(axes, result);
  ASSERT_EQ(cells.size(), 4u);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    SCOPED_TRACE(c);
    EXPECT_EQ(cells[c].trials, 1);
    EXPECT_EQ(cells[c].seated, 1);
    EXPECT_LE(cells[c].max_peak_force, 30.0);
    EXPECT_EQ(cells[c].searched, c < 2 ? 0 : 1);  // 12 mm off lands on the top face
    // the bottom reached after the planned insertion (0.6 + 5.7 s); later after a search
    EXPECT_GT(cells[c].max_seat_time, 4.0);
    if (c >= 2) EXPECT_GT(cells[c].max_seat_time, result.runs[0].seat_time);
  }
  EXPECT_NEAR(cells[3].direction, std::numbers::pi, 1e-15);
  const auto png = plot_docking_map(axes, result, test::scratch() / "docking-map", "map").path;
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
}

}  // namespace
}  // namespace mjarm
