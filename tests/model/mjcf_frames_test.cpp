// MJCF translation of <frame>, <replicate> and <include>: poses cross-checked against MuJoCo's
// own composition of nested bodies, includes with relative paths.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "mjarm/error.hpp"
#include "mjarm/model/mjcf_translate.hpp"
#include "model/mjcf_test_support.hpp"

namespace mjarm {
namespace {

using mjcf_test::DataPtr;
using mjcf_test::load_xml;
using mjcf_test::ModelPtr;

// the same model with frames ($F = frame) and with static bodies in their place ($F = body): the
// bodies' world poses are composed by MuJoCo itself, the frames' by the translator
std::string framed(const std::string& compiler, const std::string& f) {
  return R"(<mujoco>
  )" + compiler +
         R"(
  <default><default class="red"><geom rgba="1 0 0 1" size="0.02"/><site size="0.01" pos="0.01 0.02 0.03"/></default></default>
  <worldbody>
    <body name="root" pos="0.1 0.2 0.3">
      <)" +
         f + R"( pos="0.5 -0.2 0.1" euler="30 -45 60" childclass="red">
        <geom name="g_quat" type="box" size="0.1 0.2 0.3" pos="0.1 0 0" quat="0.9 0.1 0.3 -0.2"/>
        <geom name="g_axisangle" type="box" size="0.1 0.2 0.3" pos="0 0.1 0" axisangle="1 1 0 40"/>
        <geom name="g_xyaxes" type="box" size="0.1 0.2 0.3" xyaxes="0 1 0 -1 0.2 0"/>
        <geom name="g_zaxis" type="box" size="0.1 0.2 0.3" zaxis="1 1 1"/>
        <geom name="g_euler" type="box" size="0.1 0.2 0.3" euler="10 20 30"/>
        <geom name="g_fromto" type="capsule" fromto="0 0 0 0.2 0.1 0"/>
        <site name="s_default"/>
        <)" +
         f + R"( pos="0 0 0.2" axisangle="0 0 1 90">
          <body name="inner" pos="0.1 0 0" euler="0 90 0">
            <joint name="hinge" axis="1 0 0"/>
            <geom name="g_inner" type="sphere" size="0.05"/>
          </body>
        </)" +
         f + R"(>
      </)" +
         f + R"(>
    </body>
  </worldbody>
</mujoco>)";
}

void expect_same_poses(const std::string& compiler) {
  const MjcfTranslation t = translate_mjcf(framed(compiler, "frame"), ".");
  std::string err;
  const ModelPtr a = load_xml(t.xml, &err);
  ASSERT_TRUE(a) << err << "\n" << t.xml;
  const ModelPtr b = load_xml(framed(compiler, "body"), &err);
  ASSERT_TRUE(b) << err;
  DataPtr da(mj_makeData(a.get())), db(mj_makeData(b.get()));
  mj_kinematics(a.get(), da.get());
  mj_kinematics(b.get(), db.get());
  for (const char* g :
       {"g_quat", "g_axisangle", "g_xyaxes", "g_zaxis", "g_euler", "g_fromto", "g_inner"}) {
    const int ia = mj_name2id(a.get(), mjOBJ_GEOM, g), ib = mj_name2id(b.get(), mjOBJ_GEOM, g);
    ASSERT_GE(ia, 0);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(da->geom_xpos[3 * ia + k], db->geom_xpos[3 * ib + k], 1e-9) << g;
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(da->geom_xmat[9 * ia + k], db->geom_xmat[9 * ib + k], 1e-9) << g;
    EXPECT_NEAR(a->geom_size[3 * ia], b->geom_size[3 * ib], 1e-12) << g;
  }
  const int sa = mj_name2id(a.get(), mjOBJ_SITE, "s_default");
  const int sb = mj_name2id(b.get(), mjOBJ_SITE, "s_default");
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(da->site_xpos[3 * sa + k], db->site_xpos[3 * sb + k], 1e-9);
  EXPECT_NEAR(a->site_size[3 * sa], 0.01, 1e-12);  // the frame's childclass reached the site
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(da->xanchor[k], db->xanchor[k], 1e-9);
    EXPECT_NEAR(da->xaxis[k], db->xaxis[k], 1e-9);
  }
  EXPECT_EQ(std::count_if(t.warnings.begin(), t.warnings.end(),
                          [](const auto& w) { return w.find("<frame>") != std::string::npos; }),
            1);
}

TEST(MjcfFrames, ComposedPosesMatchNestedBodiesInDegrees) { expect_same_poses(""); }

TEST(MjcfFrames, ComposedPosesMatchWithExtrinsicEulerSequence) {
  expect_same_poses(R"(<compiler eulerseq="ZXY"/>)");
}

TEST(MjcfFrames, SimpleReplicateIsExpanded) {
  const MjcfTranslation t = translate_mjcf(R"(<mujoco>
  <worldbody>
    <replicate count="4" offset="0.1 0 0"><geom type="sphere" size="0.01"/></replicate>
    <replicate count="3" euler="0 0 90"><geom type="sphere" size="0.02" pos="1 0 0"/></replicate>
  </worldbody>
</mujoco>)",
                                           ".");
  const ModelPtr m = load_xml(t.xml);
  ASSERT_TRUE(m) << t.xml;
  ASSERT_EQ(m->ngeom, 7);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m->geom_pos[3 * i], 0.1 * i, 1e-12);
  const double expected[3][2] = {{1, 0}, {0, 1}, {-1, 0}};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(m->geom_pos[3 * (4 + i)], expected[i][0], 1e-12);
    EXPECT_NEAR(m->geom_pos[3 * (4 + i) + 1], expected[i][1], 1e-12);
  }
  EXPECT_EQ(t.warnings.size(), 2u);
}

// a binary STL tetrahedron with outward faces
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
  const MjcfTranslation t = translate_mjcf(scene, dir_);
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
  EXPECT_EQ(t.warnings.size(), 1u);  // the joint range relies on autolimits
}

TEST_F(MjcfInclude, MissingAndCyclicIncludesThrow) {
  try {
    translate_mjcf("<mujoco>\n  <include file=\"nope.xml\"/>\n</mujoco>", dir_);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("include (line 2)"), std::string::npos) << e.what();
  }
  write("a.xml", R"(<mujoco><include file="b.xml"/></mujoco>)");
  write("b.xml", R"(<mujoco><include file="a.xml"/></mujoco>)");
  try {
    translate_mjcf(R"(<mujoco><include file="a.xml"/></mujoco>)", dir_);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cycle"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("b.xml"), std::string::npos) << e.what();
  }
}

TEST_F(MjcfInclude, IncludesAndAssetsMustBeRegularFiles) {
  // MuJoCo would read /dev/zero forever: the translator refuses it before MuJoCo opens it
  try {
    translate_mjcf(R"(<mujoco>
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
    translate_mjcf(R"(<mujoco><include file="loop1.xml"/></mujoco>)", dir_);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("symbolic link loop"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjarm
