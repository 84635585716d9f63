#include "mjarm/control/gravity_compensation.hpp"

#include <gtest/gtest.h>

#include <random>

#include "control/joint_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

Eigen::VectorXd chain_values(const Chain& chain, const double* full) {
  Eigen::VectorXd v(chain.size());
  for (int i = 0; i < chain.size(); ++i) v[i] = full[chain.dof_address(i)];
  return v;
}

// a random configuration inside the limits (shrunk by 20 %) that touches nothing
void random_free_pose(const Chain& chain, mjData& d, std::mt19937& rng) {
  const mjModel& m = chain.robot().model();
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  do {
    mj_resetData(&m, &d);
    for (int i = 0; i < chain.size(); ++i) {
      const double mid = 0.5 * (chain.lower()[i] + chain.upper()[i]);
      d.qpos[chain.qpos_address(i)] = mid + u(rng) * (chain.upper()[i] - chain.lower()[i]);
    }
    mj_forward(&m, &d);
  } while (d.ncon > 0);
}

TEST(GravityHoldController, TorqueAtRestEqualsMujocoBias) {
  std::mt19937 rng(1);
  for (const char* name : {"panda_torque", "iiwa14_torque", "ur5e_torque", "planar2_torque"}) {
    SCOPED_TRACE(name);
    const Robot robot = Robot::bundled(name);
    const Chain chain(robot, std::string(name) == "planar2_torque" ? "tip" : "attachment_site");
    GravityHoldController hold(chain);
    DataPtr d = robot.make_data();
    JointCommand command{CommandKind::position, Eigen::VectorXd::Zero(chain.size())};
    for (int trial = 0; trial < 10; ++trial) {
      random_free_pose(chain, *d, rng);  // q̇ = 0: qfrc_bias is the gravity torque alone
      hold.compute(*d, Reference{}, command);
      EXPECT_EQ(command.kind, CommandKind::torque);
      const Eigen::VectorXd bias = chain_values(chain, d->qfrc_bias);
      EXPECT_LT((command.value - bias).norm(), 1e-10 * (1.0 + bias.norm()));
    }
  }
}

TEST(GravityHoldController, FullTermIsTheBiasWhileMoving) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  GravityHoldController gravity(chain), full(chain, BiasTerm::full);
  DataPtr d = robot.make_data();
  std::mt19937 rng(2);
  random_free_pose(chain, *d, rng);
  for (int i = 0; i < robot.nv(); ++i) d->qvel[i] = 1.5;
  mj_forward(&robot.model(), d.get());
  JointCommand a{CommandKind::torque, Eigen::VectorXd::Zero(7)}, b = a;
  gravity.compute(*d, Reference{}, a);
  full.compute(*d, Reference{}, b);
  const Eigen::VectorXd bias = chain_values(chain, d->qfrc_bias);
  EXPECT_LT((b.value - bias).norm(), 1e-12 * (1.0 + bias.norm()));
  EXPECT_GT((a.value - bias).norm(), 0.1);  // the velocity terms are not small at 1.5 rad/s
}

TEST(GravityHoldController, HoldsThePandaStillForTenSeconds) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  DataPtr d = robot.make_data();
  std::mt19937 rng(4);
  for (int pose = 0; pose < 3; ++pose) {
    if (pose == 0) {
      test::go_home(robot, *d);
    } else {
      random_free_pose(chain, *d, rng);
    }
    const Eigen::VectorXd q0 = chain.gather(d->qpos);
    GravityHoldController hold(chain);
    double drift = 0.0;
    test::run_loop(robot, *d, {&hold}, 5000, {}, [&](const mjData& s) {  // 10 s at 2 ms
      drift = std::max(drift, (chain.gather(s.qpos) - q0).cwiseAbs().maxCoeff());
    });
    EXPECT_LT(drift, 1e-4) << "pose " << pose;
  }
  // the same test can fail: without the controller the arm falls
  test::go_home(robot, *d);
  const Eigen::VectorXd q0 = chain.gather(d->qpos);
  test::run_loop(robot, *d, {}, 500, {});
  EXPECT_GT((chain.gather(d->qpos) - q0).cwiseAbs().maxCoeff(), 0.05);
}

