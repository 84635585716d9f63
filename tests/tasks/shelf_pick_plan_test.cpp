#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/tasks/approach_timing.hpp"
#include "mjarm/tasks/shelf_pick/plan.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;

ShelfPickRequest request(const char* robot, std::uint64_t seed) {
  ShelfPickRequest r;
  r.robot = robot;
  r.controller = "osc";
  r.seed = seed;
  return r;
}

TEST(ShelfPickPlan, KnowsItsRobotsAndControllers) {
  ASSERT_EQ(shelf_pick_robots().size(), 2u);
  EXPECT_EQ(shelf_pick_robots()[0].name, "planar2");
  EXPECT_EQ(shelf_pick_robots()[1].name, "panda");
  EXPECT_EQ(shelf_pick_controllers(), (std::vector<std::string>{"ct", "osc", "task-pd", "accel"}));
  const std::string robot = error_of([] { shelf_pick_robot("ur5"); });
  EXPECT_NE(robot.find("unknown robot 'ur5'"), std::string::npos) << robot;
  EXPECT_NE(robot.find("planar2, panda"), std::string::npos) << robot;
  const std::string controller = error_of([] { check_shelf_pick_controller("pid"); });
  EXPECT_NE(controller.find("unknown controller 'pid'"), std::string::npos) << controller;
  EXPECT_NE(controller.find("ct, osc, task-pd, accel"), std::string::npos) << controller;
  ShelfPickRequest bad = request("panda", 1);
  bad.controller = "lqr";
  EXPECT_THROW(plan_shelf_pick(bad), Error);
}

TEST(ShelfPickPlan, TheSeedDrawsThePickAndTheStart) {
  for (const char* robot : {"planar2", "panda"}) {
    const ShelfPickRobot& spec = shelf_pick_robot(robot);
    const ShelfPickPlan a = plan_shelf_pick(request(robot, 7));
    const ShelfPickPlan b = plan_shelf_pick(request(robot, 7));
    const ShelfPickPlan c = plan_shelf_pick(request(robot, 8));
    // same seed, same plan, bit for bit
    EXPECT_EQ(a.pick, b.pick);
    EXPECT_EQ(a.qpos_start, b.qpos_start);
    EXPECT_EQ(a.goal.q_target, b.goal.q_target);
    EXPECT_EQ(a.goal.approach_time, b.goal.approach_time);
    EXPECT_NE(a.pick, c.pick);
    EXPECT_TRUE(a.pick_drawn);
    // inside the documented box, and the start within the perturbation of home
    EXPECT_TRUE(
        ((a.pick - spec.pick_center).cwiseAbs().array() <= spec.pick_half_width.array() + 1e-15)
            .all());
    const std::vector<double> home = a.model.keyframe_qpos("home");
    const Eigen::VectorXd dq = a.goal.q_start - a.chain.gather(home.data());
    EXPECT_LE(dq.cwiseAbs().maxCoeff(), spec.start_perturbation);
    EXPECT_GT(dq.cwiseAbs().maxCoeff(), 0.0);
    // a given pick point keeps the seed's start
    ShelfPickRequest given = request(robot, 7);
    given.pick = c.pick;
    const ShelfPickPlan d = plan_shelf_pick(given);
    EXPECT_FALSE(d.pick_drawn);
    EXPECT_EQ(d.pick, c.pick);
    EXPECT_EQ(d.qpos_start, a.qpos_start);
  }
}

// draw_shelf_pick is the plan's draw, in the documented order: three numbers for the pick
// point, then one per joint for the start
TEST(ShelfPickPlan, DrawShelfPickIsWhatThePlanDraws) {
  for (const char* robot : {"planar2", "panda"}) {
    const ShelfPickRobot& spec = shelf_pick_robot(robot);
    const ShelfPickPlan plan = plan_shelf_pick(request(robot, 7));
    std::vector<double> qpos = plan.model.keyframe_qpos("home");
    std::mt19937_64 rng(7);
    const Eigen::Vector3d pick = draw_shelf_pick(spec, plan.chain, rng, qpos);
    EXPECT_EQ(pick, plan.pick);
    EXPECT_EQ(qpos, plan.qpos_start);
    std::mt19937_64 again(7);
    const double u = unit_draw(again());
    EXPECT_EQ(pick.x(), spec.pick_center.x() + (2.0 * u - 1.0) * spec.pick_half_width.x());
  }
}

