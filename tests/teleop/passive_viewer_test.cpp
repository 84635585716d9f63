// The passive viewer on a loop of the test's own: the hand-over, the mouse's spring on a selected
// body (scripted), markers and figures in screenshots, closing; its figures' arithmetic; and the
// errors before any window opens. Window tests run under an Xvfb of the test's own.
#include "mjarm/teleop/passive_viewer.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "mjarm/error.hpp"
#include "mjarm/render/png.hpp"
#include "support/virtual_display.hpp"
#include "teleop/figure_series.hpp"
#include "teleop/passive_shared.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

// a box floating without gravity in front of the camera, and a force-limited motor on a hinge
constexpr const char* kFloatingBox = R"(
<mujoco model="floating_box">
  <option gravity="0 0 0" timestep="0.002"/>
  <worldbody>
    <light pos="0 -1 2" dir="0 0.5 -1"/>
    <body name="box" pos="0 0 0.5">
      <freejoint/>
      <geom type="box" size="0.08 0.08 0.08" rgba="0.8 0.3 0.2 1" mass="1"/>
    </body>
    <body name="pendulum" pos="0.6 0.6 0.5">
      <joint name="hinge" type="hinge" axis="0 0 1"/>
      <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="motor" joint="hinge" ctrlrange="-1 1" gear="2"/>
    <general name="clipped" joint="hinge" forcelimited="true" forcerange="-4 4"/>
  </actuator>
</mujoco>)";

// a free camera looking along +y at the box: image right is world +x
PassiveViewerOptions passive_options() {
  PassiveViewerOptions o;
  o.width = 640;
  o.height = 480;
  o.camera = CameraSpec::free_camera(Eigen::Vector3d(0.0, 0.0, 0.5), 1.2, 90.0, 0.0);
  return o;
}

// the test process's own display, set for the viewer in this process
void use_passive_display() {
  static const test::VirtualDisplay server;
  ASSERT_FALSE(server.display().empty()) << server.error();
  ::setenv("DISPLAY", server.display().c_str(), 1);
}

