// The bimanual panel's widgets without a window: every item is bound to the TeleopPanel value of
// its name (no second copy of the state), item names map to the actions the viewer takes, the
// slider ranges hold the initial targets, the overlay texts show each hand, and the script
// accepts the bimanual names and keys.
#include "teleop/teleop_ui.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "mjarm/teleop/viewer_script.hpp"
#include "support/error_message.hpp"
#include "teleop/viewer_overlay.hpp"

namespace mjarm {
namespace {

class TeleopUiTest : public ::testing::Test {
 protected:
  TeleopUiTest()
      : session_(Robot::bundled("dual_arm")),
        panel_(teleop_panel(session_)),
        ranges_(teleop_ranges(session_, 300)) {}
  TeleopSession session_;
  TeleopPanel panel_;
  std::vector<PanelRanges> ranges_;
};

TEST_F(TeleopUiTest, ItemsAreBoundToThePanelValueOfTheirName) {
  const auto ui = make_teleop_ui(panel_, session_, ranges_);
  ASSERT_EQ(ui->ui().nsect, 4);  // Simulation, Left hand, Right hand, Camera
  EXPECT_STREQ(ui->ui().sect[1].name, "Left hand");
  EXPECT_STREQ(ui->ui().sect[2].name, "Right hand");
  const char* pose[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
  for (std::size_t h = 0; h < 2; ++h) {
    const std::string hand = session_.hands()[h].name;
    for (int k = 0; k < 6; ++k) {
      const mjuiItem* it = ui->item(hand + "." + pose[k]);
      ASSERT_NE(it, nullptr) << hand << "." << pose[k];
      EXPECT_EQ(it->pdata, &panel_.hands[h].pose[k]);
      EXPECT_EQ(ui->action(it), PanelAction::target);
      EXPECT_EQ(ui->name_of(it), hand + "." + pose[k]);
      // the initial target lies inside its slider's range
      EXPECT_LE(it->slider.range[0], panel_.hands[h].pose[k]);
      EXPECT_GE(it->slider.range[1], panel_.hands[h].pose[k]);
    }
    const mjuiItem* gripper = ui->item(hand + ".gripper");
    ASSERT_NE(gripper, nullptr);
    EXPECT_EQ(gripper->pdata, &panel_.hands[h].gripper);
    EXPECT_EQ(gripper->state, 1);  // dual_arm has fingers
  }
  // every value name of the panel that is a widget is an item bound to it
  EXPECT_EQ(ui->item("lift")->pdata, &panel_.lift);
  EXPECT_EQ(ui->item("mode")->pdata, &panel_.mode);
  EXPECT_EQ(ui->item("priority")->pdata, &panel_.priority);
  EXPECT_EQ(ui->item("hand")->pdata, &panel_.selected);
  EXPECT_EQ(ui->item("camera.azimuth")->pdata, &panel_.camera.azimuth);
  EXPECT_EQ(ui->item("camera.lookat_z")->pdata, &panel_.camera.lookat[2]);
  EXPECT_EQ(ui->item("camera.preset")->pdata, &panel_.camera.preset);
  for (const std::string& name : teleop_value_names(session_))
    EXPECT_NE(ui->item(name), nullptr) << name << " has no widget";
  EXPECT_EQ(ui->item("hand")->multi.nelem, 2);
  EXPECT_STREQ(ui->item("hand")->multi.name[1], "Right");
  EXPECT_STREQ(ui->item("mode")->multi.name[2], "Motor");
  // actions by name
  EXPECT_EQ(ui->action(ui->item("mode")), PanelAction::mode);
  EXPECT_EQ(ui->action(ui->item("priority")), PanelAction::priority);
  EXPECT_EQ(ui->action(ui->item("hand")), PanelAction::hand);
  EXPECT_EQ(ui->action(ui->item("camera.distance")), PanelAction::camera);
  EXPECT_EQ(ui->action(ui->item("camera.preset")), PanelAction::camera_preset);
  EXPECT_EQ(ui->action(ui->item("lift")), PanelAction::target);
  EXPECT_EQ(ui->action(ui->item("pause")), PanelAction::pause);
  EXPECT_EQ(ui->action(ui->item("step")), PanelAction::step);
  EXPECT_EQ(ui->action(ui->item("reset")), PanelAction::reset);
  // a named edit and a nudge write the numbers the widgets show
  set_teleop_value(panel_, session_, "right.z", "1.3");
  EXPECT_DOUBLE_EQ(*static_cast<const double*>(ui->item("right.z")->pdata), 1.3);
  panel_.selected = 1;
  ASSERT_TRUE(nudge(panel_, 'R', false));
  EXPECT_DOUBLE_EQ(*static_cast<const double*>(ui->item("right.z")->pdata), 1.31);
}

TEST_F(TeleopUiTest, MismatchedPanelsAndSectionsAreRefused) {
  TeleopPanel one = panel_;
  one.hands.pop_back();
  EXPECT_NE(test::error_of([&] {
              make_teleop_ui(one, session_, ranges_);
            }).find("1 hand sections and 2 slider ranges for 2 hands"),
            std::string::npos);
  ViewerUi ui;
  double v = 0.0;
  ui.add_section("A", {{mjITEM_SLIDERNUM, "v", 1, &v, "0 1", "v"}});
  EXPECT_NE(test::error_of([&] {
              ui.add_section("B", {{mjITEM_SLIDERNUM, "w", 1, &v, "0 1", "v"}});
            }).find("two items called 'v'"),
            std::string::npos);
}

TEST_F(TeleopUiTest, OverlayShowsEachHand) {
  OverlayInfo info;
  info.fps = 30.0;
  info.speed = 1.0;
  info.note = "a note";
  OverlayText common, hands;
  panel_.selected = 1;
  panel_.priority = 1;
  session_.set_mode(SimulationMode::position);
  session_.step(5);
  format_teleop_overlay(session_.stats(), session_.hands(), panel_, info, common, hands);
  EXPECT_NE(common.labels.find("Lift"), std::string::npos);
  EXPECT_NE(common.values.find("right over left"), std::string::npos);
  EXPECT_NE(common.values.find("a note"), std::string::npos);
  // one block of lines per hand, the selected one marked
  auto count = [](const std::string& s, const std::string& what) {
    int n = 0;
    for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count(hands.labels, "tracking"), 2);
  EXPECT_EQ(count(hands.labels, "grasp force"), 2);
  EXPECT_EQ(count(hands.labels, "saturated"), 2);
  EXPECT_EQ(count(hands.labels, "contacts"), 2);
  EXPECT_EQ(count(hands.labels, "IK"), 2);
  EXPECT_EQ(count(hands.values, "[keys]"), 1);
  EXPECT_EQ(count(hands.labels, "\n"), count(hands.values, "\n"));  // the columns line up
  EXPECT_LT(hands.labels.find("left hand"), hands.labels.find("right hand"));
  EXPECT_NE(hands.values.find("converged"), std::string::npos);
}

TEST(TeleopScript, BimanualNamesAndKeysParse) {
  const ViewerScript s = ViewerScript::parse(
      "set left.z 1.2\nslider right.gripper 0.5\nset priority left-over-right\nkey tab\n"
      "key shift+w\nkey g\nslider camera.azimuth 0.1\n");
  ASSERT_EQ(s.commands.size(), 7u);
  EXPECT_EQ(s.commands[3].name, "tab");
  EXPECT_EQ(viewer_key_code("tab"), 258);
  EXPECT_EQ(s.commands[4].name, "w");
  EXPECT_EQ(s.commands[4].value, "shift");
  EXPECT_EQ(viewer_key_code(s.commands[4].name), 'W');
  auto message = [](const std::string& text) {
    return test::error_of([&] { ViewerScript::parse(text, "b.txt"); });
  };
  EXPECT_NE(message("key shift+space").find("b.txt:1: unknown key 'shift+space'"),
            std::string::npos);
  EXPECT_NE(message("key q").find("unknown key 'q'"), std::string::npos);
  EXPECT_NE(message("slider priority 0.5").find("unknown slider 'priority'"), std::string::npos);
  EXPECT_NE(message("slider camera.preset 0.5").find("unknown slider"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
