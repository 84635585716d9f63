#include "mjarm/control/joint_pd.hpp"

#include <gtest/gtest.h>

#include <random>

#include "control/joint_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::panda;

// the gravity torque computed by MuJoCo on a scratch copy at rest
Eigen::VectorXd mujoco_gravity(const Chain& chain, const mjData& d) {
  const mjModel& m = chain.robot().model();
  DataPtr s(mj_copyData(nullptr, &m, &d));
  mju_zero(s->qvel, m.nv);
  mj_forward(&m, s.get());
  Eigen::VectorXd g(chain.size());
  for (int i = 0; i < chain.size(); ++i) g[i] = s->qfrc_bias[chain.dof_address(i)];
  return g;
}

TEST(JointPdGains, ExpandsScalarsAndRejectsBadValues) {
  const JointPdGains g = JointPdGains::uniform(50.0, 3.0).expanded(4, "test");
  EXPECT_EQ(g.kp, Eigen::VectorXd::Constant(4, 50.0));
  EXPECT_EQ(g.kd, Eigen::VectorXd::Constant(4, 3.0));
  const JointPdGains c = JointPdGains::critically_damped(10.0);
  EXPECT_DOUBLE_EQ(c.kp[0], 100.0);
  EXPECT_DOUBLE_EQ(c.kd[0], 20.0);
  JointPdOptions wrong_size;
  wrong_size.gains.kp = Eigen::VectorXd::Ones(3);
  try {
    JointPdController pd(panda(), wrong_size);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("kp"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("joint-pd"), std::string::npos) << e.what();
  }
  JointPdOptions negative;
  negative.gains.kd = Eigen::VectorXd::Constant(7, 1.0);
  negative.gains.kd[5] = -1.0;
  EXPECT_THROW(JointPdController(panda(), negative), Error);
  JointPdOptions not_finite;
  not_finite.gains.kp[0] = NAN;
  EXPECT_THROW(JointPdController(panda(), not_finite), Error);
}

TEST(JointPdController, ComputesTheLawWithAndWithoutGravity) {
  const Chain chain = panda();
  DataPtr d = chain.robot().make_data();
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  JointPdOptions options;
  options.gains.kp = Eigen::VectorXd::LinSpaced(7, 10.0, 70.0);
  options.gains.kd = Eigen::VectorXd::Constant(1, 4.0);
  JointPdController with_g(chain, options);
  options.gravity_compensation = false;
  JointPdController without_g(chain, options);
  for (int trial = 0; trial < 10; ++trial) {
    for (int i = 0; i < 7; ++i) {
      d->qpos[i] = chain.center()[i] + 0.5 * u(rng);
      d->qvel[i] = u(rng);
    }
    mj_forward(&chain.robot().model(), d.get());
    Reference ref;
    ref.joint.q = chain.center();
    ref.joint.qd = Eigen::VectorXd::Constant(7, 0.2);
    const Eigen::VectorXd q = chain.gather(d->qpos);
    const Eigen::VectorXd qd = Eigen::Map<const Eigen::VectorXd>(d->qvel, 7);
    const Eigen::VectorXd pd =
        options.gains.kp.cwiseProduct(ref.joint.q - q) + 4.0 * (ref.joint.qd - qd);
    JointCommand a{CommandKind::position, Eigen::VectorXd::Zero(7)}, b = a;
    with_g.compute(*d, ref, a);
    without_g.compute(*d, ref, b);
    EXPECT_EQ(a.kind, CommandKind::torque);
    EXPECT_LT((b.value - pd).norm(), 1e-12);
    EXPECT_LT((a.value - pd - mujoco_gravity(chain, *d)).norm(), 1e-9);
    EXPECT_DOUBLE_EQ(with_g.internal_values()[0], (ref.joint.q - q).norm());
    // without a position reference only damping towards q̇_d is left
    ref.joint.q.resize(0);
    without_g.compute(*d, ref, b);
    EXPECT_LT((b.value - 4.0 * (ref.joint.qd - qd)).norm(), 1e-12);
    EXPECT_EQ(without_g.internal_values()[2], 0.0);
  }
}

TEST(JointPdController, SettlesOnTargetWithGravityAndBelowItWithout) {
  const Chain chain = panda();
  const Robot& robot = chain.robot();
  DataPtr d = robot.make_data();
  JointPdOptions options;
  options.gains = JointPdGains::uniform(150.0, 15.0);
  test::go_home(robot, *d);
  const Eigen::VectorXd target = chain.gather(d->qpos) + Eigen::VectorXd::Constant(7, 0.15);
  auto reference = [&](double, Reference& r) { r.joint.q = target; };
  JointPdController pd(chain, options);
  test::run_loop(robot, *d, {&pd}, 2500, reference);  // 5 s
  EXPECT_LT((chain.gather(d->qpos) - target).cwiseAbs().maxCoeff(), 1e-4);

  // without g the arm settles where the spring holds gravity: Kp·(q_d − q) = g(q)
  options.gravity_compensation = false;
  JointPdController plain(chain, options);
  test::go_home(robot, *d);
  test::run_loop(robot, *d, {&plain}, 2500, reference);
  const Eigen::VectorXd q = chain.gather(d->qpos);
  const Eigen::VectorXd g = mujoco_gravity(chain, *d);
  EXPECT_GT((q - target).cwiseAbs().maxCoeff(), 0.01);
  EXPECT_LT((150.0 * (target - q) - g).cwiseAbs().maxCoeff(), 1e-2);
}

TEST(JointPdController, ComputeAllocatesNothingAndKeepsWrongSizedCommands) {
  const Chain chain = panda();
  DataPtr d = chain.robot().make_data();
  test::go_home(chain.robot(), *d);
  JointPdController pd(chain);
  Reference ref;
  ref.joint.q = Eigen::VectorXd::Zero(7);
  ref.joint.qd = Eigen::VectorXd::Zero(7);
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  const std::uint64_t calls = test::malloc_calls();
  for (int k = 0; k < 5; ++k) pd.compute(*d, ref, command);
  EXPECT_EQ(test::malloc_calls() - calls, 0u);
  JointCommand wrong{CommandKind::position, Eigen::VectorXd::Constant(2, 1.0)};
  pd.compute(*d, ref, wrong);
  EXPECT_EQ(wrong.value, Eigen::VectorXd::Constant(2, 1.0));
  EXPECT_EQ(wrong.kind, CommandKind::position);
  EXPECT_EQ(pd.name(), "joint-pd");
  EXPECT_EQ(pd.internal_names().size(), pd.internal_values().size());
}

}  // namespace
}  // namespace mjarm