fs::path passive_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("mjarm_passive_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// the user's loop: steps and syncs on the wall clock until the window closes (bounded)
template <class EachStep>
void run_user_loop(PassiveViewer& viewer, const Robot& robot, mjData& d, EachStep&& each_step) {
  const auto start = std::chrono::steady_clock::now();
  const auto period = std::chrono::duration<double>(robot.model().opt.timestep);
  for (int k = 0; viewer.running(); ++k) {
    mj_step(&robot.model(), &d);
    each_step();
    viewer.sync();
    std::this_thread::sleep_until(start + k * period);
    ASSERT_LT(std::chrono::steady_clock::now() - start, std::chrono::minutes(3))
        << "the script did not end the window";
  }
}

TEST(PassiveViewerWindow, ScriptedCtrlRightDragPullsTheSelectedBodyAndTheSpringEndsWithIt) {
  use_passive_display();
  const Robot robot = Robot::from_string(kFloatingBox);
  DataPtr data = robot.make_data();
  mjData& d = *data;
  mj_forward(&robot.model(), &d);
  const int box = mj_name2id(&robot.model(), mjOBJ_BODY, "box");
  PassiveViewerOptions options = passive_options();
  // the box is selected and pulled to the right; then a plain right drag moves the camera only
  options.script = ViewerScript::parse(R"(
    wait 10
    select 0 0
    wait 5
    press ctrl+right 0 0
    move 60 0
    move 120 0
    wait 40
    release
    wait 5
    drag right 40 0
    wait 5
  )");
  PassiveViewer viewer(robot, d, options);
  double force_before_selection = 0.0, largest_force_x = 0.0, rightmost_while_pulled = 0.0;
  int selected = 0;
  run_user_loop(viewer, robot, d, [&] {
    const double fx = d.xfrc_applied[6 * box];
    if (viewer.selected_body() == 0) force_before_selection += std::abs(fx);
    selected = std::max(selected, viewer.selected_body());
    largest_force_x = std::max(largest_force_x, fx);
    // the box floats freely: after the release it drifts on with the speed it had, so the
    // verdict is where the spring took it, not where it ends
    if (fx != 0.0) rightmost_while_pulled = std::max(rightmost_while_pulled, d.qpos[0]);
  });
  viewer.close();
  EXPECT_EQ(viewer.report().ended_by, "end of script");
  EXPECT_EQ(selected, box);
  EXPECT_EQ(force_before_selection, 0.0);
  EXPECT_GT(largest_force_x, 0.0) << "the spring pulls towards the pointer: world +x";
  EXPECT_GT(rightmost_while_pulled, 0.02) << "the spring pulled the box right";
  // the spring holds the grabbed point of the front face, about which the box may swing
  // horizontally: its centre stays at the height of the drag
  EXPECT_NEAR(d.qpos[2], 0.5, 0.01);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(d.xfrc_applied[6 * box + i], 0.0) << "spring released";
  EXPECT_GT(viewer.syncs(), 0);
  EXPECT_GT(viewer.report().frames, 0);
}

TEST(PassiveViewerWindow, CtrlLeftDragTurnsTheSelectedBody) {
  use_passive_display();
  const Robot robot = Robot::from_string(kFloatingBox);
  DataPtr data = robot.make_data();
  mjData& d = *data;
  mj_forward(&robot.model(), &d);
  PassiveViewerOptions options = passive_options();
  options.script = ViewerScript::parse(R"(
    wait 10
    select 0 0
    wait 5
    press ctrl+left 0 0
    move 80 0
    move 160 0
    wait 40
    release
    wait 5
  )");
  PassiveViewer viewer(robot, d, options);
  double largest_torque = 0.0, largest_angle_while_turned = 0.0;
  run_user_loop(viewer, robot, d, [&] {
    const double torque = Eigen::Map<const Eigen::Vector3d>(d.xfrc_applied + 6 + 3).norm();
    largest_torque = std::max(largest_torque, torque);
    // where the spring turned the box (after the release it may turn on with the speed it had)
    const double angle = 2.0 * std::acos(std::min(1.0, std::abs(d.qpos[3])));
    if (torque != 0.0) largest_angle_while_turned = std::max(largest_angle_while_turned, angle);
  });
  viewer.close();
  EXPECT_GT(largest_torque, 0.0);
  EXPECT_GT(largest_angle_while_turned, 0.1) << "the box turned [rad]";
  EXPECT_LT(Eigen::Vector3d(d.qpos[0], d.qpos[1], d.qpos[2] - 0.5).norm(), 0.01)
      << "without moving away";
}

TEST(PassiveViewerWindow, MarkersAndFiguresAreDrawnInScreenshots) {
  use_passive_display();
  const Robot robot = Robot::from_string(kFloatingBox);
  DataPtr data = robot.make_data();
  mjData& d = *data;
  const fs::path dir = passive_dir("shots");
  PassiveViewerOptions options = passive_options();
  options.script = ViewerScript::parse("wait 30\nscreenshot " + (dir / "plain.png").string() +
                                       "\nset figure.plots 1\nset figure.actuators 1\nwait 5\n"
                                       "screenshot " +
                                       (dir / "figures.png").string() + "\n");
  PassiveViewer viewer(robot, d, options);
  run_user_loop(viewer, robot, d, [&] {
    d.ctrl[0] = std::sin(d.time);
    viewer.markers().add_sphere(Eigen::Vector3d(0.0, -0.2, 0.5), 0.05, {0.1f, 0.9f, 0.1f, 1.0f});
    viewer.markers().add_text(Eigen::Vector3d(0.0, -0.2, 0.6), "target");
    viewer.markers().add_frame(Pose{Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.5)});
    viewer.plot("error", std::cos(d.time));
  });
  viewer.close();
  const auto& shots = viewer.report().screenshots;
  ASSERT_EQ(shots.size(), 2u);
  const Image plain = read_png(dir / "plain.png");
  const Image figures = read_png(dir / "figures.png");
  ASSERT_EQ(plain.width, figures.width);
  // the green ball sits between the camera and the box
  auto pixel = [](const Image& image, int x, int y) {
    const std::size_t at = (static_cast<std::size_t>(y) * image.width + x) * 3;
    return Eigen::Vector3i(image.rgb[at], image.rgb[at + 1], image.rgb[at + 2]);
  };
  int green = 0;
  for (int y = 0; y < plain.height; ++y) {
    for (int x = 0; x < plain.width; ++x) {
      const Eigen::Vector3i p = pixel(plain, x, y);
      if (p[1] > 150 && p[0] < 100 && p[2] < 100) ++green;
    }
  }
  EXPECT_GT(green, 100) << "the marker ball is drawn";
  // the figures fill the bottom right corner: it changed, and the rest of the view far less
  int changed_corner = 0;
  for (int y = plain.height * 3 / 4; y < plain.height; ++y) {
    for (int x = plain.width * 3 / 4; x < plain.width; ++x) {
      if ((pixel(plain, x, y) - pixel(figures, x, y)).cwiseAbs().sum() > 30) ++changed_corner;
    }
  }
  EXPECT_GT(changed_corner, 500) << "figures drawn (their grids, lines and labels)";
  fs::remove_all(dir);
}

