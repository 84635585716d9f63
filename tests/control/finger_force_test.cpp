// FingerForceController: free positioning, the squeeze settling at the grasp force (measured from
// MuJoCo's contact forces), centring, release, the servo form and its reach, bad input.

#include "mjarm/control/finger_force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "control/joint_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/contacts.hpp"
#include "support/error_message.hpp"
#include "support/finger_rig.hpp"

namespace mjarm {
namespace {

struct FingerRig {
  Robot robot;
  Chain fingers{robot, {"left", "right"}, "hand"};
  DataPtr d = robot.make_data();
  explicit FingerRig(bool servos, bool gravity = false, double kp = 400.0)
      : robot(Robot::from_string(test::finger_rig(servos, gravity, kp))) {
    d->qpos[robot.joint_info(robot.joint("left")).qpos_address] = 0.04;
    d->qpos[robot.joint_info(robot.joint("right")).qpos_address] = 0.04;
    mj_forward(&robot.model(), d.get());
  }
  FingerForceOptions options(CommandKind kind, double force = 6.0) const {
    FingerForceOptions o;
    o.command = kind;
    o.grasp_force = force;
    o.finger_geoms = {{robot.geom("left")}, {robot.geom("right")}};
    o.object_geoms = {robot.geom("cube")};
    return o;
  }
  // the normal force each finger presses on the cube with, from MuJoCo's constraint forces
  std::array<double, 2> squeeze() const {
    mj_forward(&robot.model(), d.get());
    const std::vector<ContactForce> contacts = contact_forces(robot.model(), *d);
    std::array<double, 2> out{0.0, 0.0};
    const int cube = robot.body("cube");
    for (const ContactForce& c : contacts) {
      const int finger = c.geom1 == robot.geom("left") || c.geom2 == robot.geom("left") ? 0 : 1;
      // the force on the cube, along the finger's closing direction (left closes towards −y)
      const Eigen::Vector3d on_cube = c.body2 == cube ? c.force_W : Eigen::Vector3d(-c.force_W);
      out[finger] += finger == 0 ? -on_cube.y() : on_cube.y();
    }
    return out;
  }
  double cube_y() const { return d->xpos[3 * robot.body("cube") + 1]; }
};

TEST(FingerForceController, SqueezeSettlesAtTheGraspForceAndCentresTheObject) {
  FingerRig rig(false);
  FingerForceController fingers(rig.fingers, rig.options(CommandKind::torque, 6.0));
  test::run_loop(rig.robot, *rig.d, {&fingers}, 1000,
                 [](double, Reference& r) { r.gripper = 1.0; });
  EXPECT_EQ(fingers.touching_count(), 2);
  const std::array<double, 2> f = rig.squeeze();
  EXPECT_NEAR(f[0], 6.0, 0.05);
  EXPECT_NEAR(f[1], 6.0, 0.05);
  EXPECT_NEAR(rig.cube_y(), 0.0, 2e-4);  // started 5 mm off centre
  EXPECT_NEAR(fingers.internal_values()[2], 6.0, 0.05);
  // the force follows the setting, not the object's size
  FingerRig other(false);
  FingerForceController stronger(other.fingers, other.options(CommandKind::torque, 12.0));
  test::run_loop(other.robot, *other.d, {&stronger}, 1000,
                 [](double, Reference& r) { r.gripper = 1.0; });
  EXPECT_NEAR(other.squeeze()[0], 12.0, 0.1);
}

TEST(FingerForceController, FreeFingersFollowTheFractionAndLetGo) {
  FingerRig rig(false);
  FingerForceOptions o = rig.options(CommandKind::torque);
  o.object_geoms.clear();  // never "touching": a position gripper
  o.finger_geoms.clear();
  FingerForceController free(rig.fingers, o);
  test::run_loop(rig.robot, *rig.d, {&free}, 500, [](double, Reference& r) { r.gripper = 0.25; });
  // stops on the cube at 0.015 (outside 0.04·0.75 = 0.03 it is free)
  EXPECT_NEAR(rig.fingers.gather(rig.d->qpos)[0], 0.03, 2e-4);
  EXPECT_EQ(free.touching_count(), 0);

  FingerRig held(false);
  FingerForceController grip(held.fingers, held.options(CommandKind::torque));
  test::run_loop(held.robot, *held.d, {&grip}, 600, [](double, Reference& r) { r.gripper = 1.0; });
  ASSERT_EQ(grip.touching_count(), 2);
  // opening: the reference passes the fingers, the force reverses, they leave the cube
  test::run_loop(held.robot, *held.d, {&grip}, 600, [](double, Reference& r) { r.gripper = 0.0; });
  EXPECT_EQ(grip.touching_count(), 0);
  EXPECT_NEAR(held.fingers.gather(held.d->qpos)[1], 0.04, 2e-4);
}

TEST(FingerForceController, ServoTargetsGiveTheForceWithinTheServosReach) {
  // kp = 3200: the servo reaches kp·0.015 = 48 N from the cube's faces, so 6 N is met exactly
  FingerRig rig(true, false, 3200.0);
  FingerForceController fingers(rig.fingers, rig.options(CommandKind::position, 6.0));
  EXPECT_EQ(fingers.command_kind(), CommandKind::position);
  test::run_loop(rig.robot, *rig.d, {&fingers}, 1000,
                 [](double, Reference& r) { r.gripper = 1.0; });
  std::array<double, 2> f = rig.squeeze();
  EXPECT_NEAR(f[0], 6.0, 0.05);
  EXPECT_NEAR(f[1], 6.0, 0.05);
  // kp = 200: at most 200 N/m · 15 mm = 3 N before the target would leave ctrlrange [0, 0.04]
  FingerRig weak(true, false, 200.0);
  FingerForceController capped(weak.fingers, weak.options(CommandKind::position, 6.0));
  Eigen::VectorXd lowest = Eigen::VectorXd::Constant(2, 1.0);
  test::run_loop(
      weak.robot, *weak.d, {&capped}, 1000, [](double, Reference& r) { r.gripper = 1.0; },
      [&](const mjData& d) {
        for (int i = 0; i < 2; ++i) lowest[i] = std::min(lowest[i], d.ctrl[i]);
      });
  f = weak.squeeze();
  const Eigen::VectorXd q = weak.fingers.gather(weak.d->qpos);  // the faces, a little inside
  EXPECT_NEAR(f[0], 200.0 * q[0], 0.02);
  EXPECT_NEAR(f[1], 200.0 * q[1], 0.02);
  EXPECT_GT(f[0], 2.8);
  EXPECT_GE(lowest.minCoeff(), 0.0);  // never clipped
}

TEST(FingerForceController, ComputeAllocatesNothing) {
  FingerRig rig(false);
  FingerForceController fingers(rig.fingers, rig.options(CommandKind::torque));
  Reference r;
  r.gripper = 1.0;
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(2)};
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 100; ++k) fingers.compute(*rig.d, r, command);
  (void)fingers.internal_values();
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(FingerForceController, BadInput) {
  FingerRig rig(false);
  const auto error = [&](FingerForceOptions o) {
    return test::error_of([&] { FingerForceController(rig.fingers, o); });
  };
  FingerForceOptions o = rig.options(CommandKind::torque);
  o.grasp_force = 0.0;
  EXPECT_NE(error(o).find("grasp_force"), std::string::npos);
  o = rig.options(CommandKind::torque);
  o.max_force = 1.0;
  EXPECT_NE(error(o).find("max_force"), std::string::npos);
  o = rig.options(CommandKind::torque);
  o.free_damping = NAN;
  EXPECT_NE(error(o).find("free_damping"), std::string::npos);
  o = rig.options(CommandKind::torque);
  o.finger_geoms.pop_back();
  EXPECT_NE(error(o).find("one list per finger joint"), std::string::npos);
  o = rig.options(CommandKind::torque);
  o.object_geoms = {99};
  EXPECT_NE(error(o).find("out of range"), std::string::npos);
  o = rig.options(CommandKind::torque);
  o.open = Eigen::Vector3d::Zero();
  EXPECT_NE(error(o).find("open needs"), std::string::npos);
  // position targets need position servos
  EXPECT_NE(error(rig.options(CommandKind::position)).find("position servo"), std::string::npos);
}

// a huge option is named in its shortest form, not with 309 digits and six decimals (issue 29)
TEST(FingerForceController, HugeOptionsArePrintedShortInItsErrors) {
  FingerRig rig(false);
  FingerForceOptions o = rig.options(CommandKind::torque, 1e308);
  o.max_force = 1e307;
  EXPECT_EQ(test::error_of([&] { FingerForceController(rig.fingers, o); }),
            "fingers: max_force (1e+307 N) must be ≥ grasp_force (1e+308 N)");
  o = rig.options(CommandKind::torque);
  o.free_damping = -1e308;
  EXPECT_EQ(test::error_of([&] { FingerForceController(rig.fingers, o); }),
            "fingers: free_damping must be finite and ≥ 0 [N·s/m], got -1e+308");
}

}  // namespace
}  // namespace mjarm
