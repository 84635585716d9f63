// The scripted bimanual task end to end through the session code: both hands grasp the bar of
// dual_arm_box by its ends and lift it 0.2 m without dropping it, in position and in motor mode;
// the recorded session replays headless to the same state bit for bit.
#include "mjarm/teleop/bimanual_lift.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

class BimanualLift : public ::testing::TestWithParam<SimulationMode> {};

TEST_P(BimanualLift, BothHandsLiftTheBarAndTheReplayMatches) {
  const Robot robot = Robot::bundled("dual_arm_box");
  TeleopOptions o;
  o.mode = GetParam();
  TeleopSession session(robot, o);
  SessionRecorder recorder(session);
  const BimanualLiftResult r = run_bimanual_lift(recorder);
  EXPECT_TRUE(r.success) << r.failure;
  EXPECT_NEAR(r.lifted, 0.2, 0.01);
  EXPECT_LT(r.sag, 0.005);
  // both hands squeeze the bar at the end
  EXPECT_GT(r.grasp_force[0], 1.0);
  EXPECT_GT(r.grasp_force[1], 1.0);
  EXPECT_TRUE(session.stats().hands[0].touching);
  EXPECT_TRUE(session.stats().hands[1].touching);
  // the recorded session replays to the same final state, bit for bit
  const SessionLog log = recorder.log();
  EXPECT_EQ(log.ticks, r.ticks);
  const ReplayResult replay = replay_session(robot, log);
  EXPECT_TRUE(replay.matches) << replay.digest << " vs " << log.digest;
  EXPECT_EQ(replay.ticks, log.ticks);
}

INSTANTIATE_TEST_SUITE_P(Modes, BimanualLift,
                         ::testing::Values(SimulationMode::position, SimulationMode::torque),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(BimanualLiftInput, NeedsTwoHandsAndAFreeObject) {
  TeleopSession one(Robot::bundled("panda_hand"));
  SessionRecorder r1(one);
  EXPECT_NE(test::error_of([&] { run_bimanual_lift(r1); }).find("needs two hands"),
            std::string::npos);
  TeleopSession two(Robot::bundled("dual_arm"));
  SessionRecorder r2(two);
  EXPECT_NE(test::error_of([&] { run_bimanual_lift(r2); }).find("bar"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