TEST(ServoBiasCompensation, OffsetIsBiasOverStiffnessAndNeedsServos) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  ServoBiasCompensation comp(chain);
  DataPtr d = robot.make_data();
  test::go_home(robot, *d);
  comp.update(*d);
  for (int i = 0; i < chain.size(); ++i) {
    EXPECT_EQ(comp.stiffness()[i], robot.model().actuator_gainprm[mjNGAIN * *chain.actuator(i)]);
    EXPECT_DOUBLE_EQ(comp.offset()[i], comp.bias()[i] / comp.stiffness()[i]);
  }
  EXPECT_LT((comp.bias() - chain_values(chain, d->qfrc_bias)).norm(), 1e-10);
  Eigen::VectorXd targets = Eigen::VectorXd::Ones(7);
  comp.apply(targets);
  EXPECT_LT((targets - Eigen::VectorXd::Ones(7) - comp.offset()).norm(), 1e-15);

  // motors are not servos: the error names the actuator and the joint
  const Robot torque = Robot::bundled("panda_torque");
  try {
    ServoBiasCompensation bad(Chain(torque, "attachment_site"));
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("joint1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("motor"), std::string::npos) << e.what();
  }
}

TEST(GravityCompensationController, ServosStopSagging) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  DataPtr d = robot.make_data();
  test::go_home(robot, *d);
  const Eigen::VectorXd home = chain.gather(d->qpos);
  // the reference is home; plain servos settle below it, offset servos on it
  auto reference = [&](double, Reference& r) { r.joint.q = home; };
  GravityCompensationController comp(chain);
  test::run_loop(robot, *d, {&comp}, 1500, reference);
  const double compensated = (chain.gather(d->qpos) - home).cwiseAbs().maxCoeff();
  EXPECT_LT(compensated, 1e-6);
  EXPECT_GT(comp.internal_values()[1], 0.0);  // the offsets are in use

  test::go_home(robot, *d);
  mju_copy(d->ctrl, d->qpos, 7);  // plain servos: ctrl = home
  for (int s = 0; s < 1500; ++s) mj_step(&robot.model(), d.get());
  const double sag = (chain.gather(d->qpos) - home).cwiseAbs().maxCoeff();
  EXPECT_GT(sag, 100.0 * compensated);
  EXPECT_GT(sag, 1e-4);
}

TEST(GravityCompensationController, HoldsWhereItStartedWithoutReference) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  DataPtr d = robot.make_data();
  test::go_home(robot, *d);
  const Eigen::VectorXd start = chain.gather(d->qpos);
  GravityCompensationController comp(chain);
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  comp.compute(*d, Reference{}, command);
  EXPECT_EQ(command.kind, CommandKind::position);
  EXPECT_LT((command.value - start - comp.compensation().offset()).norm(), 1e-15);
  // a moved arm keeps the latched position until reset
  d->qpos[0] += 0.3;
  mj_forward(&robot.model(), d.get());
  comp.compute(*d, Reference{}, command);
  EXPECT_NEAR(command.value[0] - comp.compensation().offset()[0], start[0], 1e-15);
  comp.reset();
  comp.compute(*d, Reference{}, command);
  EXPECT_NEAR(command.value[0] - comp.compensation().offset()[0], start[0] + 0.3, 1e-15);
}

TEST(GravityControllers, ComputeAllocatesNothingAndKeepsWrongSizedCommands) {
  const Robot servo_robot = Robot::bundled("panda");
  const Robot torque_robot = Robot::bundled("panda_torque");
  GravityCompensationController comp(Chain(servo_robot, "attachment_site"));
  GravityHoldController hold(Chain(torque_robot, "attachment_site"));
  DataPtr ds = servo_robot.make_data(), dt = torque_robot.make_data();
  test::go_home(servo_robot, *ds);
  test::go_home(torque_robot, *dt);
  Reference ref;
  ref.joint.q = Eigen::VectorXd::Zero(7);
  JointCommand a{CommandKind::torque, Eigen::VectorXd::Zero(7)}, b = a;
  comp.compute(*ds, ref, a);  // first call latches
  const std::uint64_t calls = test::malloc_calls();
  for (int k = 0; k < 5; ++k) {
    comp.compute(*ds, ref, a);
    hold.compute(*dt, ref, b);
  }
  EXPECT_EQ(test::malloc_calls() - calls, 0u);
  JointCommand wrong{CommandKind::position, Eigen::VectorXd::Constant(3, 7.0)};
  hold.compute(*dt, ref, wrong);
  EXPECT_EQ(wrong.kind, CommandKind::position);
  EXPECT_EQ(wrong.value, Eigen::VectorXd::Constant(3, 7.0));
}

}  // namespace
}  // namespace mjarm
