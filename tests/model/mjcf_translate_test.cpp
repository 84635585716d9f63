// MJCF 3.x -> 2.2.2 translation: a Menagerie-style arm, warnings, equivalence of actuator gains
// and forces, pass-through of 2.2.2 models, and the errors for what cannot be translated.

#include "mjarm/model/mjcf_translate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "mjarm/error.hpp"
#include "model/mjcf_test_support.hpp"

namespace mjarm {
namespace {

using mjcf_test::count_containing;
using mjcf_test::DataPtr;
using mjcf_test::load_xml;
using mjcf_test::ModelPtr;

// written the way MuJoCo Menagerie arms are: classes, position servos with kv / dampratio /
// inheritrange, implicitfast, gravcomp, a frame, a joint-level force limit, a 3.x-only sensor
constexpr const char* kArm3x = R"(<mujoco model="arm3x">
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

int id_of(const mjModel* m, mjtObj type, const char* name) {
  const int id = mj_name2id(m, type, name);
  EXPECT_GE(id, 0) << name;
  return id;
}

TEST(MjcfTranslate, ArmLoadsWithEquivalentPositionGains) {
  const MjcfTranslation t = translate_mjcf(kArm3x, ".");
  std::string err;
  const ModelPtr m = load_xml(t.xml, &err);
  ASSERT_TRUE(m) << err << "\n" << t.xml;

  EXPECT_EQ(m->opt.integrator, mjINT_IMPLICIT);
  EXPECT_EQ(m->nsensor, 1);  // e_kinetic dropped
  const int sh = id_of(m.get(), mjOBJ_ACTUATOR, "shoulder");
  const int el = id_of(m.get(), mjOBJ_ACTUATOR, "elbow");
  const int wr = id_of(m.get(), mjOBJ_ACTUATOR, "wrist");
  auto gain = [&](int i) { return m->actuator_gainprm[i * mjNGAIN]; };
  auto bias = [&](int i, int k) { return m->actuator_biasprm[i * mjNBIAS + k]; };

  // kp / kv from the class, kv overridden on the element
  EXPECT_DOUBLE_EQ(gain(sh), 200);
  EXPECT_DOUBLE_EQ(bias(sh, 1), -200);
  EXPECT_DOUBLE_EQ(bias(sh, 2), -20);
  EXPECT_DOUBLE_EQ(gain(el), 200);
  EXPECT_DOUBLE_EQ(bias(el, 2), -5);

  // dampratio: kv = 2 dampratio sqrt(kp m), m the reflected inertia at qpos0 (armature included)
  const int wdof = m->jnt_dofadr[id_of(m.get(), mjOBJ_JOINT, "wrist")];
  EXPECT_GT(m->dof_M0[wdof], 0.05);  // at least the armature
  EXPECT_NEAR(bias(wr, 2), -2 * 0.8 * std::sqrt(40 * m->dof_M0[wdof]), 1e-12);
  EXPECT_DOUBLE_EQ(gain(wr), 40);

  // inheritrange: the joint range scaled about its centre
  EXPECT_TRUE(m->actuator_ctrllimited[sh]);
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * sh], -2.8);
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * sh + 1], 2.8);
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * el], 0.25 - 0.5 * 1.75);
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * el + 1], 0.25 + 0.5 * 1.75);
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * wr + 1], 3);

  // actuatorfrcrange of the shoulder joint became its only actuator's forcerange
  EXPECT_TRUE(m->actuator_forcelimited[sh]);
  EXPECT_DOUBLE_EQ(m->actuator_forcerange[2 * sh], -80);
  EXPECT_DOUBLE_EQ(m->actuator_forcerange[2 * sh + 1], 80);

  // the frame pose lives on in link2
  DataPtr d(mj_makeData(m.get()));
  mj_kinematics(m.get(), d.get());
  const int l2 = id_of(m.get(), mjOBJ_BODY, "link2");
  EXPECT_NEAR(d->xpos[3 * l2 + 2], 0.4, 1e-12);
  EXPECT_NEAR(d->xquat[4 * l2], std::cos(0.25), 1e-12);
  EXPECT_NEAR(d->xquat[4 * l2 + 3], std::sin(0.25), 1e-12);
}

