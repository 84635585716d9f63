// Marker balls of RenderOptions: drawn where they are, in their colour; bad ones rejected.

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "mjarm/render/offscreen_renderer.hpp"
#include "render/render_test_support.hpp"

namespace mjarm {
namespace {

TEST(RenderMarker, ABallIsDrawnAtItsProjectedPixelInItsColour) {
  const Robot empty = test::empty_scene();
  DataPtr d = empty.make_data();
  mj_forward(&empty.model(), d.get());
  const Eigen::Vector3d ball(0.3, -0.2, 0.5);
  const CameraSpec camera = CameraSpec::free_camera({0.0, 0.0, 0.4}, 2.0, 120.0, -20.0);
  RenderOptions options;
  options.shadows = false;
  options.markers.push_back({ball, 0.08, {0.95f, 0.05f, 0.05f, 1.0f}});
  OffscreenRenderer renderer(empty, 96, 72, options);
  const Image with = renderer.render(*d, camera);
  const Eigen::Vector3d uvd = project(renderer.view(*d, camera), 96, 72, ball);
  ASSERT_GT(uvd.z(), 0.0);
  const std::uint8_t* px = with.at(static_cast<int>(uvd.x()), static_cast<int>(uvd.y()));
  EXPECT_GT(px[0], 120) << int(px[0]) << " " << int(px[1]) << " " << int(px[2]);
  EXPECT_LT(px[1], 60);
  EXPECT_LT(px[2], 60);

  // without it the pixel is the scene's (not red)
  RenderOptions plain;
  plain.shadows = false;
  renderer.set_options(plain);
  const Image without = renderer.render(*d, camera);
  const std::uint8_t* bare = without.at(static_cast<int>(uvd.x()), static_cast<int>(uvd.y()));
  EXPECT_FALSE(bare[0] > 120 && bare[1] < 60 && bare[2] < 60);

  // bad markers: an Error, the options in force kept
  RenderOptions bad;
  bad.markers.push_back({ball, 0.0, {1.0f, 0.0f, 0.0f, 1.0f}});
  EXPECT_THROW(renderer.set_options(bad), Error);
  bad.markers[0] = {ball, 0.05, {1.5f, 0.0f, 0.0f, 1.0f}};
  EXPECT_THROW(renderer.set_options(bad), Error);
  EXPECT_THROW(OffscreenRenderer(empty, 8, 8, bad), Error);
  EXPECT_TRUE(renderer.options().markers.empty());
}

}  // namespace
}  // namespace mjarm
