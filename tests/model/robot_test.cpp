#include "mjarm/model/robot.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <optional>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/scene/scene.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

using test::error_of;

TEST(Robot, ReportsWhatTheModelHolds) {
  const Robot robot = Robot::from_string(test::kTrickyArm);
  EXPECT_EQ(robot.name(), "tricky");
  EXPECT_EQ(robot.nq(), 6 + 7);
  EXPECT_EQ(robot.nv(), 6 + 6);
  const auto joints = robot.joints();
  ASSERT_EQ(joints.size(), 7u);
  EXPECT_EQ(joints[2].name, "off_path");
  EXPECT_EQ(joints[3].type, JointType::slide);
  EXPECT_TRUE(joints[3].limited);
  EXPECT_DOUBLE_EQ(joints[3].upper, 0.2);
  EXPECT_EQ(joints[6].type, JointType::free);
  EXPECT_EQ(robot.site("tool"), 0);
}

TEST(Robot, UnknownNamesThrowWithTheClosestNames) {
  const Robot robot = Robot::from_string(test::kTrickyArm);
  const std::string message = error_of([&] { robot.site("tol"); });
  EXPECT_NE(message.find("site 'tol' not found in model 'tricky'"), std::string::npos) << message;
  EXPECT_NE(message.find("tool"), std::string::npos) << message;
  EXPECT_NE(error_of([&] { robot.joint("j9"); }).find("closest: j"), std::string::npos);
  EXPECT_NE(error_of([&] { robot.camera("top"); }).find("no named camera"), std::string::npos);
  EXPECT_THROW(robot.actuator("motor"), Error);
  EXPECT_THROW(robot.keyframe("home"), Error);
}

TEST(Robot, NamedStateAccessChecksSizesAndValues) {
  const Robot robot = Robot::from_string(test::kTrickyArm);
  const auto d = robot.make_data();
  const double angle = 0.25;
  robot.set_qpos(*d, "j2", {&angle, 1});
  EXPECT_EQ(robot.qpos(*d, "j2")[0], 0.25);
  EXPECT_EQ(robot.qpos(*d, "box_free").size(), 7u);
  EXPECT_EQ(robot.qvel(*d, "box_free").size(), 6u);
  const double two[2] = {0, 0};
  EXPECT_THROW(robot.set_qpos(*d, "j2", two), Error);
  const double nan = std::nan("");
  EXPECT_THROW(robot.set_qpos(*d, "j2", {&nan, 1}), Error);
  EXPECT_THROW(robot.set_qvel(*d, "nope", {&angle, 1}), Error);
}

TEST(Robot, MissingFileAndMalformedXmlGiveClearErrors) {
  EXPECT_NE(error_of([] { Robot::from_file("/nonexistent/arm.xml"); }).find("does not exist"),
            std::string::npos);
  const std::string malformed =
      error_of([] { Robot::from_string("<mujoco><worldbody></mujoco>"); });
  EXPECT_NE(malformed.find("malformed XML"), std::string::npos) << malformed;
  EXPECT_NE(malformed.find("line 1"), std::string::npos) << malformed;
  const std::string invalid = error_of(
      [] { Robot::from_string("<mujoco><worldbody><geom type=\"blob\"/></worldbody></mujoco>"); });
  EXPECT_NE(invalid.find("cannot load"), std::string::npos) << invalid;
  EXPECT_NE(error_of([] { Robot::bundled("pandaa"); }).find("no bundled model named 'pandaa'"),
            std::string::npos);
}

TEST(Robot, LoadsUrdf) {
  const char* urdf = R"(<?xml version="1.0"?>
<robot name="two_link">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="upper"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>)";
  const Robot robot = Robot::from_string(urdf);
  ASSERT_EQ(robot.joints().size(), 1u);
  EXPECT_EQ(robot.joints()[0].name, "shoulder");
  EXPECT_TRUE(robot.joints()[0].limited);
  EXPECT_DOUBLE_EQ(robot.joints()[0].lower, -1.0);
  // and from a file
  const auto path = std::filesystem::temp_directory_path() / "mjarm_two_link.urdf";
  std::ofstream(path) << urdf;
  EXPECT_EQ(Robot::from_file(path).nq(), 1);
  std::filesystem::remove(path);
}

TEST(Robot, CopiesShareOneModel) {
  const Robot a = Robot::from_string(test::kTrickyArm);
  const Robot b = a;
  EXPECT_EQ(&a.model(), &b.model());
}