TEST(MjcfTranslate, ArmForceMatchesThe3xServoLaw) {
  const ModelPtr m = load_xml(translate_mjcf(kArm3x, ".").xml);
  ASSERT_TRUE(m);
  DataPtr d(mj_makeData(m.get()));
  const double q[3] = {0.3, -0.4, 1.1}, qd[3] = {0.7, -1.3, 2.0}, u[3] = {0.5, 0.9, -0.6};
  const double kp[3] = {200, 200, 40};
  for (int i = 0; i < 3; ++i) {
    d->qpos[i] = q[i];
    d->qvel[i] = qd[i];
    d->ctrl[i] = u[i];
  }
  mj_forward(m.get(), d.get());
  for (int i = 0; i < 3; ++i) {
    const double kv = -m->actuator_biasprm[i * mjNBIAS + 2];
    double expected = kp[i] * (u[i] - q[i]) - kv * qd[i];
    if (m->actuator_forcelimited[i]) {
      expected =
          std::clamp(expected, m->actuator_forcerange[2 * i], m->actuator_forcerange[2 * i + 1]);
    }
    EXPECT_NEAR(d->actuator_force[i], expected, 1e-9) << "actuator " << i;
    EXPECT_NEAR(d->qfrc_actuator[i], expected, 1e-9) << "actuator " << i;
  }
  EXPECT_NEAR(-m->actuator_biasprm[2], 20, 1e-12);
  // a step runs and stays finite
  mj_step(m.get(), d.get());
  for (int i = 0; i < m->nv; ++i) EXPECT_TRUE(std::isfinite(d->qvel[i]));
}

TEST(MjcfTranslate, OneWarningPerRewriteNamingTheElement) {
  const MjcfTranslation t = translate_mjcf(kArm3x, ".");
  const std::set<std::string> unique(t.warnings.begin(), t.warnings.end());
  EXPECT_EQ(unique.size(), t.warnings.size());
  EXPECT_EQ(count_containing(t.warnings,
                             "option (line 3): integrator=\"implicitfast\" is MuJoCo "
                             "3.x; using \"implicit\""),
            1);
  EXPECT_EQ(count_containing(t.warnings, "flag (line 4): eulerdamp"), 1);
  EXPECT_EQ(count_containing(t.warnings, "position 'shoulder' (line 36)"), 1);
  EXPECT_EQ(count_containing(t.warnings, "position 'elbow' (line 37)"), 1);
  EXPECT_EQ(count_containing(t.warnings, "position 'wrist' (line 38)"), 1);
  EXPECT_EQ(count_containing(t.warnings, "dampratio 0.8"), 1);
  EXPECT_EQ(count_containing(t.warnings, "default (line 7)"), 1);
  EXPECT_EQ(count_containing(t.warnings, "default (line 10)"), 1);
  EXPECT_EQ(count_containing(t.warnings, "body 'link1' (line 18): gravcomp"), 1);
  EXPECT_EQ(count_containing(t.warnings, "frame (line 21)"), 1);
  EXPECT_EQ(count_containing(t.warnings, "joint 'shoulder' (line 19): actuatorfrcrange"), 1);
  EXPECT_EQ(count_containing(t.warnings, "e_kinetic 'energy' (line 42)"), 1);
  EXPECT_EQ(count_containing(t.warnings, "autolimits"), 1);
  EXPECT_EQ(t.warnings.size(), 12u);
}

TEST(MjcfTranslate, TranslationIsIdempotent) {
  const MjcfTranslation once = translate_mjcf(kArm3x, ".");
  const MjcfTranslation twice = translate_mjcf(once.xml, ".");
  EXPECT_TRUE(twice.warnings.empty()) << twice.warnings.front();
  EXPECT_EQ(once.xml, twice.xml);
}

