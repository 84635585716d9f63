// Pictures as observations: `pixels:CAMERA` and `depth:CAMERA` of a model camera or the free one,
// their shapes and bounds, what they show, repeatability, and an unknown camera. Rendered
// headless (EGL); these tests run without leak checking (tests/CMakeLists.txt: Mesa's JIT).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "env/env_test_support.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::HookTask;

EnvironmentOptions picture_options(int width = 84, int height = 84) {
  EnvironmentOptions o;
  o.action_space = ActionSpace::joint_torques;
  o.observations = {"pixels:free", "depth:free", "joint_positions"};
  o.pixels_width = width;
  o.pixels_height = height;
  return o;
}

std::vector<double> array_of(const TimeStep& ts, const std::string& name) {
  const auto values = ts.observation[name];
  return std::vector<double>(values.begin(), values.end());
}

TEST(EnvPixels, PicturesAreObservationsWithTheirShapesAndBounds) {
  Environment env(std::make_unique<HookTask>(), picture_options(48, 32));
  const ArraySpec& pixels = env.observation_spec().at("pixels:free");
  EXPECT_EQ(pixels.shape, (std::vector<int>{32, 48, 3}));
  EXPECT_EQ(pixels.minimum.minCoeff(), 0.0);
  EXPECT_EQ(pixels.maximum.maxCoeff(), 255.0);
  EXPECT_EQ(env.observation_spec().at("depth:free").shape, (std::vector<int>{32, 48}));
  const TimeStep ts = env.reset(2);
  const std::vector<double> rgb = array_of(ts, "pixels:free");
  ASSERT_EQ(rgb.size(), 32u * 48u * 3u);
  const auto [lo, hi] = std::minmax_element(rgb.begin(), rgb.end());
  EXPECT_GE(*lo, 0.0);
  EXPECT_LE(*hi, 255.0);
  EXPECT_GT(*hi - *lo, 50.0) << "a picture, not a blank";
  const std::vector<double> depth = array_of(ts, "depth:free");
  for (double z : depth) ASSERT_TRUE(std::isfinite(z) && z > 0.0);
  EXPECT_LT(*std::min_element(depth.begin(), depth.end()),
            *std::max_element(depth.begin(), depth.end()))
      << "the arm nearer than the floor behind it";
}

TEST(EnvPixels, TheArmMovingChangesThePictureAndASeedRepeatsIt) {
  Environment env(std::make_unique<HookTask>(), picture_options());
  const std::vector<double> start = array_of(env.reset(5), "pixels:free");
  const double torque[] = {20.0, 0.0};
  TimeStep ts;
  for (int k = 0; k < 25; ++k) ts = env.step(torque);
  const std::vector<double> moved = array_of(ts, "pixels:free");
  int changed = 0;
  for (std::size_t i = 0; i < start.size(); ++i) changed += start[i] != moved[i];
  EXPECT_GT(changed, 100) << "the first joint turned the arm";
  EXPECT_EQ(array_of(env.reset(5), "pixels:free"), start) << "the same seed, the same picture";
}

TEST(EnvPixels, AnUnknownCameraOrSizeIsRefused) {
  EnvironmentOptions o = picture_options();
  o.observations = {"pixels:overhead"};
  test::expect_error_containing([&] { Environment env(std::make_unique<HookTask>(), o); },
                                {"no such camera", "cameras: free"});
  EnvironmentOptions small = picture_options(8, 84);
  test::expect_error_containing([&] { Environment env(std::make_unique<HookTask>(), small); },
                                {"pixels_width"});
}

}  // namespace
}  // namespace mjarm
