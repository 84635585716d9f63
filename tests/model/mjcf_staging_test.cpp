// MJCF staging: includes inlined and assets made absolute through the checked reader, the line
// map back to the user's files, and a Menagerie-style model that loads exactly as MuJoCo loads it.

#include "model/mjcf_staging.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "model/mjcf_test_support.hpp"

namespace mjarm {
namespace {

using mjcf_test::load_xml;
using mjcf_test::ModelPtr;

void write_tetrahedron(const std::filesystem::path& file) {
  const float v[4][3] = {{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}, {0, 0, 0.1f}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::ofstream out(file, std::ios::binary);
  const char header[80] = {};
  out.write(header, 80);
  const std::uint32_t n = 4;
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : faces) {
    const float normal[3] = {0, 0, 0};
    out.write(reinterpret_cast<const char*>(normal), sizeof(normal));
    for (const int i : f) out.write(reinterpret_cast<const char*>(v[i]), sizeof(v[i]));
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

class MjcfInclude : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("mjarm_mjcf_include_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "robot");
    std::filesystem::create_directories(dir_ / "meshes");
    write_tetrahedron(dir_ / "meshes" / "tet.stl");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void write(const std::string& rel, const std::string& text) { std::ofstream(dir_ / rel) << text; }
  std::filesystem::path dir_;
};

TEST_F(MjcfInclude, RelativeIncludesAndAssetsBecomeAbsolute) {
  write("robot/arm.xml", R"(<mujoco>
  <include file="robot/defaults.xml"/>
  <asset><mesh name="tet" file="tet.stl"/></asset>
  <worldbody>
    <body name="b"><joint name="j" range="-1 1"/><geom type="mesh" mesh="tet" class="blue"/></body>
  </worldbody>
  <include file="sensors.xml"/>
</mujoco>)");
  write(
      "robot/defaults.xml",
      R"(<mujoco><default><default class="blue"><geom rgba="0 0 1 1"/></default></default></mujoco>)");
  write("robot/sensors.xml", R"(<mujoco><sensor><jointpos joint="j"/></sensor></mujoco>)");
  const std::string scene = R"(<mujoco>
  <compiler meshdir="meshes"/>
  <include file="robot/arm.xml"/>
</mujoco>)";
  const StagedMjcf t = stage_mjcf(scene, dir_);
  EXPECT_EQ(t.xml.find("<include"), std::string::npos);
  EXPECT_NE(t.xml.find("file=\"" + (dir_ / "meshes" / "tet.stl").string() + "\""),
            std::string::npos)
      << t.xml;
  std::string err;
  const ModelPtr m = load_xml(t.xml, &err);  // from memory: only absolute paths can work
  ASSERT_TRUE(m) << err << "\n" << t.xml;
  EXPECT_EQ(m->nmesh, 1);
  EXPECT_EQ(m->nsensor, 1);
  EXPECT_FLOAT_EQ(m->geom_rgba[2], 1.0f);
  EXPECT_EQ(m->jnt_limited[0], 1);  // the range alone limits the joint (autolimits)
}

// MuJoCo 4 reports a load warning to the log handler and again in the error buffer: once here
TEST_F(MjcfInclude, ALoadWarningIsReportedOnce) {
  const std::string xml = R"(<mujoco><statistic meaninertia="2"/>
  <worldbody><body><joint/><geom size=".1"/></body></worldbody></mujoco>)";
  write("warn.xml", xml);
  for (const Robot& robot : {Robot::from_string(xml), Robot::from_file(dir_ / "warn.xml")}) {
    ASSERT_EQ(robot.load_warnings().size(), 1u);
    EXPECT_NE(robot.load_warnings()[0].find("meaninertia"), std::string::npos);
  }
}

TEST_F(MjcfInclude, MissingAndCyclicIncludesThrow) {
  try {
    stage_mjcf("<mujoco>\n  <include file=\"nope.xml\"/>\n</mujoco>", dir_);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("include (line 2)"), std::string::npos) << e.what();
  }
  write("a.xml", R"(<mujoco><include file="b.xml"/></mujoco>)");
  write("b.xml", R"(<mujoco><include file="a.xml"/></mujoco>)");
  try {
    stage_mjcf(R"(<mujoco><include file="a.xml"/></mujoco>)", dir_);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cycle"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("b.xml"), std::string::npos) << e.what();
  }
}

TEST_F(MjcfInclude, IncludesAndAssetsMustBeRegularFiles) {
  // MuJoCo would read /dev/zero forever: the staging refuses it before MuJoCo opens it
  try {
    stage_mjcf(R"(<mujoco>
  <asset><mesh name="m" file="/dev/zero"/></asset>
</mujoco>)",
                   dir_);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 'm' (line 2)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'/dev/zero' is a character device"), std::string::npos)
        << e.what();
  }
  std::filesystem::create_symlink("loop2.xml", dir_ / "loop1.xml");
  std::filesystem::create_symlink("loop1.xml", dir_ / "loop2.xml");
  try {
    stage_mjcf(R"(<mujoco><include file="loop1.xml"/></mujoco>)", dir_);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("symbolic link loop"), std::string::npos) << e.what();
  }
}

