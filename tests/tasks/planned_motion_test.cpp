// The planned motion in a scene file's world: planned around its obstacles, tracked without
// touching them; a plan made without them runs into them, and the tracking says where and when.

#include "mjarm/tasks/planned_motion.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "mjarm/planning/waypoint_file.hpp"
#include "mjarm/planning/waypoint_path_plan.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

using ::testing::HasSubstr;

/// A box in the way of joint 1's swing from home to a tool position on the left.
std::filesystem::path wall_scene() {
  const std::filesystem::path path = test::scratch() / "planned_motion_wall.yaml";
  std::ofstream(path) << R"(name: wall_in_the_way
fixtures:
  - {name: wall, shape: box, size: [0.08, 0.08, 0.08], mass: 1, pos: [0.22, 0.22, 0.55]}
)";
  return path;
}

std::filesystem::path left_waypoint() {
  const std::filesystem::path path = test::scratch() / "planned_motion_left.json";
  std::ofstream(path) << R"({"waypoints": [{"position": [-0.0089, 0.3067, 0.59]}]})";
  return path;
}

Eigen::VectorXd home(const Robot& model) {
  const std::vector<double> q = model.keyframe_qpos("home");
  return Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
}

TEST(PlannedMotion, AroundASceneFilesObstacleAndTrackedWithoutTouchingIt) {
  PlannedMotionOptions options;
  options.waypoints = left_waypoint();
  options.scene = wall_scene();
  const PlannedMotionReport r = run_planned_motion(options);
  ASSERT_TRUE(r.planned()) << r.plan.result.message;
  EXPECT_TRUE(r.tracked.run.ok()) << r.tracked.run.message;
  EXPECT_FALSE(r.tracked.contacts.any()) << r.tracked.contacts.first_pair;
  EXPECT_EQ(r.tracked.contacts.ticks, 0);
  EXPECT_TRUE(r.ok());
  // the plan is not the straight joint motion of the world without the wall
  ASSERT_EQ(r.plan.result.waypoints.size(), 1u);
  const WaypointReport& w = r.plan.result.waypoints[0];
  EXPECT_TRUE(w.detour || w.branch != 0) << "branch " << w.branch;
}

TEST(PlannedMotion, APlanMadeWithoutTheWallRunsIntoItAndTheContactIsNamed) {
  const ShelfPickRobot& robot = shelf_pick_robot("panda");
  const PlannedMotionWorld bare = planned_motion_world(robot, "");
  const PlannedMotionWorld world = planned_motion_world(robot, wall_scene());
  EXPECT_EQ(world.frame, "panda/attachment_site");
  ASSERT_EQ(world.model.model().nq, bare.model.model().nq);
  const Chain bare_chain(bare.model, bare.frame);
  const Eigen::VectorXd start = home(bare.model);
  const WaypointPathPlan plan =
      plan_waypoint_path(bare_chain, start, load_waypoints(left_waypoint()), PlanOptions{});
  ASSERT_TRUE(plan.result.ok()) << plan.result.message;

  TrackingOptions tracking;
  tracking.controller = "ct";
  const Chain chain(world.model, world.frame);
  const PlannedMotionRun run =
      track_planned_motion(chain, robot, start, plan.result.trajectory, tracking);
  ASSERT_TRUE(run.contacts.any());
  EXPECT_THAT(run.contacts.first_pair, HasSubstr("geom 'wall/"));
  EXPECT_THAT(run.contacts.first_pair, HasSubstr("panda/"));
  EXPECT_GT(run.contacts.first_time, 0.0);
  EXPECT_LT(run.contacts.first_time, plan.result.trajectory.duration());
  EXPECT_LE(run.contacts.deepest.distance, run.contacts.first.distance);
  EXPECT_LE(run.contacts.deepest.distance, 0.0);
  // the same plan tracked in the world without the wall touches nothing
  const PlannedMotionRun free =
      track_planned_motion(bare_chain, robot, start, plan.result.trajectory, tracking);
  EXPECT_FALSE(free.contacts.any()) << free.contacts.first_pair;
  EXPECT_LT(free.tracking.max_position, 0.01);
}

TEST(PlannedMotion, ASceneFileThatAlreadyHoldsTheRobotIsRefusedWithBothNamed) {
  const std::filesystem::path path = test::scratch() / "planned_motion_twice.yaml";
  std::ofstream(path) << "name: twice\nrobots:\n  - {name: panda, model: panda}\n";
  const std::string message =
      test::error_of([&] { planned_motion_world(shelf_pick_robot("panda"), path); });
  EXPECT_THAT(message, HasSubstr("panda_torque"));
  EXPECT_THAT(message, HasSubstr(path.string()));
  EXPECT_THAT(test::error_of([&] {
                planned_motion_world(shelf_pick_robot("panda"), test::scratch() / "none.yaml");
              }),
              HasSubstr("none.yaml"));
}

}  // namespace
}  // namespace mjarm