TEST(PassiveViewerWindow, CloseFromTheProgramEndsRunningAndLaterSyncsDoNothing) {
  use_passive_display();
  const Robot robot = Robot::from_string(kFloatingBox);
  DataPtr data = robot.make_data();
  PassiveViewerOptions options = passive_options();
  PassiveViewer viewer(robot, *data, options);
  EXPECT_TRUE(viewer.running());
  for (int k = 0; k < 8; ++k) viewer.plot("line " + std::to_string(k), k);
  EXPECT_THROW(viewer.plot("a ninth line", 1.0), Error);
  EXPECT_THROW(viewer.plot("line 0", NAN), Error);
  for (int k = 0; k < 50; ++k) {
    mj_step(&robot.model(), data.get());
    viewer.sync();
  }
  viewer.close();
  EXPECT_FALSE(viewer.running());
  EXPECT_EQ(viewer.report().ended_by, "closed by the program");
  EXPECT_EQ(viewer.syncs(), 50);
  viewer.sync();  // nothing, no error
  EXPECT_EQ(viewer.syncs(), 50);
}

TEST(PassiveViewerWindow, EscapeClosesTheWindowAndEndsRunning) {
  use_passive_display();
  const Robot robot = Robot::from_string(kFloatingBox);
  DataPtr data = robot.make_data();
  PassiveViewerOptions options = passive_options();
  options.script = ViewerScript::parse("wait 5\nkey escape\nwait 1000\n");
  PassiveViewer viewer(robot, *data, options);
  run_user_loop(viewer, robot, *data, [] {});
  EXPECT_FALSE(viewer.running());
  EXPECT_EQ(viewer.report().ended_by, "escape") << "not the script's end: it waits 1000 frames";
}

TEST(PassiveViewerWindow, AScriptErrorReachesTheLoop) {
  use_passive_display();
  const Robot robot = Robot::from_string(kFloatingBox);
  DataPtr data = robot.make_data();
  PassiveViewerOptions options = passive_options();
  options.script = ViewerScript::parse("set figure.nothing 1\n");
  PassiveViewer viewer(robot, *data, options);
  const auto start = std::chrono::steady_clock::now();
  while (viewer.running() && std::chrono::steady_clock::now() - start < std::chrono::minutes(1))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  try {
    viewer.sync();
    FAIL() << "the window thread's error is raised";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("figure.nothing"), std::string::npos) << e.what();
  }
  viewer.sync();  // raised once
}

TEST(PassiveViewer, RefusesBadOptionsAnotherModelsDataAndNoDisplay) {
  const Robot robot = Robot::from_string(kFloatingBox);
  const Robot other = Robot::bundled("panda");
  DataPtr data = robot.make_data();
  DataPtr other_data = other.make_data();
  PassiveViewerOptions bad;
  bad.render_hz = 0.0;
  EXPECT_THROW(PassiveViewer(robot, *data, bad), Error);
  try {
    PassiveViewer viewer(robot, *other_data);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not made for model"), std::string::npos) << e.what();
  }
  ::unsetenv("DISPLAY");
  try {
    PassiveViewer viewer(robot, *data);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), kNoDisplayMessage);
  }
}

TEST(PassiveViewer, MarkersAreBoundedFiniteAndTheirTextIsCut) {
  ViewerMarkers markers(2);
  EXPECT_TRUE(markers.add_sphere(Eigen::Vector3d::Zero(), 0.1));
  EXPECT_FALSE(markers.add_sphere(Eigen::Vector3d::Constant(NAN), 0.1)) << "not finite";
  EXPECT_TRUE(markers.add_line(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()));
  EXPECT_FALSE(markers.add_text(Eigen::Vector3d::Zero(), "full")) << "capacity reached";
  EXPECT_EQ(markers.size(), 2);
  ViewerMarkers frames(3);
  EXPECT_TRUE(frames.add_frame(Pose{}));
  EXPECT_EQ(frames.size(), 3) << "three axes";
  const std::string long_text(300, 'x');
  ViewerMarkers text(1);
  EXPECT_TRUE(text.add_text(Eigen::Vector3d::Zero(), long_text));
  EXPECT_EQ(std::string(text.geoms()[0].label).size(), sizeof(mjvGeom::label) - 1);
}

