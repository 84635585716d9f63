// Camera conventions and projection, independent of OpenGL.

#include "mjarm/render/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

TEST(Camera, AzimuthAndElevationSigns) {
  const Eigen::Vector3d lookat(0.5, -0.2, 0.3);
  // azimuth 0, level: looking along +x, so the camera sits on the −x side
  CameraView v = free_camera_view(lookat, 2.0, 0.0, 0.0, 45.0);
  EXPECT_LT((v.forward - Eigen::Vector3d::UnitX()).norm(), 1e-12);
  EXPECT_LT((v.position - (lookat - 2.0 * Eigen::Vector3d::UnitX())).norm(), 1e-12);
  EXPECT_LT((v.up - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  // azimuth 90: looking along +y
  v = free_camera_view(lookat, 2.0, 90.0, 0.0, 45.0);
  EXPECT_LT((v.forward - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  // elevation −30: looking down, camera above the look-at point by distance·sin 30°
  v = free_camera_view(lookat, 2.0, 45.0, -30.0, 45.0);
  EXPECT_LT(v.forward.z(), 0.0);
  EXPECT_NEAR(v.position.z() - lookat.z(), 1.0, 1e-12);
  // an orthonormal, right-handed frame
  EXPECT_NEAR(v.forward.norm(), 1.0, 1e-12);
  EXPECT_NEAR(v.up.norm(), 1.0, 1e-12);
  EXPECT_NEAR(v.forward.dot(v.up), 0.0, 1e-12);
  EXPECT_GT(v.up.z(), 0.0);
}

TEST(Camera, ProjectionOfKnownPoints) {
  const CameraView v = free_camera_view({0, 0, 0}, 3.0, 0.0, 0.0, 90.0);
  // the look-at point is the image centre at depth = distance
  Eigen::Vector3d uvd = project(v, 200, 100, Eigen::Vector3d::Zero());
  EXPECT_NEAR(uvd.x(), 100.0, 1e-9);
  EXPECT_NEAR(uvd.y(), 50.0, 1e-9);
  EXPECT_NEAR(uvd.z(), 3.0, 1e-12);
  // fovy 90°: a point 3 m above the look-at point is on the top edge; +z is image-up
  uvd = project(v, 200, 100, Eigen::Vector3d(0, 0, 3.0));
  EXPECT_NEAR(uvd.y(), 0.0, 1e-9);
  // the camera looks along +x with +z up, so image-right is −y; horizontal extent follows aspect
  uvd = project(v, 200, 100, Eigen::Vector3d(0, -6.0, 0));
  EXPECT_NEAR(uvd.x(), 200.0, 1e-9);
  // behind the camera: negative depth
  EXPECT_LT(project(v, 200, 100, Eigen::Vector3d(-5, 0, 0)).z(), 0.0);
}

TEST(Camera, BadNumbersAreErrors) {
  EXPECT_THROW(free_camera_view({0, 0, 0}, -1.0, 0, 0, 45), Error);
  EXPECT_THROW(free_camera_view({0, 0, 0}, 1.0, 0, 90.0, 45), Error);
  EXPECT_THROW(free_camera_view({0, 0, 0}, 1.0, INFINITY, 0, 45), Error);
  EXPECT_THROW(free_camera_view({0, 0, 0}, 1.0, 0, 0, 180.0), Error);
  EXPECT_THROW(free_camera_view({NAN, 0, 0}, 1.0, 0, 0, 45), Error);
}

TEST(Camera, SpecsDescribeThemselves) {
  EXPECT_EQ(CameraSpec::model_camera("top").describe(), "model camera 'top'");
  const auto follow = CameraSpec::follow("tcp", 0.5, 90, -30);
  EXPECT_EQ(follow.kind, CameraKind::follow);
  EXPECT_NE(follow.describe().find("follow 'tcp'"), std::string::npos);
  EXPECT_NE(CameraSpec::free_camera({1, 2, 3}, 2, 10, -5).describe().find("lookat [1, 2, 3]"),
            std::string::npos);
  EXPECT_STREQ(to_string(CameraKind::free), "free");
}

}  // namespace
}  // namespace mjarm
