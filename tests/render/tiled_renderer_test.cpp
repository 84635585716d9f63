// TiledRenderer: each tile is the picture of its camera rendered alone, the grid, blit, bad input.

#include "mjarm/render/tiled_renderer.hpp"

#include <gtest/gtest.h>

#include <string>

#include "mjarm/error.hpp"
#include "render_test_support.hpp"

namespace mjarm {
namespace {

using test::error_of;
using test::same;

constexpr const char* kTwoCameras = R"(
<mujoco model="tiles">
  <include file="common/scene.xml"/>
  <worldbody>
    <camera name="overhead" pos="0 0 3" xyaxes="1 0 0 0 1 0"/>
    <camera name="side" pos="2 0 0.5" xyaxes="0 1 0 0 0 1"/>
    <body name="ball" pos="0.3 0.1 0.4"><geom type="sphere" size="0.1" rgba="1 0 0 1"/></body>
  </worldbody>
</mujoco>)";

// the tile of @p image at column @p column, row @p row
Image tile_of(const Image& image, int column, int row, int w, int h) {
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = image.at(column * w + x, row * h + y)[c];
  return out;
}

TEST(TileGrid, OneRowUpToThreeThenASquare) {
  EXPECT_EQ(TileGrid::of(1).columns, 1);
  EXPECT_EQ(TileGrid::of(3).columns, 3);
  EXPECT_EQ(TileGrid::of(3).rows, 1);
  EXPECT_EQ(TileGrid::of(4).columns, 2);
  EXPECT_EQ(TileGrid::of(4).rows, 2);
  EXPECT_EQ(TileGrid::of(5).columns, 3);
  EXPECT_EQ(TileGrid::of(5).rows, 2);
  EXPECT_EQ(TileGrid::of(4, 1).rows, 4);
  EXPECT_EQ(TileGrid::of(2, 5).columns, 2);  // never more columns than tiles
  EXPECT_NE(error_of([] { TileGrid::of(0); }).find("at least one camera"), std::string::npos);
  EXPECT_NE(error_of([] { TileGrid::of(2, -1); }).find("columns"), std::string::npos);
}

TEST(TileGrid, BlitCopiesAndClips) {
  Image tile(2, 2);
  for (auto& b : tile.rgb) b = 200;
  Image out(3, 3);
  blit(tile, out, 2, 2);  // only the top-left pixel of the tile lands inside
  int lit = 0;
  for (auto b : out.rgb) lit += b == 200;
  EXPECT_EQ(lit, 3);
  EXPECT_EQ(out.at(2, 2)[0], 200);
  blit(tile, out, -5, 0);  // entirely outside: nothing
  EXPECT_EQ(out.at(0, 0)[0], 0);
}

TEST(TiledRenderer, EachTileIsItsCameraAlone) {
  const Robot robot = Robot::from_string(kTwoCameras, MJARM_MODELS_DIR);
  DataPtr d = robot.make_data();
  mj_forward(&robot.model(), d.get());
  const int w = 160, h = 120;
  const std::vector<CameraSpec> cameras{CameraSpec::model_camera("overhead"),
                                        CameraSpec::model_camera("side"),
                                        CameraSpec::free_camera({0.3, 0.1, 0.4}, 1.5, 90.0, -30.0)};
  TiledRenderer tiled(robot, w, h, cameras, 2);  // 2 columns: a 2×2 grid, the last tile black
  EXPECT_EQ(tiled.width(), 2 * w);
  EXPECT_EQ(tiled.height(), 2 * h);
  const Image picture = tiled.render(*d);
  OffscreenRenderer alone(robot, w, h);
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    const Image expected = alone.render(*d, cameras[static_cast<std::size_t>(k)]);
    EXPECT_TRUE(same(tile_of(picture, k % 2, k / 2, w, h), expected));
    EXPECT_GT(test::pixel_stats(expected).grey_stddev, 5.0);  // a real picture, not a blank
  }
  EXPECT_EQ(test::pixel_stats(tile_of(picture, 1, 1, w, h)).dark_share, 1.0);
  // reusing the picture: same pixels
  Image again;
  tiled.render(*d, again);
  EXPECT_TRUE(same(again, picture));
}

TEST(TiledRenderer, BadInput) {
  const Robot robot = Robot::from_string(kTwoCameras, MJARM_MODELS_DIR);
  DataPtr d = robot.make_data();
  mj_forward(&robot.model(), d.get());
  EXPECT_NE(error_of([&] { TiledRenderer(robot, 64, 48, {}); }).find("at least one camera"),
            std::string::npos);
  TiledRenderer unknown(robot, 64, 48,
                        {CameraSpec::model_camera("overhead"), CameraSpec::model_camera("sidee")});
  const std::string message = error_of([&] { unknown.render(*d); });
  EXPECT_NE(message.find("sidee"), std::string::npos) << message;
  EXPECT_NE(message.find("side"), std::string::npos) << message;
}

}  // namespace
}  // namespace mjarm