TEST(MjcfStaging, LinesMapBackToTheSource) {
  const std::string xml = R"(<mujoco>
  <!-- two
       comment lines -->
  <option integrator="implicitfast"/>
  <worldbody>

    <frame pos="0 0 1"><geom name="g" size="0.1"/></frame>
  </worldbody>
</mujoco>)";
  const StagedMjcf t = stage_mjcf(xml, ".", "arm.xml");
  // every output line has a source, and the geom's line is the geom's source line
  const auto lines = std::count(t.xml.begin(), t.xml.end(), '\n');
  ASSERT_EQ(t.source_lines.size(), static_cast<std::size_t>(lines));
  const std::size_t geom_at = t.xml.find("<geom");
  const auto geom_line = std::count(t.xml.begin(), t.xml.begin() + geom_at, '\n');
  EXPECT_EQ(t.source_lines[geom_line].line, 7);
  EXPECT_EQ(t.source_lines[geom_line].file, "arm.xml");
  // MuJoCo's message forms: the parser's and the compiler's
  const std::string n = std::to_string(geom_line + 1);
  EXPECT_EQ(t.to_source_lines("Element 'geom', line " + n + "\n"),
            "Element 'geom', line 7 of 'arm.xml'\n");
  EXPECT_EQ(t.to_source_lines("Element name 'g', id 0, line " + n),
            "Element name 'g', id 0, line 7 of 'arm.xml'");
  // numbers that are not line numbers of the document stay as they are
  EXPECT_EQ(t.to_source_lines("line 99999; pipeline 3; baseline 2"),
            "line 99999; pipeline 3; baseline 2");
  // without a file name, lines of the text itself
  const StagedMjcf s = stage_mjcf(xml, ".");
  EXPECT_EQ(s.to_source_lines("Element 'geom', line " + n), "Element 'geom', line 7");
}

TEST(MjcfStaging, MalformedXmlNamesTheParserErrorAndLine) {
  const auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string bad = message([] { stage_mjcf("<mujoco>\n  <worldbody>\n    <body>\n</mujoco>\n", "."); });
  EXPECT_NE(bad.find("malformed XML"), std::string::npos) << bad;
  EXPECT_NE(bad.find("XML_ERROR_MISMATCHED_ELEMENT"), std::string::npos) << bad;
  const std::string root = message([] { stage_mjcf("<robot/>", "."); });
  EXPECT_NE(root.find("<mujoco>"), std::string::npos) << root;
}

