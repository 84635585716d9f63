#include "mjarm/model/finite_model.hpp"

#include <gtest/gtest.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;

// a one-joint arm with `body`, `joint`, `geom` and `extra` spliced into its elements
std::string one_joint_arm(const std::string& body, const std::string& joint = "",
                          const std::string& geom = "", const std::string& extra = "") {
  return R"(<mujoco model="bad">)" + extra + R"(
  <worldbody>
    <body name="link" )" +
         body + R"(>
      <joint name="hinge" axis="0 0 1" )" +
         joint + R"(/>
      <geom name="rod" size="0.05 0.2" type="capsule" )" +
         geom + R"(/>
      <site name="tip"/>
    </body>
  </worldbody>
</mujoco>)";
}

void expect_names(const std::string& message, std::initializer_list<std::string> parts) {
  for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

TEST(FiniteModel, NonFiniteNumbersFailTheLoadNamingElementAndAttribute) {
  expect_names(error_of([] { Robot::from_string(one_joint_arm(R"(pos="inf 0 0")")); }),
               {"non-finite", "body 'link'", "attribute pos = inf 0 0", "mjModel::body_pos"});
  // MuJoCo's own parser refuses an overflowing number
  expect_names(error_of([] { Robot::from_string(one_joint_arm(R"(pos="0 0 1e999")")); }),
               {"'pos'", "line 3"});
  expect_names(
      error_of([] { Robot::from_string(one_joint_arm("", R"(limited="true" range="-1 nan")")); }),
      {"joint 'hinge'", "attribute range", "mjModel::jnt_range"});
  expect_names(error_of([] { Robot::from_string(one_joint_arm("", R"(damping="inf")")); }),
               {"joint 'hinge'", "attribute damping", "mjModel::dof_damping"});
  expect_names(
      error_of([] { Robot::from_string(one_joint_arm("", "", R"(friction="nan 0.005 0.0001")")); }),
      {"geom 'rod'", "friction", "mjModel::geom_friction"});
  expect_names(error_of([] {
                 Robot::from_string(one_joint_arm("", "", "", R"(<option gravity="0 0 -inf"/>)"));
               }),
               {"<option> gravity = 0 0 -inf", "mjModel::opt.gravity"});
  expect_names(error_of([] {
                 Robot::from_string(one_joint_arm("", "", "", R"(<option timestep="nan"/>)"));
               }),
               {"<option> timestep"});
}

TEST(FiniteModel, TheSourceIsNamedNotWhatItSpreadTo) {
  // a non-finite mass spreads to subtreemass, invweight0 and dof_M0; the error names the mass
  const std::string mass = error_of([] {
    Robot::from_string(R"(<mujoco>
  <worldbody>
    <body name="heavy">
      <joint name="hinge" axis="0 0 1"/>
      <inertial pos="0 0 0" mass="inf" diaginertia="1 1 1"/>
    </body>
  </worldbody>
</mujoco>)");
  });
  expect_names(mass, {"body 'heavy'", "<inertial> mass", "mjModel::body_mass"});
}

TEST(FiniteModel, KeyframesAndUnnamedElementsAreNamed) {
  expect_names(error_of([] {
                 Robot::from_string(one_joint_arm(
                     "", "", "", R"(<keyframe><key name="home" qpos="nan"/></keyframe>)"));
               }),
               {"key 'home'", "qpos = nan", "mjModel::key_qpos"});
  expect_names(error_of([] {
                 Robot::from_string(
                     R"(<mujoco><worldbody><geom size="0.1" pos="0 inf 0"/></worldbody></mujoco>)");
               }),
               {"geom 0 (unnamed)", "pos = 0 inf 0"});
}

TEST(FiniteModel, NanIsRefusedNamingElementAndAttribute) {
  // issue 29's probe: MuJoCo 4 keeps the NaN (2.2.2 zeroed it) and only warns
  expect_names(error_of([] { Robot::from_string(one_joint_arm(R"(pos="nan 0 0.3")")); }),
               {"non-finite", "body 'link'", "attribute pos = nan 0 0.3", "mjModel::body_pos"});
  // <visual> and <statistic> reach the renderer's camera and clipping planes
  expect_names(error_of([] {
                 Robot::from_string(one_joint_arm("", "", "", R"(<visual><global fovy="nan"/></visual>)"));
               }),
               {"<visual> <global> fovy = nan", "mjModel::vis.global.fovy"});
  expect_names(error_of([] {
                 Robot::from_string(
                     one_joint_arm("", "", "", R"(<visual><headlight ambient="0.1 nan 0.1"/></visual>)"));
               }),
               {"<visual> <headlight> ambient = 0.1 nan 0.1"});
  expect_names(error_of([] {
                 Robot::from_string(one_joint_arm("", "", "", R"(<statistic center="inf 0 0"/>)"));
               }),
               {"<statistic> center = inf 0 0", "mjModel::stat.center"});
}

TEST(FiniteModel, LengthsAndMassesBeyondMuJoCosBoundAreRefused) {
  // issue 29, item 4: these loaded, and the first step diverged ("Nan, Inf or huge value")
  const auto in_world = [](const std::string& body) {
    return "<mujoco><worldbody>" + body + "</worldbody></mujoco>";
  };
  expect_names(error_of([&] {
                 Robot::from_string(in_world(R"(<body name="far" pos="1e300 0 0.3">
                   <geom size="0.1"/></body>)"));
               }),
               {"a value beyond 1e+10", "body 'far'", "attribute pos = 1e+300 0 0.3"});
  expect_names(error_of([&] {
                 Robot::from_string(in_world(R"(<body name="heavy"><joint axis="0 0 1"/>
                   <inertial pos="0 0 0" mass="1e308" diaginertia="1 1 1"/></body>)"));
               }),
               {"a value beyond 1e+10", "body 'heavy'", "<inertial> mass", "= 1e+308",
                "mjModel::body_mass"});
  expect_names(error_of([&] {
                 Robot::from_string(in_world(R"(<geom name="huge" size="1e11"/>)"));
               }),
               {"geom 'huge'", "attribute size = 1e+11"});
  // up to the bound a model loads
  EXPECT_NO_THROW(Robot::from_string(in_world(R"(<body pos="1e9 0 0"><geom size="0.1"/></body>)")));
}

TEST(FiniteModel, MuJoCosFirstStepWarningsAreLoadWarnings) {
  // a stiff spring pulled away from qpos0 on a light link: qacc beyond 1e10 at the first step,
  // though every model number is within bounds
  const Robot robot = Robot::from_string(
      one_joint_arm("", R"(stiffness="1e9" springref="1")", R"(mass="0.001")"));
  ASSERT_EQ(robot.load_warnings().size(), 1u);
  EXPECT_NE(robot.load_warnings()[0].find("Nan, Inf or huge value in QACC"), std::string::npos)
      << robot.load_warnings()[0];
  // a model that steps well warns of nothing
  EXPECT_TRUE(Robot::from_string(one_joint_arm("")).load_warnings().empty());
  // a first step that fails outright (contacts beyond a tiny arena) is a warning, not a refusal:
  // the model loaded before the check, and kinematics need no step
  std::string crowd = R"(<mujoco><size memory="100K"/><worldbody>)";
  for (int i = 0; i < 200; ++i)
    crowd += R"(<body pos=")" + std::to_string(0.01 * i) + R"( 0 0"><geom size="0.004"/></body>)";
  const Robot crowded = Robot::from_string(crowd + "</worldbody></mujoco>");
  ASSERT_FALSE(crowded.load_warnings().empty());
  EXPECT_NE(crowded.load_warnings().back().find("the first step at qpos0 fails: MuJoCo error: "),
            std::string::npos)
      << crowded.load_warnings().back();
}

TEST(FiniteModel, EveryBundledModelIsFinite) {
  for (const auto& name : Robot::bundled_names()) {
    const Robot robot = Robot::bundled(name);  // the constructor checks; check again explicitly
    EXPECT_NO_THROW(check_model_finite(robot.model(), name)) << name;
  }
}

}  // namespace
}  // namespace mjarm
