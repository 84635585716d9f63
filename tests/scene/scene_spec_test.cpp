#include "mjarm/scene/scene_spec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>
#include <vector>

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

// The declared ranges (the Python docs say them) are the ones validate() enforces: below or
// above a declared bound, or NaN, in any numeric field is refused with the field's name.
template <class S>
void expect_declared_ranges_enforced(const S& good) {
  validate(good);
  for_each_field<S>([&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::Type;
    if constexpr (NumberField<T> || VectorField<T>) {
      std::vector<double> outside{NAN};
      if (f.range.min > -Range::inf)
        outside.push_back(f.range.min_open ? f.range.min : f.range.min - 1.0);
      if (f.range.max < Range::inf)
        outside.push_back(f.range.max_open ? f.range.max : f.range.max + 1.0);
      for (const double x : outside) {
        S bad = good;
        if constexpr (NumberField<T>) {
          bad.*(f.member) = x;
        } else {
          if ((bad.*(f.member)).empty()) continue;
          (bad.*(f.member))[0] = x;
        }
        const std::string message = error_of([&] { validate(bad); });
        EXPECT_TRUE(says(message, std::string(f.name)))
            << fields_of<S>().owner << " " << f.name << " = " << x << ": " << message;
      }
    }
  });
}

TEST(SceneSpec, DeclaredRangesAreTheOnesValidateEnforces) {
  ArenaSpec arena;
  arena.table = true;  // the table's fields are checked when there is one
  expect_declared_ranges_enforced(arena);
  expect_declared_ranges_enforced(RobotSpec{"arm", "panda", {}, {1, 0, 0, 0}, false});
  ObjectSpec cube;
  cube.name = "cube";
  expect_declared_ranges_enforced(cube);
  ObjectSpec tetra;
  tetra.name = "tetra";
  tetra.shape = ObjectShape::mesh;
  tetra.size.clear();
  tetra.mesh_vertices = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  expect_declared_ranges_enforced(tetra);
  CompoundFixtureSpec bin;
  bin.name = "bin";
  bin.pieces = {cube};
  expect_declared_ranges_enforced(bin);
  SceneCameraSpec camera;
  camera.name = "c";
  camera.xyaxes = {1, 0, 0, 0, 1, 0};
  expect_declared_ranges_enforced(camera);
  SiteSpec site;
  site.name = "s";
  expect_declared_ranges_enforced(site);
  expect_declared_ranges_enforced(WeldSpec{"w", "a", "b", false, {0.002, 1.0}});
}

}  // namespace
}  // namespace mjarm
