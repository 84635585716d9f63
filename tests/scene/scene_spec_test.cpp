#include "mjarm/scene/scene_spec.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;

bool says(const std::string& message, const std::string& part) {
  return message.find(part) != std::string::npos;
}

TEST(SceneSpec, NamesRoundTrip) {
  for (auto shape : {ObjectShape::box, ObjectShape::sphere, ObjectShape::cylinder,
                     ObjectShape::capsule, ObjectShape::mesh})
    EXPECT_EQ(object_shape(to_string(shape)), shape);
  for (auto type : {SensorType::jointpos, SensorType::framepos, SensorType::framequat,
                    SensorType::touch, SensorType::force, SensorType::torque})
    EXPECT_EQ(sensor_type(to_string(type)), type);
  EXPECT_TRUE(says(error_of([] { sensor_type("frampos"); }), "closest: framepos"));
}

TEST(SceneSpec, ObjectsNeedSizesMassesAndFrictionsThatMakeSense) {
  ObjectSpec cube;
  cube.name = "cube";
  validate(cube);
  ObjectSpec bad = cube;
  bad.size = {0.01, 0.0, 0.01};
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "size must be positive"));
  bad = cube;
  bad.friction[0] = -0.5;
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "friction must be >= 0"));
  bad = cube;
  bad.mass = NAN;
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "mass holds a non-finite value"));
  bad.mass = -1.0;
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "mass must be positive"));
  bad = cube;
  bad.quat = {0, 0, 0, 0};
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "zero quaternion"));
  bad = cube;
  bad.shape = ObjectShape::capsule;
  EXPECT_TRUE(
      says(error_of([&] { validate(bad); }), "size expects 2 value(s) (radius, half length)"));
  bad = cube;
  bad.shape = ObjectShape::mesh;
  bad.size.clear();
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "needs a mesh file"));
  bad = cube;
  bad.rgba[3] = 2.0;
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "rgba"));
  bad = cube;
  bad.name = "a\"b";
  EXPECT_TRUE(says(error_of([&] { validate(bad); }), "may not contain"));
}

TEST(SceneSpec, RobotsCamerasSitesWeldsAndArenasAreChecked) {
  EXPECT_TRUE(says(error_of([] {
                     validate(RobotSpec{"a/b", "panda", {}, {1, 0, 0, 0}, false});
                   }),
                   "may not contain '/'"));
  EXPECT_TRUE(says(error_of([] {
                     validate(RobotSpec{"a", "", {}, {1, 0, 0, 0}, false});
                   }),
                   "needs a model"));
  EXPECT_TRUE(says(error_of([] {
                     validate(GripperSpec{"a", "franka_hand", "", "g"});
                   }),
                   "needs the robot frame"));
  SceneCameraSpec camera;
  camera.name = "c";
  camera.fovy = 190.0;
  EXPECT_TRUE(says(error_of([&] { validate(camera); }), "fovy must lie in (0, 180)"));
  SiteSpec site;
  site.name = "s";
  site.size = -1.0;
  EXPECT_TRUE(says(error_of([&] { validate(site); }), "size must be positive"));
  EXPECT_TRUE(says(error_of([] {
                     validate(WeldSpec{"w", "a", "a", false, {0.002, 1.0}});
                   }),
                   "to itself"));
  EXPECT_TRUE(says(error_of([] {
                     validate(WeldSpec{"w", "a", "b", false, {0.0, 1.0}});
                   }),
                   "solref must be positive"));
  ArenaSpec arena;
  arena.table = true;
  arena.table_height = 0.0;
  EXPECT_TRUE(says(error_of([&] { validate(arena); }), "table_height"));
}

}  // namespace
}  // namespace mjarm
