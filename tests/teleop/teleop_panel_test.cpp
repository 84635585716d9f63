// The bimanual panel without a window: it starts at the session's targets, its targets round-trip
// the orientation sliders, named edits and keyboard nudges move the right values, the priority
// choices give the tasks they name, and bad edits are clear errors.
#include "mjarm/teleop/teleop_panel.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/lie/so3.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

class TeleopPanelTest : public ::testing::Test {
 protected:
  TeleopPanelTest() : session_(Robot::bundled("dual_arm")), panel_(teleop_panel(session_)) {}
  TeleopSession session_;
  TeleopPanel panel_;
};

TEST_F(TeleopPanelTest, StartsAtTheSessionTargets) {
  ASSERT_EQ(panel_.hands.size(), 2u);
  const TeleopTargets t = panel_targets(panel_);
  for (int i = 0; i < 2; ++i) {
    const Pose& X = session_.initial_targets().hands[i].X_WT;
    EXPECT_LT((t.hands[i].X_WT.p - X.p).norm(), 1e-12);
    EXPECT_LT(so3::angle(t.hands[i].X_WT.R.transpose() * X.R), 1e-9);
  }
  EXPECT_DOUBLE_EQ(panel_.lift, 0.2);
  EXPECT_EQ(panel_.mode, static_cast<int>(SimulationMode::position));
  // the camera looks at the middle between the hands, 10 cm lower
  EXPECT_NEAR(panel_.camera.lookat[1], 0.0, 1e-9);
  EXPECT_NEAR(panel_.camera.lookat[2], session_.stats().hands[0].X_WE.p.z() - 0.1, 1e-9);
}

TEST_F(TeleopPanelTest, NamedEditsAndPresets) {
  set_teleop_value(panel_, session_, "right.z", "1.05");
  set_teleop_value(panel_, session_, "left.yaw", "1.5");
  set_teleop_value(panel_, session_, "left.gripper", "1");
  set_teleop_value(panel_, session_, "lift", "0.35");
  set_teleop_value(panel_, session_, "hand", "right");
  set_teleop_value(panel_, session_, "mode", "torque");
  set_teleop_value(panel_, session_, "priority", "right-over-left");
  EXPECT_DOUBLE_EQ(panel_.hands[1].pose[2], 1.05);
  EXPECT_DOUBLE_EQ(panel_.hands[0].pose[5], 1.5);
  EXPECT_DOUBLE_EQ(panel_.hands[0].gripper, 1.0);
  EXPECT_DOUBLE_EQ(panel_.lift, 0.35);
  EXPECT_EQ(panel_.selected, 1);
  EXPECT_EQ(panel_.mode, 2);
  const auto tasks = priority_tasks(session_, static_cast<TeleopPriority>(panel_.priority));
  EXPECT_EQ(tasks[1].kind, TargetKind::pose);  // right pose first
  EXPECT_EQ(tasks[1].priority, 0);
  EXPECT_EQ(tasks[0].kind, TargetKind::position);  // left position second
  EXPECT_EQ(tasks[0].priority, 1);
  set_teleop_value(panel_, session_, "camera.preset", "top");
  EXPECT_LT(panel_.camera.elevation, -80.0);
  set_teleop_value(panel_, session_, "camera.azimuth", "30");
  set_teleop_value(panel_, session_, "camera.lookat_y", "0.5");
  EXPECT_DOUBLE_EQ(panel_.camera.azimuth, 30.0);
  EXPECT_DOUBLE_EQ(panel_.camera.lookat[1], 0.5);
  // the targets take the edits: right hand 1.05 m high, left hand turned to yaw 1.5
  const TeleopTargets t = panel_targets(panel_);
  EXPECT_DOUBLE_EQ(t.hands[1].X_WT.p.z(), 1.05);
  EXPECT_NEAR(rpy_from_rotation(t.hands[0].X_WT.R)[2], 1.5, 1e-9);
}

TEST_F(TeleopPanelTest, KeyboardNudgesTheSelectedHand) {
  const TeleopPanel before = panel_;
  EXPECT_TRUE(nudge(panel_, 'W', false));  // left hand +1 cm in x
  EXPECT_NEAR(panel_.hands[0].pose[0] - before.hands[0].pose[0], 0.01, 1e-12);
  EXPECT_EQ(panel_.hands[1].pose[0], before.hands[1].pose[0]);
  EXPECT_TRUE(nudge(panel_, 258, false));  // TAB: the right hand
  EXPECT_EQ(panel_.selected, 1);
  EXPECT_TRUE(nudge(panel_, 'F', false));  // right hand 1 cm down
  EXPECT_NEAR(panel_.hands[1].pose[2] - before.hands[1].pose[2], -0.01, 1e-12);
  EXPECT_TRUE(nudge(panel_, 'R', true));  // shift: yaw +5°
  EXPECT_NEAR(panel_.hands[1].pose[5] - before.hands[1].pose[5], 0.087, 1e-12);
  EXPECT_TRUE(nudge(panel_, 'G', false));
  EXPECT_EQ(panel_.hands[1].gripper, 1.0);
  EXPECT_FALSE(nudge(panel_, 'Z', false));
  EXPECT_TRUE(nudge(panel_, 258, false));  // wraps to the left hand
  EXPECT_EQ(panel_.selected, 0);
}

TEST_F(TeleopPanelTest, BadEditsAreClearErrors) {
  auto message = [&](const char* name, const char* value) {
    return test::error_of([&] { set_teleop_value(panel_, session_, name, value); });
  };
  EXPECT_NE(message("left.x", "far").find("finite number"), std::string::npos);
  EXPECT_NE(message("left.gripper", "2").find("within [0, 1], got 2"), std::string::npos);
  EXPECT_NE(message("lift", "0.9").find("lift"), std::string::npos);
  EXPECT_NE(message("camera.elevation", "95").find("camera.elevation"), std::string::npos);
  EXPECT_NE(message("camera.preset", "side").find("front, left, right, top, overview"),
            std::string::npos);
  EXPECT_NE(message("mode", "fast").find("kinematic, position, torque"), std::string::npos);
  EXPECT_NE(message("hand", "middle").find("no hand called 'middle'"), std::string::npos);
  EXPECT_NE(message("elbow.x", "0").find("values: left.x"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