// written the way MuJoCo Menagerie arms are: classes, position servos with kv / dampratio /
// inheritrange, implicitfast, gravcomp, a frame, a joint-level force limit, a newer sensor
constexpr const char* kMenagerieStyleArm = R"(<mujoco model="arm">
  <compiler angle="radian"/>
  <option integrator="implicitfast" timestep="0.002">
    <flag eulerdamp="disable"/>
  </option>
  <default>
    <default class="arm">
      <joint armature="0.05" damping="0.5"/>
      <position kp="200" kv="20" inheritrange="1"/>
      <default class="wrist">
        <position kp="40" dampratio="0.8"/>
      </default>
    </default>
  </default>
  <worldbody>
    <body name="base" childclass="arm">
      <geom type="cylinder" size="0.06 0.05" mass="2"/>
      <body name="link1" pos="0 0 0.1" gravcomp="1">
        <joint name="shoulder" axis="0 0 1" range="-2.8 2.8" actuatorfrcrange="-80 80"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.3" size="0.04" mass="1.5"/>
        <frame pos="0 0 0.3" euler="0 0 0.5">
          <body name="link2">
            <joint name="elbow" axis="0 1 0" range="-1.5 2.0"/>
            <geom type="capsule" fromto="0 0 0 0.25 0 0" size="0.03" mass="1"/>
            <replicate count="2" offset="0.1 0 0">
              <site name="marker" size="0.01"/>
            </replicate>
            <body name="link3" pos="0.25 0 0">
              <joint name="wrist" class="wrist" axis="1 0 0" range="-3 3"/>
              <geom type="box" size="0.03 0.04 0.05" mass="0.3"/>
              <site name="tool" pos="0.05 0 0"/>
            </body>
          </body>
        </frame>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="shoulder" class="arm" joint="shoulder"/>
    <position name="elbow" class="arm" joint="elbow" kv="5" inheritrange="0.5"/>
    <position name="wrist" class="wrist" joint="wrist"/>
  </actuator>
  <sensor>
    <jointpos name="q_shoulder" joint="shoulder"/>
    <e_kinetic name="energy"/>
  </sensor>
</mujoco>
)";

// the staging changes nothing MuJoCo compiles: every array of the model loaded by mjarm equals
// the one of the model MuJoCo loads from the user's text itself
TEST(MjcfStaging, MenagerieStyleModelLoadsAsMuJoCoLoadsIt) {
  const Robot robot = Robot::from_string(kMenagerieStyleArm);
  std::string err;
  const ModelPtr direct = load_xml(kMenagerieStyleArm, &err);
  ASSERT_TRUE(direct) << err;
  const mjModel& a = robot.model();
  const mjModel& b = *direct;
  EXPECT_EQ(robot.load_warnings().size(), 0u);
  ASSERT_EQ(a.nbuffer, b.nbuffer);
  ASSERT_EQ(a.nq, b.nq);
  ASSERT_EQ(a.nu, b.nu);
  ASSERT_EQ(a.nsite, 3);  // the tool and the two replicated markers
  const mjModel* pa = &a;
  const mjModel* pb = &b;
  int compared = 0;
#define X(type, name, nr, nc)                                                              \
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(pa->nr) * (nc); ++i) {           \
    if (!(pa->name[i] == pb->name[i])) {                                                   \
      ADD_FAILURE() << "mjModel::" #name "[" << i << "] differs";                          \
      break;                                                                               \
    }                                                                                      \
  }                                                                                        \
  ++compared;
  MJMODEL_POINTERS_PREAMBLE(pa)
  MJMODEL_POINTERS
#undef X
  EXPECT_GT(compared, 100);
  // the servo laws are MuJoCo's own: dampratio became a damping the compiler computed
  const int wrist = mj_name2id(pb, mjOBJ_ACTUATOR, "wrist");
  EXPECT_LT(a.actuator_biasprm[wrist * mjNBIAS + 2], 0.0);
  EXPECT_EQ(a.opt.integrator, mjINT_IMPLICITFAST);
}

}  // namespace
}  // namespace mjarm