TEST(FigureSeries, KeepsTheLastSecondsThinnedAndRestartsWhenTimeGoesBack) {
  detail::FigureSeries series(2, 1.0, 100);  // 1 s, a point every 10 ms at most
  for (int k = 0; k <= 1000; ++k) {
    const float v[2] = {static_cast<float>(k), -static_cast<float>(k)};
    series.add(k * 0.002, v);  // 2 ms samples: one in five kept
  }
  EXPECT_NEAR(series.last_time(), 2.0, 1e-12);
  EXPECT_EQ(series.size(), 100);
  auto figure = std::make_unique<mjvFigure>();
  mjv_defaultFigure(figure.get());
  const std::string names[2] = {"a", "b"};
  series.fill(*figure, names);
  EXPECT_STREQ(figure->linename[1], "b");
  EXPECT_GE(figure->linepnt[0], 99);
  EXPECT_LE(figure->linepnt[0], 100);
  const int n = figure->linepnt[0];
  EXPECT_FLOAT_EQ(figure->linedata[0][2 * (n - 1)], 0.0f) << "x: time before the newest";
  EXPECT_FLOAT_EQ(figure->linedata[0][2 * (n - 1) + 1], 1000.0f);
  EXPECT_FLOAT_EQ(figure->linedata[1][2 * (n - 1) + 1], -1000.0f);
  EXPECT_GE(figure->linedata[0][0], -1.0f) << "nothing older than the span";
  EXPECT_EQ(figure->linepnt[2], 0);
  const float v[2] = {1.0f, 2.0f};
  EXPECT_TRUE(series.add(0.5, v)) << "time went back: a new run";
  EXPECT_EQ(series.size(), 1);
  EXPECT_THROW(detail::FigureSeries(0, 1.0), Error);
  EXPECT_THROW(detail::FigureSeries(1, 0.0), Error);
}

TEST(FigureSeries, SamplesTheContactForceAndActuatorForcesAgainstTheirLimits) {
  const Robot robot = Robot::from_string(R"(
<mujoco>
  <worldbody>
    <geom type="plane" size="1 1 0.1"/>
    <body pos="0 0 0.1"><freejoint/><geom type="box" size="0.1 0.1 0.1" mass="2"/></body>
    <body pos="0.5 0 0.5"><joint name="hinge" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02"/></body>
  </worldbody>
  <actuator>
    <motor name="motor" joint="hinge" ctrlrange="-1 1" gear="2"/>
    <position name="servo" joint="hinge" kp="10" ctrlrange="-1 1"/>
    <general name="clipped" joint="hinge" forcelimited="true" forcerange="-4 4"/>
  </actuator>
</mujoco>)");
  const auto actuators = detail::limited_actuators(robot.model());
  ASSERT_EQ(actuators.size(), 2u) << "the motor and the force-limited one; a servo has no limit";
  EXPECT_EQ(actuators[0].id, 0);
  EXPECT_DOUBLE_EQ(actuators[0].limit, 1.0) << "the force before the gear";
  EXPECT_EQ(actuators[1].id, 2);
  EXPECT_DOUBLE_EQ(actuators[1].limit, 4.0);
  DataPtr data = robot.make_data();
  mjData& d = *data;
  d.ctrl[0] = 0.5;                                            // half the motor's force
  for (int k = 0; k < 500; ++k) mj_step(&robot.model(), &d);  // the box settles on the floor
  const detail::FigureSample s = detail::figure_sample(robot.model(), d, actuators, {0.25});
  EXPECT_NEAR(s.contact, 2.0 * 9.81, 0.05 * 2.0 * 9.81) << "the box's weight";
  EXPECT_NEAR(s.actuator[0], 50.0f, 1e-4);
  EXPECT_FLOAT_EQ(s.plots[0], 0.25f);
  EXPECT_DOUBLE_EQ(s.time, d.time);
}

TEST(ViewerScript, ParsesTheMouseCommandsOfThePassiveViewer) {
  const ViewerScript s = ViewerScript::parse(
      "select 5 -3\npress ctrl+right 1 2\nmove 60 0\nrelease\npress left 0 0\n");
  ASSERT_EQ(s.commands.size(), 5u);
  EXPECT_EQ(s.commands[0].action, ScriptAction::select);
  EXPECT_EQ(s.commands[0].x, 5.0);
  EXPECT_EQ(s.commands[0].y, -3.0);
  EXPECT_EQ(s.commands[1].action, ScriptAction::press);
  EXPECT_EQ(s.commands[1].name, "right");
  EXPECT_EQ(s.commands[1].value, "ctrl");
  EXPECT_EQ(s.commands[2].action, ScriptAction::move);
  EXPECT_EQ(s.commands[3].action, ScriptAction::release);
  EXPECT_EQ(s.commands[4].value, "");
  EXPECT_THROW(ViewerScript::parse("press ctrl+up 0 0"), Error);
  EXPECT_THROW(ViewerScript::parse("select 1"), Error);
  EXPECT_THROW(ViewerScript::parse("release now"), Error);
  EXPECT_THROW(ViewerScript::parse("move nan 0"), Error);
}

}  // namespace
}  // namespace mjarm