TEST(Names, ClosestNamesPreferContainmentThenEditDistance) {
  const std::vector<std::string> names = {"attachment_site", "tcp", "grip", "tip"};
  const auto close = closest_names("attachment", names, 2);
  ASSERT_EQ(close.size(), 2u);
  EXPECT_EQ(close[0], "attachment_site");
  EXPECT_EQ(closest_names("tpi", names, 1)[0], "tip");
}

// sets $MJARM_MODELS for one test and restores it
class ModelsFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* old = std::getenv("MJARM_MODELS")) old_ = old;
  }
  void TearDown() override {
    if (old_) {
      ::setenv("MJARM_MODELS", old_->c_str(), 1);
    } else {
      ::unsetenv("MJARM_MODELS");
    }
  }
  std::optional<std::string> old_;
};

TEST_F(ModelsFolder, MissingOrEmptyFolderIsAnErrorNamingItAndTheVariable) {
  ::setenv("MJARM_MODELS", "/nonexistent/models", 1);
  const std::string missing = error_of([] { Robot::bundled_names(); });
  EXPECT_NE(missing.find("bundled models folder '/nonexistent/models' (from $MJARM_MODELS) does "
                         "not exist"),
            std::string::npos)
      << missing;
  // every lookup of a bundled name says the same
  EXPECT_EQ(error_of([] { Robot::bundled("panda"); }), missing);
  EXPECT_EQ(error_of([] { Robot::load("panda"); }), missing);

  const auto empty = test::scratch() / "no_models";
  std::filesystem::create_directories(empty);
  std::ofstream(empty / "readme.txt") << "not a model";
  ::setenv("MJARM_MODELS", empty.c_str(), 1);
  const std::string none = error_of([] { Robot::bundled("panda"); });
  EXPECT_NE(none.find("'" + empty.string() + "' (from $MJARM_MODELS) holds no models"),
            std::string::npos)
      << none;
  ::setenv("MJARM_MODELS", (empty / "readme.txt").c_str(), 1);
  EXPECT_NE(error_of([] { Robot::bundled_names(); }).find("is not a folder"), std::string::npos);
}

// issue 29, smaller: a file's kind by its extension in any case ("ARM.XML" was no model)
TEST_F(ModelsFolder, AModelFileIsFoundWhateverTheCaseOfItsExtension) {
  const auto folder = test::scratch() / "upper_models";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "Arm.XML") << "<mujoco model=\"upper\"><worldbody><body><joint/>"
                                       "<geom size=\"0.1\"/></body></worldbody></mujoco>";
  std::ofstream(folder / "notes.xmlx") << "not a model";
  ::setenv("MJARM_MODELS", folder.c_str(), 1);
  EXPECT_EQ(Robot::bundled_names(), std::vector<std::string>{"Arm"});
  EXPECT_EQ(Robot::bundled("Arm").name(), "upper");
  EXPECT_EQ(Robot::load("Arm").nq(), 1);
  // a scene takes it by its name too
  Scene scene;
  scene.add_robot(RobotSpec{"a", "Arm", {0, 0, 0}, {1, 0, 0, 0}, false});
  EXPECT_EQ(scene.compile().nq(), 1);
}

// issue 29, item 6 in XML: tinyxml2 reads a second root element and MuJoCo dropped it
TEST(Robot, ASecondRootElementIsRefused) {
  const std::string one = "<mujoco model=\"a\"><worldbody><geom size=\"0.1\"/></worldbody></mujoco>";
  std::string message = error_of([&] { Robot::from_string(one + "\n<mujoco model=\"b\"/>"); });
  EXPECT_NE(message.find("XML string line 2: a second root element <mujoco> (the first, <mujoco>, "
                         "is at line 1); an XML file holds one"),
            std::string::npos)
      << message;
  const auto dir = test::scratch() / "two_roots";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "parts.xml") << one << "\n\n<robot name=\"r\"/>\n";
  std::ofstream(dir / "main.xml") << "<mujoco>\n  <include file=\"parts.xml\"/>\n</mujoco>\n";
  message = error_of([&] { Robot::from_file(dir / "main.xml"); });
  EXPECT_NE(message.find("'" + (dir / "parts.xml").string() +
                         "' line 3: a second root element <robot>"),
            std::string::npos)
      << message;
  std::ofstream(dir / "two.urdf") << "<robot name=\"r\"><link name=\"l\"/></robot>\n<robot name=\"s\"/>";
  message = error_of([&] { Robot::from_file(dir / "two.urdf"); });
  EXPECT_NE(message.find("two.urdf' line 2: a second root element <robot>"), std::string::npos)
      << message;
}