// valid MuJoCo 2.2.2 MJCF must come through without warnings and compile to the same model
constexpr const char* kModel222 = R"(<mujoco model="plain">
  <compiler angle="degree"/>
  <option timestep="0.001" integrator="RK4"/>
  <default>
    <joint limited="true" damping="0.2"/>
    <position kp="30" ctrllimited="true" ctrlrange="-1 1"/>
    <default class="heavy"><geom density="3000"/></default>
  </default>
  <worldbody>
    <light pos="0 0 2" dir="0 0 -1"/>
    <body name="a" pos="0 0 0.5" euler="10 20 30">
      <joint name="ja" type="hinge" axis="0 1 0" range="-90 90"/>
      <geom class="heavy" type="box" size="0.1 0.05 0.02"/>
      <site name="s" pos="0.1 0 0"/>
      <body name="b" pos="0.2 0 0">
        <joint name="jb" type="slide" axis="1 0 0" range="-0.1 0.1"/>
        <geom type="sphere" size="0.04"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="pa" joint="ja"/>
    <general name="gb" joint="jb" gainprm="5" biasprm="0 -5 -1" biastype="affine" ctrllimited="true" ctrlrange="-0.1 0.1"/>
    <velocity name="vb" joint="jb" kv="3"/>
  </actuator>
  <sensor><framepos objtype="site" objname="s"/></sensor>
  <keyframe><key name="home" qpos="0.1 0.02"/></keyframe>
</mujoco>
)";

TEST(MjcfTranslate, Mujoco222ModelPassesUnchanged) {
  const MjcfTranslation t = translate_mjcf(kModel222, ".");
  EXPECT_TRUE(t.warnings.empty()) << t.warnings.front();
  std::string err;
  const ModelPtr a = load_xml(kModel222, &err);
  ASSERT_TRUE(a) << err;
  const ModelPtr b = load_xml(t.xml, &err);
  ASSERT_TRUE(b) << err;
  ASSERT_EQ(a->nq, b->nq);
  ASSERT_EQ(a->nu, b->nu);
  ASSERT_EQ(a->nbody, b->nbody);
  for (int i = 0; i < a->nbody; ++i) {
    EXPECT_DOUBLE_EQ(a->body_mass[i], b->body_mass[i]);
    for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(a->body_quat[4 * i + k], b->body_quat[4 * i + k]);
  }
  for (int i = 0; i < a->nu * mjNBIAS; ++i) {
    EXPECT_DOUBLE_EQ(a->actuator_biasprm[i], b->actuator_biasprm[i]);
    EXPECT_DOUBLE_EQ(a->actuator_gainprm[i], b->actuator_gainprm[i]);
  }
  for (int i = 0; i < 2 * a->njnt; ++i) EXPECT_DOUBLE_EQ(a->jnt_range[i], b->jnt_range[i]);
  EXPECT_EQ(a->opt.integrator, b->opt.integrator);
}

MjcfTranslation translate_snippet(const std::string& body) {
  return translate_mjcf("<mujoco>\n" + body + "\n</mujoco>", ".");
}

// runs `fn`, expecting mjarm::Error whose message contains every needle
template <class Fn>
void expect_error(Fn fn, std::initializer_list<std::string> needles) {
  try {
    fn();
    ADD_FAILURE() << "no mjarm::Error thrown";
  } catch (const Error& e) {
    for (const auto& n : needles) {
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what() << " lacks " << n;
    }
  }
}

TEST(MjcfTranslate, MalformedXmlNamesTinyxmlErrorAndLine) {
  expect_error([] { translate_mjcf("<mujoco>\n  <worldbody>\n    <body>\n</mujoco>\n", "."); },
               {"malformed XML", "line", "XML_ERROR_MISMATCHED_ELEMENT"});
  expect_error([] { translate_mjcf("<robot/>", "."); }, {"robot", "<mujoco>"});
}

