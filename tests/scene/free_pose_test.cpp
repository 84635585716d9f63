#include "mjarm/scene/free_pose.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/scene/scene.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;

Robot arm_and_two_cubes() {
  Scene scene("cubes");
  scene.add_arena();
  scene.add_robot({"arm", "arm6", {-1.0, 0.0, 0.0}, {1, 0, 0, 0}, false});
  for (const char* name : {"a", "b"}) {
    ObjectSpec cube;
    cube.name = name;
    cube.pos = {0.0, name[0] == 'a' ? 0.3 : -0.3, 0.02};
    scene.add_object(cube);
  }
  return scene.compile();
}

TEST(FreePose, SetsTheFreeJointsQposAndTheBodyFollows) {
  const Robot robot = arm_and_two_cubes();
  DataPtr d = robot.make_data();
  const double h = std::sqrt(0.5);
  // an unnormalized quaternion comes out unit
  set_free_pose(robot, *d, "b", {{0.4, -0.1, 0.3}, {2 * h, 0.0, 0.0, 2 * h}});
  const int adr = free_qpos_address(robot, "b");
  EXPECT_EQ(adr, robot.model().jnt_qposadr[robot.joint("b/joint")]);
  EXPECT_EQ(d->qpos[adr], 0.4);
  EXPECT_NEAR(d->qpos[adr + 3], h, 1e-15);
  mj_forward(&robot.model(), d.get());
  const int body = robot.body("b");
  EXPECT_NEAR(d->xpos[3 * body + 0], 0.4, 1e-15);
  EXPECT_NEAR(d->xpos[3 * body + 2], 0.3, 1e-15);
  EXPECT_NEAR(d->xquat[4 * body + 3], h, 1e-15);
  // the other cube and the arm are untouched
  const FreePose a = free_pose(robot, *d, "a");
  EXPECT_EQ(a.p_WB[1], 0.3);
  EXPECT_EQ(a.quat_WB[0], 1.0);
  const FreePose b = free_pose(robot, *d, "b/joint");
  EXPECT_EQ(b.p_WB[0], 0.4);
}

TEST(FreePose, BadInputIsNamed) {
  const Robot robot = arm_and_two_cubes();
  DataPtr d = robot.make_data();
  EXPECT_NE(error_of([&] { free_qpos_address(robot, "arm/link2"); }).find("has no free joint"),
            std::string::npos);
  EXPECT_NE(error_of([&] { free_qpos_address(robot, "arm/joint2"); }).find("is not a free joint"),
            std::string::npos);
  const std::string unknown = error_of([&] { free_qpos_address(robot, "c"); });
  EXPECT_NE(unknown.find("body 'c' not found in model 'cubes'"), std::string::npos) << unknown;
  EXPECT_NE(error_of([&] {
              set_free_pose(robot, *d, "a", {{0, 0, 0}, {0, 0, 0, 0}});
            }).find("zero quaternion"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              set_free_pose(robot, *d, "a", {{NAN, 0, 0}, {1, 0, 0, 0}});
            }).find("not finite"),
            std::string::npos);
  // a refused pose leaves the state as it was
  EXPECT_EQ(free_pose(robot, *d, "a").p_WB[1], 0.3);
}

}  // namespace
}  // namespace mjarm
