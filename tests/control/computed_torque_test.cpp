#include "mjarm/control/computed_torque.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "control/joint_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::panda;

// a random state inside the limits (shrunk), touching nothing, with joint speeds in ±1 rad/s
void random_state(const Chain& chain, mjData& d, std::mt19937& rng) {
  const mjModel& m = chain.robot().model();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  do {
    mj_resetData(&m, &d);
    for (int i = 0; i < chain.size(); ++i) {
      const double half = 0.4 * (chain.upper()[i] - chain.lower()[i]);
      d.qpos[chain.qpos_address(i)] = chain.center()[i] + half * u(rng);
      d.qvel[chain.dof_address(i)] = u(rng);
    }
    mj_forward(&m, &d);
  } while (d.ncon > 0);
}

TEST(ComputedTorqueController, MatchesTheDenseFormulaAndProducesTheCommandedAcceleration) {
  const Chain chain = panda();
  const mjModel& m = chain.robot().model();
  DataPtr d = chain.robot().make_data();
  ComputedTorqueOptions options;
  options.gains.kp = Eigen::VectorXd::LinSpaced(7, 100.0, 400.0);
  options.gains.kd = Eigen::VectorXd::LinSpaced(7, 20.0, 40.0);
  ComputedTorqueController ct(chain, options);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    random_state(chain, *d, rng);
    Reference ref;
    ref.joint.q = chain.gather(d->qpos) + 0.01 * Eigen::VectorXd::Random(7);
    ref.joint.qd = 0.1 * Eigen::VectorXd::Random(7);
    ref.joint.qdd = Eigen::VectorXd::Random(7);
    JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
    ct.compute(*d, ref, command);
    // plain formula from MuJoCo's dense mass matrix
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(m.nv, m.nv);
    mj_fullM(&m, d.get(), M.data());
    const Eigen::VectorXd q = chain.gather(d->qpos);
    const Eigen::VectorXd qd = Eigen::Map<const Eigen::VectorXd>(d->qvel, 7);
    const Eigen::VectorXd a = ref.joint.qdd + options.gains.kp.cwiseProduct(ref.joint.q - q) +
                              options.gains.kd.cwiseProduct(ref.joint.qd - qd);
    const Eigen::VectorXd expected = M.topLeftCorner(7, 7) * a +
                                     Eigen::Map<const Eigen::VectorXd>(d->qfrc_bias, 7) -
                                     Eigen::Map<const Eigen::VectorXd>(d->qfrc_passive, 7);
    EXPECT_LT((command.value - expected).norm(), 1e-9 * (1.0 + expected.norm()));
    // forward dynamics with that torque gives back the commanded acceleration
    test::apply_torque(chain, command, *d);
    mj_forward(&m, d.get());
    EXPECT_LT((Eigen::Map<const Eigen::VectorXd>(d->qacc, 7) - a).norm(), 1e-8 * (1.0 + a.norm()));
  }
}

TEST(ComputedTorqueController, TracksASinusoidOnEveryPandaJoint) {
  const Chain chain = panda();
  const Robot& robot = chain.robot();
  DataPtr d = robot.make_data();
  test::go_home(robot, *d);
  const Eigen::VectorXd home = chain.gather(d->qpos);
  // each joint swings ±0.2 rad at its own frequency and phase, starting on the reference
  const Eigen::VectorXd amplitude = Eigen::VectorXd::Constant(7, 0.2);
  const Eigen::VectorXd omega = Eigen::VectorXd::LinSpaced(7, 1.0, 2.5);  // rad/s
  const Eigen::VectorXd phase = Eigen::VectorXd::LinSpaced(7, 0.0, 3.0);
  auto at = [&](double t, Reference& r) {
    r.joint.q.resize(7);
    r.joint.qd.resize(7);
    r.joint.qdd.resize(7);
    for (int i = 0; i < 7; ++i) {
      const double s = std::sin(omega[i] * t + phase[i]), c = std::cos(omega[i] * t + phase[i]);
      r.joint.q[i] = home[i] + amplitude[i] * (s - std::sin(phase[i]));
      r.joint.qd[i] = amplitude[i] * omega[i] * c;
      r.joint.qdd[i] = -amplitude[i] * omega[i] * omega[i] * s;
    }
  };
  Reference start;
  at(0.0, start);
  chain.scatter(start.joint.q, d->qpos);
  for (int i = 0; i < 7; ++i) d->qvel[chain.dof_address(i)] = start.joint.qd[i];
  mj_forward(&robot.model(), d.get());

  ComputedTorqueController ct(chain);
  Eigen::VectorXd sum_sq = Eigen::VectorXd::Zero(7);
  int samples = 0;
  Reference now;
  test::run_loop(robot, *d, {&ct}, 2500, at, [&](const mjData& s) {  // 5 s
    at(s.time, now);
    sum_sq += (chain.gather(s.qpos) - now.joint.q).cwiseAbs2();
    ++samples;
  });
  const Eigen::VectorXd rms = (sum_sq / samples).cwiseSqrt();
  for (int i = 0; i < 7; ++i) EXPECT_LT(rms[i], 1e-3) << "joint " << i + 1;
  EXPECT_EQ(d->ncon, 0);
}

TEST(ComputedTorqueController, RejectsBadGainsAllocatesNothingKeepsWrongSizedCommands) {
  ComputedTorqueOptions bad;
  bad.gains.kd = Eigen::VectorXd::Ones(5);
  EXPECT_THROW(ComputedTorqueController(panda(), bad), Error);
  const Chain chain = panda();
  DataPtr d = chain.robot().make_data();
  test::go_home(chain.robot(), *d);
  ComputedTorqueController ct(chain);
  Reference ref;
  ref.joint.q = chain.gather(d->qpos);
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  const std::uint64_t calls = test::malloc_calls();
  for (int k = 0; k < 5; ++k) ct.compute(*d, ref, command);
  EXPECT_EQ(test::malloc_calls() - calls, 0u);
  // without velocity and acceleration references at rest on target: τ = g
  EXPECT_LT((command.value - Eigen::Map<const Eigen::VectorXd>(d->qfrc_bias, 7)).norm(), 1e-9);
  JointCommand wrong{CommandKind::torque, Eigen::VectorXd::Constant(8, 1.0)};
  ct.compute(*d, ref, wrong);
  EXPECT_EQ(wrong.value, Eigen::VectorXd::Constant(8, 1.0));
  EXPECT_EQ(ct.name(), "ct");
}

}  // namespace
}  // namespace mjarm