TEST(MjcfTranslate, UntranslatableConstructsThrowNamingTheElement) {
  expect_error(
      [] {
        translate_snippet(R"(<extension>
  <plugin plugin="mujoco.elasticity.cable"/>
</extension>)");
      },
      {"<extension>", "line 2"});
  expect_error(
      [] {
        translate_snippet(R"(<worldbody>
  <replicate count="2" offset="0 0 0.1"><site name="marker"/></replicate>
</worldbody>)");
      },
      {"replicate (line 3)", "names"});
  expect_error(
      [] {
        translate_snippet(
            R"(<worldbody><body name="b"><joint name="j"/><geom size="0.1"/></body></worldbody>
<actuator>
  <position name="p" joint="j" kv="1" dampratio="1"/>
</actuator>)");
      },
      {"position 'p' (line 4)", "kv and dampratio"});
  expect_error(
      [] {
        translate_snippet(
            R"(<worldbody><body><joint name="j" actuatorfrcrange="-1 1"/><geom size="0.1"/></body></worldbody>
<actuator><motor joint="j"/><motor joint="j"/></actuator>)");
      },
      {"joint 'j' (line 2)", "2 actuators"});
  expect_error(
      [] { translate_snippet(R"(<worldbody><geom size="0.1" frobnicate="1"/></worldbody>)"); },
      {"geom (line 2)", "frobnicate", "no translation rule"});
  expect_error(
      [] {
        translate_snippet(R"(<worldbody><body><joint name="j"/><geom size="0.1"/></body></worldbody>
<actuator><position joint="j" inheritrange="1"/></actuator>)");
      },
      {"position (line 3)", "no range"});
  expect_error([] { translate_snippet(R"(<option><flag spring="disable"/></option>)"); },
               {"flag (line 2)", "passive"});
}

TEST(MjcfTranslate, SpringAndDamperFlagsBecomePassive) {
  const MjcfTranslation t =
      translate_snippet(R"(<option><flag spring="disable" damper="disable"/></option>)");
  const ModelPtr m = load_xml(t.xml);
  ASSERT_TRUE(m);
  EXPECT_TRUE(m->opt.disableflags & mjDSBL_PASSIVE);
  EXPECT_EQ(t.warnings.size(), 1u);
}

TEST(MjcfTranslate, TimeconstGivesTheExactFilterUpdate) {
  // 3.x filterexact: a' = u + (a - u) exp(-h / tau); 2.2.2's filter reproduces it step by step
  const MjcfTranslation t = translate_snippet(R"(<option timestep="0.01"/>
<worldbody><body><joint name="j"/><geom size="0.1"/></body></worldbody>
<actuator><position joint="j" kp="10" timeconst="0.05"/></actuator>)");
  const ModelPtr m = load_xml(t.xml);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->actuator_dyntype[0], mjDYN_FILTER);
  DataPtr d(mj_makeData(m.get()));
  d->ctrl[0] = 1.0;
  double a = 0;
  for (int k = 0; k < 5; ++k) {
    mj_step(m.get(), d.get());
    a = 1.0 + (a - 1.0) * std::exp(-0.01 / 0.05);
    EXPECT_NEAR(d->act[0], a, 1e-12) << "step " << k;
  }
}

TEST(MjcfTranslate, DampratioOnGearedActuatorUsesReflectedInertia) {
  const MjcfTranslation t = translate_snippet(R"(<compiler angle="radian"/>
<worldbody><body><joint name="j" axis="0 0 1" armature="0.2"/><geom type="box" size="0.3 0.1 0.1" mass="2"/></body></worldbody>
<actuator><position joint="j" kp="50" dampratio="1.5" gear="3"/></actuator>)");
  const ModelPtr m = load_xml(t.xml);
  ASSERT_TRUE(m);
  // moment = gear: reflected inertia dof_M0 / gear^2
  const double mass = m->dof_M0[0] / 9.0;
  EXPECT_NEAR(m->actuator_biasprm[2], -2 * 1.5 * std::sqrt(50 * mass), 1e-12);
  EXPECT_NEAR(m->dof_M0[0], 0.2 + 2.0 * (0.6 * 0.6 + 0.2 * 0.2) / 12, 1e-12);
}