TEST(Robot, FilesThatAreNotRegularOrTooDeepGiveClearErrors) {
  const std::string device = error_of([] { Robot::from_file("/dev/zero"); });
  EXPECT_NE(device.find("model file '/dev/zero' is a character device"), std::string::npos)
      << device;
  const auto dir = test::scratch() / "robot_files";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "include_urandom.xml")
      << "<mujoco>\n<include file=\"/dev/urandom\"/>\n</mujoco>";
  const std::string include = error_of([&] { Robot::from_file(dir / "include_urandom.xml"); });
  EXPECT_NE(include.find("include (line 2"), std::string::npos) << include;
  EXPECT_NE(include.find("included file '/dev/urandom' is a character device"), std::string::npos)
      << include;
  // an <include> of a FIFO: refused at once (guarded: a regression fails instead of hanging)
  const auto fifo = dir / "pipe.xml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::ofstream(dir / "include_fifo.xml") << R"(<mujoco><include file="pipe.xml"/></mujoco>)";
  auto read = std::async(std::launch::async, [&] {
    return error_of([&] { Robot::from_file(dir / "include_fifo.xml"); });
  });
  if (read.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "an included FIFO blocked the load";
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  const std::string pipe = read.get();
  EXPECT_NE(pipe.find("is a FIFO (named pipe)"), std::string::npos) << pipe;
  // a well-formed chain of 500 bodies: the parser's depth limit is named, not "malformed"
  std::string deep = "<mujoco><worldbody>";
  for (int i = 0; i < 500; ++i) deep += "<body><joint/><geom size=\"0.1\"/>";
  for (int i = 0; i < 500; ++i) deep += "</body>";
  deep += "</worldbody></mujoco>";
  std::ofstream(dir / "deep.xml") << deep;
  for (const std::string& message : {error_of([&] { Robot::from_file(dir / "deep.xml"); }),
                                     error_of([&] { Robot::from_string(deep); })}) {
    EXPECT_NE(message.find("more than 100 deep"), std::string::npos) << message;
    EXPECT_NE(message.find("TINYXML2_MAX_ELEMENT_DEPTH"), std::string::npos) << message;
    EXPECT_EQ(message.find("malformed"), std::string::npos) << message;
  }
}

TEST(Robot, LoadErrorsNameTheUsersFileAndLine) {
  const auto dir = test::scratch() / "robot_lines";
  std::filesystem::create_directories(dir);
  // an include and a comment shift the staged lines; the missing mesh is on line 10 of the
  // user's file
  const auto main = dir / "arm3x.xml";
  std::ofstream(main) << R"(<mujoco model="arm3x">
  <!-- a comment
       over three lines -->
  <compiler angle="radian"/>
  <option integrator="implicitfast"/>

  <include file="parts.xml"/>
  <asset>

    <mesh name="shell" file="missing.stl"/>
  </asset>
  <worldbody>
    <frame pos="0 0 1">
      <body name="b"><joint name="j" range="-1 1"/><geom type="mesh" mesh="shell"/></body>
    </frame>
  </worldbody>
</mujoco>)";
  std::ofstream(dir / "parts.xml") << "<mujoco>\n  <default/>\n</mujoco>";
  const std::string mesh = error_of([&] { Robot::from_file(main); });
  EXPECT_NE(mesh.find("missing.stl"), std::string::npos) << mesh;
  EXPECT_NE(mesh.find("line 10 of '" + main.string() + "'"), std::string::npos) << mesh;

  // an error inside an included file names that file and its line (MuJoCo itself says line 0)
  std::ofstream(main) << R"(<mujoco model="arm">
  <!-- a comment -->
  <include file="parts.xml"/>
</mujoco>)";
  std::ofstream(dir / "parts.xml") << R"(<mujoco>
  <worldbody>

    <geom name="short" size="0.1" pos="1 2"/>
  </worldbody>
</mujoco>)";
  const std::string part = error_of([&] { Robot::from_file(main); });
  const auto parts = std::filesystem::canonical(dir / "parts.xml");
  EXPECT_NE(part.find("'pos'"), std::string::npos) << part;
  EXPECT_NE(part.find("line 4 of '" + parts.string() + "'"), std::string::npos) << part;

  // a file without includes too
  std::ofstream(dir / "plain.xml") << R"(<mujoco>

  <worldbody><geom size="0.1" type="blob"/></worldbody>
</mujoco>)";
  const std::string plain = error_of([&] { Robot::from_file(dir / "plain.xml"); });
  EXPECT_NE(plain.find("line 3 of '" + (dir / "plain.xml").string() + "'"), std::string::npos)
      << plain;
}

TEST(Robot, MujocoErrorsBecomeExceptions) {
  install_mujoco_handlers();
  EXPECT_THROW(mju_error("deliberate"), Error);
}

}  // namespace
}  // namespace mjarm
