// The bimanual session without a window: hands found on dual_arm, each mode brings both hands to
// targets moved on their own, priorities decide a conflict, the fingers follow their commands,
// a tick allocates nothing, and bad input is refused.
#include "mjarm/teleop/teleop_session.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

void run_seconds(TeleopSession& session, double seconds) {
  const int ticks = static_cast<int>(std::lround(seconds / session.control_period()));
  ASSERT_EQ(session.step(ticks), ticks) << session.stats().fault;
}

// the initial targets with the left hand moved by dl and the right by dr [m]
TeleopTargets moved(const TeleopSession& s, const Eigen::Vector3d& dl, const Eigen::Vector3d& dr) {
  TeleopTargets t = s.initial_targets();
  t.hands[0].X_WT.p += dl;
  t.hands[1].X_WT.p += dr;
  return t;
}

TEST(TeleopSession, DualArmHasTwoHandsWithFingersAndALift) {
  const Robot robot = Robot::bundled("dual_arm");
  const auto hands = find_teleop_hands(robot);
  ASSERT_EQ(hands.size(), 2u);
  EXPECT_EQ(hands[0].name, "left");
  EXPECT_EQ(hands[0].frame, "left_tcp");
  EXPECT_EQ(hands[0].fingers, (std::vector<std::string>{"left_finger_left", "left_finger_right"}));
  EXPECT_EQ(hands[1].frame, "right_tcp");
  TeleopSession session(robot);
  EXPECT_TRUE(session.has_lift());
  EXPECT_DOUBLE_EQ(session.lift_range()[1], 0.5);
  for (int m = 0; m < 3; ++m)
    EXPECT_TRUE(session.available(static_cast<SimulationMode>(m)))
        << session.unavailable_reason(static_cast<SimulationMode>(m));
  // home: both tool frames 0.357 m ahead, ±0.25 m aside, pointing down; lift at 0.2 m
  const TeleopStats& s = session.stats();
  EXPECT_NEAR(s.hands[0].X_WE.p.x(), 0.357, 1e-3);
  EXPECT_NEAR(s.hands[0].X_WE.p.y(), 0.25, 1e-3);
  EXPECT_NEAR(s.hands[1].X_WE.p.y(), -0.25, 1e-3);
  EXPECT_NEAR(s.lift, 0.2, 1e-9);
}

TEST(TeleopSession, PandaHandHasOneHandNamedHand) {
  const auto hands = find_teleop_hands(Robot::bundled("panda_hand"));
  ASSERT_EQ(hands.size(), 1u);
  EXPECT_EQ(hands[0].name, "hand");
  EXPECT_EQ(hands[0].fingers.size(), 2u);
  EXPECT_NE(
      test::error_of([] { find_teleop_hands(Robot::bundled("panda")); }).find("no hand frame"),
      std::string::npos);
}

// one hand, no lift: the session is not only for two
TEST(TeleopSession, OneHandedPandaReachesItsTarget) {
  TeleopSession session(Robot::bundled("panda_hand"));
  EXPECT_FALSE(session.has_lift());
  TeleopTargets t = session.initial_targets();
  t.hands[0].X_WT.p += Eigen::Vector3d(0.05, -0.05, -0.05);
  t.hands[0].gripper = 1.0;
  session.set_targets(t);
  run_seconds(session, 2.0);
  EXPECT_LT((session.stats().hands[0].X_WE.p - t.hands[0].X_WT.p).norm(), 3e-3);
  EXPECT_DOUBLE_EQ(session.stats().hands[0].gripper, 1.0);
}

// every mode: the two hands go to different targets (left 10 cm forward and down, right 10 cm
// aside and up), the lift rises 5 cm, and the grippers close
TEST(TeleopSession, EveryModeReachesBothHandTargetsAndTheLift) {
  const Robot robot = Robot::bundled("dual_arm");
  for (int m = 0; m < 3; ++m) {
    TeleopOptions o;
    o.mode = static_cast<SimulationMode>(m);
    TeleopSession session(robot, o);
    TeleopTargets t = moved(session, {0.1, 0.0, -0.1}, {0.0, -0.1, 0.1});
    t.lift = 0.25;
    t.hands[0].gripper = 1.0;
    t.hands[1].gripper = 0.5;
    session.set_targets(t);
    run_seconds(session, 2.5);
    const TeleopStats& s = session.stats();
    SCOPED_TRACE(to_string(session.mode()));
    ASSERT_FALSE(s.faulted) << s.fault;
    // the hand targets are world poses: the lift's rise is taken up by the arms
    for (int i = 0; i < 2; ++i) {
      EXPECT_LT((s.hands[i].X_WE.p - t.hands[i].X_WT.p).norm(), 3e-3) << i;
      EXPECT_LT(so3::angle(s.hands[i].X_WE.R.transpose() * t.hands[i].X_WT.R), 1e-2) << i;
      EXPECT_EQ(s.hands[i].ik_status, IkStatus::converged) << i;
    }
    EXPECT_NEAR(s.lift, 0.25, 2e-3);
    EXPECT_DOUBLE_EQ(s.hands[0].gripper, 1.0);
    EXPECT_DOUBLE_EQ(s.hands[1].gripper, 0.5);
    // the fingers follow: closed on the left (0 m), half open on the right (0.02 m)
    const mjData& d = session.simulation().data();
    const mjModel& mm = session.robot().model();
    auto finger = [&](const char* name) {
      return d.qpos[mm.jnt_qposadr[mj_name2id(&mm, mjOBJ_JOINT, name)]];
    };
    EXPECT_NEAR(finger("left_finger_left"), 0.0, 2e-3);
    EXPECT_NEAR(finger("right_finger_right"), 0.02, 2e-3);
  }
}