TEST(MjcfTranslate, TranslatedLinesMapBackToTheSource) {
  const std::string xml = R"(<mujoco>
  <!-- two
       comment lines -->
  <option integrator="implicitfast"/>
  <worldbody>

    <frame pos="0 0 1"><geom name="g" size="0.1"/></frame>
  </worldbody>
</mujoco>)";
  const MjcfTranslation t = translate_mjcf(xml, ".", "arm.xml");
  // every output line has a source, and the geom's line is the geom's source line
  const auto lines = std::count(t.xml.begin(), t.xml.end(), '\n');
  ASSERT_EQ(t.source_lines.size(), static_cast<std::size_t>(lines));
  const std::size_t geom_at = t.xml.find("<geom");
  const auto geom_line = std::count(t.xml.begin(), t.xml.begin() + geom_at, '\n');
  EXPECT_EQ(t.source_lines[geom_line].line, 7);
  EXPECT_EQ(t.source_lines[geom_line].file, "arm.xml");
  // MuJoCo's two message forms
  const std::string n = std::to_string(geom_line + 1);
  EXPECT_EQ(t.to_source_lines("Element 'geom', line " + n + "\n"),
            "Element 'geom', line 7 of 'arm.xml'\n");
  EXPECT_EQ(t.to_source_lines("Object name = g, id = 0, line = " + n + ", column = -1"),
            "Object name = g, id = 0, line 7 of 'arm.xml'");
  // numbers that are not line numbers of the document stay as they are
  EXPECT_EQ(t.to_source_lines("line 99999; pipeline 3; baseline 2"),
            "line 99999; pipeline 3; baseline 2");
  // the warnings name the file too
  EXPECT_EQ(count_containing(t.warnings, "option (line 4 of 'arm.xml')"), 1);
  // without a file name, lines of the text itself
  const MjcfTranslation s = translate_mjcf(xml, ".");
  EXPECT_EQ(s.to_source_lines("Element 'geom', line " + n), "Element 'geom', line 7");
}

// MuJoCo 3.x refuses ctrlrange next to inheritrange on <position> / <intvelocity> only
// (xml_native_reader.cc); its compiler sets the range of any position-servo actuator whose
// class carries inheritrange, <general> included (mjCActuator::Compile)
TEST(MjcfTranslate, InheritrangeFollowsTheRulesOfMuJoCo3) {
  const std::string model = R"(<compiler angle="radian"/>
<default>
  <default class="servo"><position kp="10" inheritrange="1"/></default>
  <default class="integ"><intvelocity kp="10" inheritrange="0.5"/></default>
</default>
<worldbody><body><joint name="j" range="-1 2"/><geom size="0.1"/></body></worldbody>
<actuator>
  )";
  // a position-servo <general> with its own ctrlrange: accepted, the range is inherited
  const MjcfTranslation servo =
      translate_snippet(model + R"(<general name="g" class="servo" joint="j" ctrlrange="-5 5"/>
</actuator>)");
  const ModelPtr m = load_xml(servo.xml);
  ASSERT_TRUE(m) << servo.xml;
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[0], -1);
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[1], 2);
  EXPECT_EQ(count_containing(servo.warnings, "replaces the element's own ctrlrange"), 1);

  // not a servo (no bias): inheritrange does not apply, its own ctrlrange stays
  const MjcfTranslation motor = translate_snippet(
      model + R"(<general name="g" class="servo" joint="j" biastype="none" ctrlrange="-5 5"/>
</actuator>)");
  const ModelPtr mm = load_xml(motor.xml);
  ASSERT_TRUE(mm) << motor.xml;
  EXPECT_DOUBLE_EQ(mm->actuator_ctrlrange[0], -5);
  EXPECT_DOUBLE_EQ(mm->actuator_ctrlrange[1], 5);
  EXPECT_EQ(count_containing(motor.warnings, "not a position servo"), 1);

  // an integrator <general> from an intvelocity class: the activation range is inherited
  const MjcfTranslation integ =
      translate_snippet(model + R"(<general name="g" class="integ" joint="j" ctrlrange="-1 1"/>
</actuator>)");
  const ModelPtr mi = load_xml(integ.xml);
  ASSERT_TRUE(mi) << integ.xml;
  EXPECT_DOUBLE_EQ(mi->actuator_actrange[0], 0.5 - 0.75);
  EXPECT_DOUBLE_EQ(mi->actuator_actrange[1], 0.5 + 0.75);
  EXPECT_DOUBLE_EQ(mi->actuator_ctrlrange[0], -1);

  // the shortcuts still refuse the pair, from the element or from the class
  expect_error(
      [&] {
        translate_snippet(model + R"(<position class="servo" joint="j" ctrlrange="-5 5"/>
</actuator>)");
      },
      {"position (line 9)", "ctrlrange and inheritrange cannot both be defined"});
  expect_error(
      [&] {
        translate_snippet(model + R"(<intvelocity class="integ" joint="j" actrange="-1 1"/>
</actuator>)");
      },
      {"intvelocity (line 9)", "actrange and inheritrange"});
}

}  // namespace
}  // namespace mjarm
