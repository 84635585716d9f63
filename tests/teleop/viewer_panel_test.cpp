// The viewer's window-free pieces: panel state ↔ target mapping, named edits, the panel
// definition (mjui without OpenGL), scripts and overlay text. The target filter is tested in
// tests/trajectory/target_filter_test.cpp.
#include "mjarm/teleop/viewer_panel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/teleop/viewer_script.hpp"
#include "teleop/viewer_overlay.hpp"
#include "teleop/viewer_ui.hpp"

namespace mjarm {
namespace {

constexpr double kPi = std::numbers::pi;

Pose pose(double x, double y, double z, double roll, double pitch, double yaw) {
  return Pose::from_rpy(Eigen::Vector3d(x, y, z), Eigen::Vector3d(roll, pitch, yaw));
}

TEST(ViewerPanel, TargetRoundTripsThroughTheSliders) {
  PanelRanges ranges;  // defaults: roll, yaw in [−π, π]
  for (const Pose& X :
       {pose(0.3, -0.1, 0.5, 0.2, -0.4, 1.0), pose(0.0, 0.2, 0.7, -3.0, 0.1, 2.9)}) {
    const PanelState state = panel_state(X, ranges, 0.25, SimulationMode::position);
    const Pose back = panel_target(state);
    EXPECT_TRUE(back.is_approx(X, 1e-12));
    EXPECT_DOUBLE_EQ(state.gripper, 0.25);
    EXPECT_EQ(panel_mode(state), SimulationMode::position);
  }
}

TEST(ViewerPanel, AnglesAreUnwrappedIntoTheSliderRange) {
  // an end effector pointing down has roll ≈ ±π: the ranges centre it, whichever sign comes out
  PanelRanges ranges;
  ranges.lower[slider_roll] = kPi - kPi;
  ranges.upper[slider_roll] = kPi + kPi;
  const Pose down = pose(0.3, 0.0, 0.5, -kPi + 1e-3, 0.0, 0.0);  // rpy gives roll near −π
  const PanelState state = panel_state(down, ranges, 0.0, SimulationMode::kinematic);
  EXPECT_GE(state.target[slider_roll], ranges.lower[slider_roll]);
  EXPECT_LE(state.target[slider_roll], ranges.upper[slider_roll]);
  EXPECT_TRUE(panel_target(state).is_approx(down, 1e-12));
}

TEST(ViewerPanel, RangesComeFromTheWorkspaceAndCentreTheInitialPose) {
  const Chain chain(Robot::bundled("panda"), "attachment_site");
  const Pose X0 = pose(0.3, 0.0, 0.5, kPi, 0.0, 0.0);
  const PanelRanges r = panel_ranges(chain, X0, 500);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(r.lower[i], X0.p[i]);
    EXPECT_GT(r.upper[i], X0.p[i]);
    EXPECT_GT(r.upper[i] - r.lower[i], 1.0) << i;  // the panda reaches ~0.85 m around its base
    EXPECT_LT(r.upper[i] - r.lower[i], 2.5) << i;
  }
  const Eigen::Vector3d rpy = rpy_from_rotation(X0.R);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(0.5 * (r.lower[3 + i] + r.upper[3 + i]), rpy[i], 1e-12);
  }
  EXPECT_THROW(panel_ranges(chain, X0, 0), Error);
}

