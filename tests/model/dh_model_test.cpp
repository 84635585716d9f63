#include "mjarm/model/dh_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

constexpr double pi = std::numbers::pi;

// the published tables (as tests/model/dh_test.cpp checks the bundled models against)
DhArm panda_table() {
  DhArm arm;
  arm.name = "panda_dh";
  arm.convention = DhConvention::modified;
  arm.links = {{.d = 0.333},
               {.alpha = -pi / 2},
               {.d = 0.316, .alpha = pi / 2},
               {.a = 0.0825, .alpha = pi / 2},
               {.a = -0.0825, .d = 0.384, .alpha = -pi / 2},
               {.alpha = pi / 2},
               {.a = 0.088, .alpha = pi / 2}};
  arm.tool(2, 3) = 0.107;
  return arm;
}

DhArm iiwa14_table() {
  DhArm arm;
  arm.name = "iiwa14_dh";
  arm.links = {{.d = 0.36, .alpha = -pi / 2},
               {.alpha = pi / 2},
               {.d = 0.42, .alpha = pi / 2},
               {.alpha = -pi / 2},
               {.d = 0.4, .alpha = -pi / 2},
               {.alpha = pi / 2},
               {.d = 0.126}};
  return arm;
}

DhArm ur5e_table() {
  DhArm arm;
  arm.name = "ur5e_dh";
  arm.links = {{.d = 0.1625, .alpha = pi / 2},
               {.a = -0.425},
               {.a = -0.3922},
               {.d = 0.1333, .alpha = pi / 2},
               {.d = 0.0997, .alpha = -pi / 2},
               {.d = 0.0996}};
  return arm;
}

/// The DH arm's end site against the bundled model's flange at random joint values (the
/// bundled model's other joints, fingers say, left at qpos0).
void expect_same_flange(const DhArm& table, const std::string& bundled,
                        const std::vector<std::string>& joints) {
  const Robot dh = dh_robot(table);
  const Robot model = Robot::bundled(bundled);
  DataPtr a = dh.make_data(), b = model.make_data();
  const int end = dh.site("end"), flange = model.site("attachment_site");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  double worst_p = 0.0, worst_R = 0.0;
  for (int sample = 0; sample < 200; ++sample) {
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const double q = u(rng);
      a->qpos[i] = q;
      b->qpos[model.model().jnt_qposadr[model.joint(joints[i])]] = q;
    }
    mj_kinematics(&dh.model(), a.get());
    mj_kinematics(&model.model(), b.get());
    const Eigen::Map<const Eigen::Vector3d> pa(a->site_xpos + 3 * end),
        pb(b->site_xpos + 3 * flange);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> Ra(a->site_xmat + 9 * end),
        Rb(b->site_xmat + 9 * flange);
    worst_p = std::max(worst_p, (pa - pb).norm());
    worst_R = std::max(worst_R, (Ra - Rb).norm());
  }
  EXPECT_LT(worst_p, 1e-9) << bundled;
  EXPECT_LT(worst_R, 1e-9) << bundled;
}

std::vector<std::string> numbered(int n) {
  std::vector<std::string> names;
  for (int i = 1; i <= n; ++i) names.push_back("joint" + std::to_string(i));
  return names;
}

TEST(DhModel, ThePublishedTablesBuildTheBundledArms) {
  expect_same_flange(panda_table(), "panda", numbered(7));
  expect_same_flange(iiwa14_table(), "iiwa14", numbered(7));
  expect_same_flange(ur5e_table(), "ur5e",
                     {"shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"});
}

TEST(DhModel, APlanarTwoLinkArmPutsItsTipWhereTheBookSays) {
  DhArm arm;
  arm.links = {{.a = 0.3}, {.a = 0.3}};
  arm.actuators = DhActuators::none;
  const Robot robot = dh_robot(arm);
  DataPtr d = robot.make_data();
  d->qpos[0] = 0.0;
  d->qpos[1] = pi / 4;
  mj_kinematics(&robot.model(), d.get());
  const Eigen::Map<const Eigen::Vector3d> tip(d->site_xpos + 3 * robot.site("end"));
  EXPECT_NEAR(tip.x(), 0.512132, 5e-7);
  EXPECT_NEAR(tip.y(), 0.212132, 5e-7);
  EXPECT_NEAR(tip.z(), 0.0, 1e-15);
  EXPECT_EQ(robot.nu(), 0);
}

TEST(DhModel, MassesActuatorsAndLimitsReachTheModel) {
  DhArm arm = ur5e_table();
  arm.links[1].mass = 8.393;
  arm.links[2].com = Eigen::Vector3d(-0.2, 0.0, 0.01);
  arm.links[2].inertia = Eigen::Vector3d(0.1, 0.2, 0.3);
  arm.links[0].lower = -1.0;
  arm.links[0].upper = 2.0;
  arm.links[5].prismatic = true;
  arm.actuators = DhActuators::position;
  const Robot robot = dh_robot(arm);
  const mjModel& m = robot.model();
  EXPECT_NEAR(m.body_mass[robot.body("link2")], 8.393, 1e-12);
  EXPECT_NEAR(m.body_mass[robot.body("link3")], 1.0, 1e-12);
  EXPECT_EQ(m.jnt_range[0], -1.0);
  EXPECT_EQ(m.jnt_range[1], 2.0);
  EXPECT_EQ(m.jnt_type[5], mjJNT_SLIDE);
  EXPECT_EQ(robot.nu(), 6);
  EXPECT_EQ(m.actuator_gainprm[0], arm.position_gain);
  EXPECT_GE(robot.keyframe("zero"), 0);
}

TEST(DhModel, BadTablesAreRefusedNamingTheRow) {
  const auto message = [](const DhArm& arm) {
    try {
      dh_mjcf(arm);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  DhArm arm = ur5e_table();
  arm.links[2].a = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(arm).find("row 3"), std::string::npos) << message(arm);
  arm = ur5e_table();
  arm.links[1].mass = 0.0;
  EXPECT_NE(message(arm).find("mass"), std::string::npos) << message(arm);
  arm = ur5e_table();
  arm.links[0].lower = 1.0;
  arm.links[0].upper = -1.0;
  EXPECT_NE(message(arm).find("lower < upper"), std::string::npos) << message(arm);
  arm = ur5e_table();
  arm.links.clear();
  EXPECT_NE(message(arm).find("no rows"), std::string::npos) << message(arm);
  arm = ur5e_table();
  arm.base(0, 0) = 2.0;
  EXPECT_NE(message(arm).find("rigid"), std::string::npos) << message(arm);
  arm = ur5e_table();
  arm.name = "a\"b";
  EXPECT_NE(message(arm).find("name"), std::string::npos) << message(arm);
}

}  // namespace
}  // namespace mjarm