// a conflict through the shared lift: the left hand asked high, the right hand low, both at the
// edge of their arm's reach; the hand first in priority gets there, the other comes short
TEST(TeleopSession, PriorityDecidesAConflict) {
  const Robot robot = Robot::bundled("dual_arm");
  for (const int first : {0, 1}) {
    TeleopOptions o;
    o.mode = SimulationMode::kinematic;
    o.lift_in_ik = true;
    o.tasks = {HandTask{TargetKind::position, first == 0 ? 0 : 1},
               HandTask{TargetKind::position, first == 1 ? 0 : 1}};
    TeleopSession session(robot, o);
    TeleopTargets t = session.initial_targets();
    t.hands[0].X_WT.p = Eigen::Vector3d(0.35, 0.25, 2.2);
    t.hands[1].X_WT.p = Eigen::Vector3d(0.55, -0.25, 0.45);
    session.set_targets(t);
    run_seconds(session, 3.0);
    const TeleopStats& s = session.stats();
    const double e_first = (s.hands[first].X_WE.p - t.hands[first].X_WT.p).norm();
    const double e_second = (s.hands[1 - first].X_WE.p - t.hands[1 - first].X_WT.p).norm();
    EXPECT_LT(e_first, 0.01) << "first " << first;
    EXPECT_LT(e_first, e_second) << "first " << first;
    EXPECT_GT(e_second, 0.02) << "first " << first;
  }
}

TEST(TeleopSession, ModeSwitchKeepsTheStateAndTicksAllocateNothing) {
  TeleopSession session(Robot::bundled("dual_arm"));
  session.set_targets(moved(session, {0.05, 0.0, 0.0}, {0.0, 0.0, 0.05}));
  run_seconds(session, 0.3);
  for (const auto mode :
       {SimulationMode::torque, SimulationMode::kinematic, SimulationMode::position}) {
    const mjData& from = session.simulation().data();
    const std::vector<double> before(from.qpos, from.qpos + session.robot().nq());
    session.set_mode(mode);
    const mjData& to = session.simulation().data();
    EXPECT_EQ(std::vector<double>(to.qpos, to.qpos + session.robot().nq()), before);
    session.step(2);  // warm-up (first ticks after a switch)
    const std::uint64_t calls = test::malloc_calls();
    ASSERT_EQ(session.step(20), 20) << session.stats().fault;
    EXPECT_EQ(test::malloc_calls(), calls) << to_string(mode);
  }
}

TEST(TeleopSession, KinematicModeRollsBackAMoveIntoTheTable) {
  TeleopOptions o;
  o.mode = SimulationMode::kinematic;
  TeleopSession session(Robot::bundled("dual_arm_box"), o);
  TeleopTargets t = session.initial_targets();
  t.hands[0].X_WT.p = Eigen::Vector3d(0.45, 0.25, 0.85);  // 10 cm into the table
  session.set_targets(t);
  run_seconds(session, 2.0);
  EXPECT_GT(session.stats().rollbacks, 0);
  EXPECT_GT(session.stats().hands[0].X_WE.p.z(), 0.95);  // stopped above the table top
}

TEST(TeleopSession, BadInputIsRefused) {
  const Robot robot = Robot::bundled("dual_arm");
  TeleopSession session(robot);
  TeleopTargets t = session.initial_targets();
  t.hands.pop_back();
  EXPECT_NE(test::error_of([&] { session.set_targets(t); }).find("targets for 1 hands"),
            std::string::npos);
  EXPECT_THROW(session.set_task(2, HandTask{}), Error);
  EXPECT_THROW(session.set_task(0, HandTask{TargetKind::pose, -1}), Error);
  TeleopOptions o;
  o.keyframe = "nope";
  EXPECT_THROW(TeleopSession(robot, o), Error);
  o = {};
  o.lift = "elevator";
  EXPECT_THROW(TeleopSession(robot, o), Error);
  // NaN targets are ignored, not taken
  TeleopTargets nan = session.initial_targets();
  nan.hands[0].X_WT.p.x() = std::nan("");
  nan.hands[0].gripper = std::nan("");
  nan.lift = std::nan("");
  session.set_targets(nan);
  EXPECT_TRUE(session.targets().hands[0].X_WT.p.allFinite());
  EXPECT_EQ(session.targets().hands[0].gripper, 0.0);
}

}  // namespace
}  // namespace mjarm