TEST(ShelfPickPlan, TheJointTargetPutsTheToolOnThePick) {
  for (const char* robot : {"planar2", "panda"}) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const ShelfPickPlan plan = plan_shelf_pick(request(robot, seed));
      ChainKinematics kin(plan.chain);
      const Pose X = kin.update(plan.goal.q_target);
      EXPECT_LT((X.p - plan.pick).norm(), 1e-8) << robot << seed;
      EXPECT_TRUE(plan.chain.within_limits(plan.goal.q_target));
      EXPECT_TRUE(plan.goal.X_WS.is_approx(kin.update(plan.goal.q_start), 1e-15));
      if (!plan.goal.position_only) {
        // the panda's tool keeps its home orientation (pointing down)
        const std::vector<double> home = plan.model.keyframe_qpos("home");
        const Pose X_home = kin.update(plan.chain.gather(home.data()));
        EXPECT_LT((X.R - X_home.R).norm(), 1e-7);
        EXPECT_NEAR(X.R(2, 2), -1.0, 1e-6);
      }
      // the approach respects the robot's bounds and the torque budget
      const ShelfPickRobot& spec = *plan.robot;
      const double d = (plan.pick - plan.goal.X_WS.p).norm();
      const double T = plan.goal.approach_time;
      EXPECT_GE(T, spec.min_approach_time);
      EXPECT_LE(1.875 * d / T, spec.max_speed * (1 + 1e-12));
      EXPECT_LE(5.7735026918962 * d / (T * T), spec.max_acceleration * (1 + 1e-9));
      EXPECT_NEAR(torque_feasible_duration(plan.chain, plan.qpos_start, plan.goal.q_target, T,
                                           spec.torque_fraction),
                  T, 0.02 * T);
    }
  }
}

TEST(ShelfPickPlan, APickOutOfReachNamesTheReach) {
  ShelfPickRequest far = request("planar2", 1);
  far.pick = Eigen::Vector3d(0.92, 0.0, 1.0);
  const std::string message = error_of([&] { plan_shelf_pick(far); });
  EXPECT_NE(message.find("pick point (0.92, 0, 1) m is out of reach of planar2"), std::string::npos)
      << message;
  EXPECT_NE(message.find("0.920 m from the shoulder (0, 0, 1)"), std::string::npos) << message;
  EXPECT_NE(message.find("reaches 0.2"), std::string::npos) << message;  // 0.24–0.75 m
  EXPECT_NE(message.find("–0.75 m"), std::string::npos) << message;

  ShelfPickRequest near = request("planar2", 1);
  near.pick = Eigen::Vector3d(0.1, 0.0, 1.0);  // inside the elbow's dead zone
  EXPECT_NE(error_of([&] { plan_shelf_pick(near); }).find("out of reach"), std::string::npos);

  ShelfPickRequest off = request("planar2", 1);
  off.pick = Eigen::Vector3d(0.5, 0.1, 0.8);
  const std::string plane = error_of([&] { plan_shelf_pick(off); });
  EXPECT_NE(plane.find("off the arm's plane"), std::string::npos) << plane;

  ShelfPickRequest panda = request("panda", 1);
  panda.pick = Eigen::Vector3d(1.2, 0.0, 0.5);
  const std::string p = error_of([&] { plan_shelf_pick(panda); });
  EXPECT_NE(p.find("out of reach of panda"), std::string::npos) << p;
  EXPECT_NE(p.find("m from the shoulder (0, 0, 0.333)"), std::string::npos) << p;
  EXPECT_NE(p.find("with the tool at its home orientation"), std::string::npos) << p;

  ShelfPickRequest floor = request("panda", 1);
  floor.pick = Eigen::Vector3d(0.4, 0.0, -0.05);
  EXPECT_NE(error_of([&] { plan_shelf_pick(floor); }).find("above the floor"), std::string::npos);

  ShelfPickRequest nan = request("panda", 1);
  nan.pick = Eigen::Vector3d(std::nan(""), 0.0, 0.5);
  EXPECT_NE(error_of([&] { plan_shelf_pick(nan); }).find("NaN"), std::string::npos);

  ShelfPickRequest criteria = request("panda", 1);
  criteria.criteria.hold_time = 0.0;
  EXPECT_THROW(plan_shelf_pick(criteria), Error);
}

TEST(ShelfPickPlan, UnitDrawUsesTheTop53Bits) {
  EXPECT_EQ(unit_draw(0), 0.0);
  EXPECT_EQ(unit_draw(~std::uint64_t{0}), 1.0 - 0x1.0p-53);
  EXPECT_EQ(unit_draw(std::uint64_t{1} << 63), 0.5);
  EXPECT_EQ(unit_draw(2047), 0.0);  // the low 11 bits are dropped
}

}  // namespace
}  // namespace mjarm