TEST(ViewerPanel, NamedEditsAreCheckedAgainstTheSliders) {
  PanelRanges ranges;
  PanelState state;
  set_panel_value(state, ranges, "x", "0.4");
  set_panel_value(state, ranges, "yaw", "-1.5");
  set_panel_value(state, ranges, "gripper", "1");
  set_panel_value(state, ranges, "mode", "torque");
  EXPECT_DOUBLE_EQ(state.target[slider_x], 0.4);
  EXPECT_DOUBLE_EQ(state.target[slider_yaw], -1.5);
  EXPECT_DOUBLE_EQ(state.gripper, 1.0);
  EXPECT_EQ(panel_mode(state), SimulationMode::torque);

  auto message = [&](std::string_view name, std::string_view value) {
    try {
      set_panel_value(state, ranges, name, value);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("height", "1").find("values: x, y, z, roll, pitch, yaw, gripper, mode"),
            std::string::npos);
  EXPECT_NE(message("x", "abc").find("finite number"), std::string::npos);
  EXPECT_NE(message("x", "nan").find("finite number"), std::string::npos);
  EXPECT_NE(message("x", "0.4m").find("finite number"), std::string::npos);
  EXPECT_NE(message("z", "7").find("outside its slider range [0, 1]"), std::string::npos);
  EXPECT_NE(message("gripper", "-0.1").find("outside"), std::string::npos);
  EXPECT_NE(message("mode", "fast").find("kinematic, position, torque"), std::string::npos);
  EXPECT_DOUBLE_EQ(state.target[slider_x], 0.4);  // failed edits change nothing
  state.mode = 7;
  EXPECT_THROW(panel_mode(state), Error);
}

TEST(ViewerUi, PanelItemsAreBoundToThePanelState) {
  PanelState state;
  PanelRanges ranges;
  ViewerUi ui(state, ranges, /*gripper=*/false);
  const mjUI& m = ui.ui();
  ASSERT_EQ(m.nsect, 2);
  const char* names[] = {"x", "y", "z", "roll", "pitch", "yaw", "gripper"};
  for (int i = 0; i < 7; ++i) {
    const mjuiItem* it = ui.item(names[i]);
    ASSERT_NE(it, nullptr) << names[i];
    EXPECT_EQ(it->type, mjITEM_SLIDERNUM);
    EXPECT_EQ(it->pdata, i < 6 ? static_cast<void*>(&state.target[i]) : &state.gripper);
    EXPECT_EQ(ui.action(it), PanelAction::target);
    if (i < 6) {
      EXPECT_DOUBLE_EQ(it->slider.range[0], ranges.lower[i]);
      EXPECT_DOUBLE_EQ(it->slider.range[1], ranges.upper[i]);
    }
  }
  EXPECT_EQ(ui.item("gripper")->state, 0);  // no gripper: disabled
  const mjuiItem* mode = ui.item("mode");
  ASSERT_NE(mode, nullptr);
  EXPECT_EQ(mode->type, mjITEM_RADIO);
  EXPECT_EQ(mode->pdata, &state.mode);
  ASSERT_EQ(mode->multi.nelem, 3);
  EXPECT_STREQ(mode->multi.name[2], "Torque");
  EXPECT_EQ(ui.action(mode), PanelAction::mode);
  EXPECT_EQ(ui.action(nullptr), PanelAction::none);
  const mjuiSection& sim = m.sect[1];
  EXPECT_EQ(ui.action(&sim.item[1]), PanelAction::pause);
  EXPECT_EQ(ui.action(&sim.item[2]), PanelAction::step);
  EXPECT_EQ(ui.action(&sim.item[3]), PanelAction::reset);
  EXPECT_EQ(ui.item("nonsense"), nullptr);
  EXPECT_FALSE(ui.slider_point("x", 0.5).has_value());  // no geometry before attach

  // layout and pointer bookkeeping work without OpenGL
  ui.layout(800, 600);
  ui.move_pointer(400.0, 300.0);
  EXPECT_EQ(ui.input().mouserect, rect_view);  // the panel has no width before attach
  ui.move_pointer(450.0, 280.0);
  EXPECT_DOUBLE_EQ(ui.input().dx, 50.0);
  EXPECT_DOUBLE_EQ(ui.input().dy, -20.0);
  ui.move_pointer(900.0, 300.0);
  EXPECT_EQ(ui.input().mouserect, 0);  // outside every rectangle
}

TEST(ViewerScript, ParsesEveryCommand) {
  const ViewerScript script = ViewerScript::parse(
      "# a test session\n"
      "wait 10\n"
      "set x 0.45   # metres\n"
      "set mode torque\n"
      "slider gripper 0.75\n"
      "key space\n"
      "drag left 40 -20\n"
      "scroll 2\n"
      "\n"
      "screenshot out/a.png\n"
      "quit\n");
  ASSERT_EQ(script.commands.size(), 9u);
  const auto& c = script.commands;
  EXPECT_EQ(c[0].action, ScriptAction::wait);
  EXPECT_EQ(c[0].frames, 10);
  EXPECT_EQ(c[0].line, 2);
  EXPECT_EQ(c[1].action, ScriptAction::set);
  EXPECT_EQ(c[1].name, "x");
  EXPECT_EQ(c[1].value, "0.45");
  EXPECT_EQ(c[2].value, "torque");
  EXPECT_EQ(c[3].action, ScriptAction::slider);
  EXPECT_DOUBLE_EQ(c[3].x, 0.75);
  EXPECT_EQ(c[4].action, ScriptAction::key);
  EXPECT_EQ(viewer_key_code(c[4].name), 32);
  EXPECT_EQ(c[5].action, ScriptAction::drag);
  EXPECT_EQ(c[5].name, "left");
  EXPECT_DOUBLE_EQ(c[5].x, 40.0);
  EXPECT_DOUBLE_EQ(c[5].y, -20.0);
  EXPECT_DOUBLE_EQ(c[6].x, 2.0);
  EXPECT_EQ(c[7].action, ScriptAction::screenshot);
  EXPECT_EQ(c[7].name, "out/a.png");
  EXPECT_EQ(c[7].line, 10);
  EXPECT_EQ(c[8].action, ScriptAction::quit);
}

TEST(ViewerScript, ErrorsNameTheLine) {
  auto message = [](std::string_view text) {
    try {
      ViewerScript::parse(text, "s.txt");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("wait 1\njump 3\n").rfind("s.txt:2: unknown command 'jump'", 0), 0u)
      << message("wait 1\njump 3\n");
  // the closest command, as for an unknown key in every file mjarm reads (issue 29, item 1)
  EXPECT_EQ(message("wiat 3\n"),
            "s.txt:1: unknown command 'wiat'; closest: wait; commands: wait, "
            "set, slider, key, drag, scroll, select, press, move, release, screenshot, quit");
  EXPECT_NE(message("drag lefft 1 2").find("unknown mouse button 'lefft'; closest: left"),
            std::string::npos);
  EXPECT_NE(message("wait -1").find("s.txt:1: the frame count must be a whole number"),
            std::string::npos);
  EXPECT_NE(message("wait 1.5").find("whole number"), std::string::npos);
  // a wait beyond the bound names the bound, not only "a whole number"
  EXPECT_EQ(message("wait 100000000"),
            "s.txt:1: the frame count 1e+08 is more than the bound of 10⁷ frames");
  EXPECT_EQ(message("wait 10000000"), "no error");
  EXPECT_NE(message("set x").find("takes a name and a value"), std::string::npos);
  EXPECT_NE(message("set height 2").find("unknown panel value 'height'"), std::string::npos);
  EXPECT_NE(message("slider mode 0.5").find("unknown slider 'mode'"), std::string::npos);
  EXPECT_NE(message("slider x 1.5").find("[0, 1]"), std::string::npos);
  EXPECT_NE(message("key enter").find("unknown key 'enter'"), std::string::npos);
  EXPECT_NE(message("drag up 1 2").find("unknown mouse button 'up'"), std::string::npos);
  EXPECT_NE(message("drag left 1 inf").find("DY must be a finite number"), std::string::npos);
  EXPECT_NE(message("quit now").find("takes no argument"), std::string::npos);
  EXPECT_THROW(ViewerScript::load("/nonexistent/script.txt"), Error);
  EXPECT_THROW(ViewerScript::load("/dev/zero"), Error);  // refused, not read forever
}

TEST(ViewerOverlay, ShowsTrackingSaturationContactsAndRate) {
  const Robot robot = Robot::bundled("panda");
  ViewerStats stats;
  stats.mode = SimulationMode::torque;
  stats.time = 1.5;
  stats.tracking_position = 0.0042;
  stats.tracking_orientation = 0.01;
  stats.contacts.contacts = 2;
  stats.contacts.normal_force = 12.34;
  std::vector<std::uint8_t> saturated(static_cast<std::size_t>(robot.nu()), 0);
  saturated[3] = 1;
  OverlayInfo info;
  info.fps = 59.94;
  info.speed = 0.98;
  OverlayText text;
  format_overlay(stats, info, robot.model(), saturated, text);
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  EXPECT_EQ(lines(text.labels), lines(text.values));  // one value per label
  EXPECT_NE(text.labels.find("Tracking error"), std::string::npos);
  EXPECT_NE(text.values.find("4.2 mm  0.57 deg"), std::string::npos) << text.values;
  EXPECT_NE(text.values.find("1 of 7: joint4"), std::string::npos) << text.values;
  EXPECT_NE(text.values.find("2, normal force 12.3 N"), std::string::npos) << text.values;
  EXPECT_NE(text.values.find("59.9 fps"), std::string::npos);
  EXPECT_NE(text.values.find("1.50 s  (speed 0.98x)"), std::string::npos);
  EXPECT_EQ(text.labels.find("FAULT"), std::string::npos);

  stats.mode = SimulationMode::kinematic;
  stats.contacts.forces_valid = false;
  stats.faulted = true;
  stats.fault = "t = 1 s: diverged";
  info.paused = true;
  format_overlay(stats, info, robot.model(), saturated, text);
  EXPECT_NE(text.values.find("kinematic  (paused)"), std::string::npos);
  EXPECT_NE(text.values.find("n/a (kinematic)"), std::string::npos);
  EXPECT_NE(text.values.find("2 (forces n/a"), std::string::npos);
  EXPECT_NE(text.labels.find("FAULT"), std::string::npos);
  EXPECT_EQ(lines(text.labels), lines(text.values));
}

TEST(RateMeter, MeasuresOverWindows) {
  RateMeter meter(0.5);
  EXPECT_DOUBLE_EQ(meter.rate(), 0.0);
  for (int k = 0; k <= 60; ++k) meter.add(k / 60.0);  // 60 events per second for 1 s
  EXPECT_NEAR(meter.rate(), 60.0, 1.0);
  RateMeter amounts(1.0);
  for (int k = 0; k <= 100; ++k) amounts.add(k * 0.01, 0.005);  // 0.5 units per second
  EXPECT_NEAR(amounts.rate(), 0.5, 0.01);
}

}  // namespace
}  // namespace mjarm
