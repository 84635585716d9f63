#include "mjarm/dynamics/chain_dynamics.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "dynamics/dynamics_test_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

using test::random_state;

/// The chain's block of MuJoCo's dense mass matrix.
Eigen::MatrixXd mujoco_mass_block(const Chain& chain, const mjData* d) {
  const mjModel& m = chain.robot().model();
  std::vector<double> full(static_cast<std::size_t>(m.nv * m.nv));
  mj_fullM(&m, d, full.data());
  Eigen::MatrixXd M(chain.size(), chain.size());
  for (int r = 0; r < chain.size(); ++r) {
    for (int c = 0; c < chain.size(); ++c) {
      M(r, c) = full[static_cast<std::size_t>(chain.dof_address(r) * m.nv + chain.dof_address(c))];
    }
  }
  return M;
}

Eigen::VectorXd chain_values(const Chain& chain, const double* full) {
  Eigen::VectorXd v(chain.size());
  for (int i = 0; i < chain.size(); ++i) v[i] = full[chain.dof_address(i)];
  return v;
}

/// Runs @p check on @p trials random states of every test arm and of the tricky test arm.
template <class Check>
void for_each_arm_state(Check check, int trials = 20) {
  std::vector<Chain> chains;
  for (const auto& arm : test::dynamics_arms()) chains.emplace_back(Robot::bundled(arm.robot), arm.frame);
  chains.emplace_back(Robot::from_string(test::kTrickyArm), "tool");
  std::mt19937 rng(11);
  for (const Chain& chain : chains) {
    SCOPED_TRACE(chain.robot().name());
    DataPtr d = chain.robot().make_data();
    ChainDynamics dyn(chain);
    for (int trial = 0; trial < trials; ++trial) {
      random_state(chain, d.get(), rng);
      dyn.update(*d);
      check(chain, dyn, d.get(), rng);
    }
  }
}

TEST(ChainDynamics, MassMatrixBiasAndJacobianMatchMujoco) {
  for_each_arm_state([](const Chain& chain, const ChainDynamics& dyn, mjData* d, std::mt19937&) {
    EXPECT_LT((dyn.mass_matrix() - mujoco_mass_block(chain, d)).norm(), 1e-12);
    EXPECT_LT((dyn.bias() - chain_values(chain, d->qfrc_bias)).norm(), 1e-12);
    EXPECT_EQ((dyn.q() - chain.gather(d->qpos)).norm(), 0.0);
    Matrix6Xd J(6, chain.size());
    mujoco_frame_jacobian(chain, *d, J);
    EXPECT_LT((dyn.jacobian() - J).norm(), 1e-12);
    EXPECT_TRUE(dyn.pose().is_approx(frame_pose(chain.robot().model(), *d, chain.frame()), 0.0));
  });
}

TEST(ChainDynamics, GravityMatchesRneWithZeroVelocity) {
  for_each_arm_state([](const Chain& chain, const ChainDynamics& dyn, mjData* d, std::mt19937&) {
    // MuJoCo's recursive Newton-Euler on a scratch copy with q̇ = 0 and q̈ = 0 gives g(q)
    const mjModel& m = chain.robot().model();
    DataPtr scratch(mj_copyData(nullptr, &m, d));
    mju_zero(scratch->qvel, m.nv);
    mj_forward(&m, scratch.get());
    std::vector<double> rne(static_cast<std::size_t>(m.nv));
    mj_rne(&m, scratch.get(), 0, rne.data());
    const Eigen::VectorXd expected = chain_values(chain, rne.data());
    EXPECT_LT((dyn.gravity() - expected).norm(), 1e-10 * (1.0 + expected.norm()));
    // and it is the bias force at rest
    EXPECT_LT((dyn.gravity() - chain_values(chain, scratch->qfrc_bias)).norm(), 1e-10 * (1.0 + expected.norm()));
  });
}

TEST(ChainDynamics, InverseDynamicsMatchesMjInverse) {
  for_each_arm_state([](const Chain& chain, ChainDynamics& dyn, mjData* d, std::mt19937& rng) {
    const mjModel& m = chain.robot().model();
    std::uniform_real_distribution<double> u(-5.0, 5.0);
    Eigen::VectorXd qdd(chain.size());
    for (int i = 0; i < chain.size(); ++i) qdd[i] = u(rng);
    Eigen::VectorXd tau(chain.size());
    dyn.inverse_dynamics(*d, qdd, tau);
    // mj_inverse (recursive Newton-Euler + armature) on a scratch copy: it returns
    // M·q̈ + h − τ_passive − τ_constraint
    DataPtr scratch(mj_copyData(nullptr, &m, d));
    mju_zero(scratch->qacc, m.nv);
    for (int i = 0; i < chain.size(); ++i) scratch->qacc[chain.dof_address(i)] = qdd[i];
    mj_inverse(&m, scratch.get());
    Eigen::VectorXd expected = chain_values(chain, scratch->qfrc_inverse) +
                               chain_values(chain, scratch->qfrc_passive) +
                               chain_values(chain, scratch->qfrc_constraint);
    EXPECT_LT((tau - expected).norm(), 1e-9 * (1.0 + expected.norm()));
    // the dense form agrees too
    const Eigen::VectorXd dense = dyn.mass_matrix() * qdd + dyn.bias();
    EXPECT_LT((tau - dense).norm(), 1e-10 * (1.0 + dense.norm()));
  });
}

TEST(ChainDynamics, BiasAccelerationMatchesFiniteDifferences) {
  for_each_arm_state([](const Chain& chain, const ChainDynamics& dyn, mjData* d, std::mt19937&) {
    const mjModel& m = chain.robot().model();
    // velocity of E equals J·q̇ (every joint on these paths belongs to the chain)
    const Vector6d Jqd = dyn.jacobian() * dyn.qd();
    EXPECT_LT((dyn.velocity() - Jqd).norm(), 1e-11 * (1.0 + Jqd.norm()));
    // with q̈ = 0 the state moves along q(t) = q + t·q̇; difference E's velocity in time
    const double eps = 1e-6;
    DataPtr scratch(mj_copyData(nullptr, &m, d));
    ChainDynamics probe(chain);
    const auto velocity_at = [&](double t) {
      mju_copy(scratch->qpos, d->qpos, m.nq);
      mj_integratePos(&m, scratch->qpos, d->qvel, t);
      mj_forward(&m, scratch.get());
      probe.update(*scratch);
      return probe.velocity();
    };
    const Vector6d fd = finite_difference_derivative(velocity_at, 0.0, eps);
    EXPECT_LT((dyn.bias_acceleration() - fd).norm(), 1e-6 * (1.0 + fd.norm()));
    // and ChainKinematics' own recursion agrees
    ChainKinematics kin(chain);
    kin.set_fixed_qpos(Eigen::Map<const Eigen::VectorXd>(d->qpos, m.nq));
    kin.update(dyn.q());
    EXPECT_LT((dyn.bias_acceleration() - kin.bias_acceleration(dyn.qd())).norm(), 1e-10 * (1.0 + fd.norm()));
  });
}

TEST(ChainDynamics, NeverWritesTheCallersDataNorAllocates) {
  for_each_arm_state([](const Chain& chain, ChainDynamics& dyn, mjData* d, std::mt19937&) {
    const std::vector<unsigned char> before = test::data_bytes(d);
    Eigen::VectorXd qdd = Eigen::VectorXd::Ones(chain.size());
    Eigen::VectorXd tau(chain.size());
    const std::uint64_t calls = test::malloc_calls();
    dyn.update(*d);
    dyn.inverse_dynamics(*d, qdd, tau);
    EXPECT_EQ(test::malloc_calls() - calls, 0u);
    EXPECT_TRUE(test::data_bytes(d) == before);
  }, 2);  // the byte snapshot is large (mjData's stack): a few states suffice
}

TEST(ChainDynamics, OffPathJointsGiveZeroColumnsAndNoCoupling) {
  // the tricky arm's 'off_path' hinge sits between j2 and j3 in dof order, on a branch
  const Robot robot = Robot::from_string(test::kTrickyArm);
  const Chain chain(robot, {"j1", "off_path", "j3"}, "tool");
  ChainDynamics dyn(chain);
  DataPtr d = robot.make_data();
  std::mt19937 rng(3);
  random_state(chain, d.get(), rng);
  dyn.update(*d);
  EXPECT_EQ(dyn.jacobian().col(1).norm(), 0.0);
  EXPECT_EQ(dyn.mass_matrix()(1, 2), 0.0);  // neither is the other's ancestor
  EXPECT_LT((dyn.mass_matrix() - mujoco_mass_block(chain, d.get())).norm(), 1e-12);
}

TEST(ChainDynamics, GravityIsZeroWhenDisabled) {
  const Robot robot = Robot::from_string(R"(
<mujoco>
  <option><flag gravity="disable"/></option>
  <worldbody><body><joint name="a" axis="0 1 0"/><geom size="0.1" pos="0.3 0 0"/>
    <site name="s" pos="0.3 0 0"/></body></worldbody>
</mujoco>)");
  const Chain chain(robot, "s");
  ChainDynamics dyn(chain);
  DataPtr d = robot.make_data();
  mj_forward(&robot.model(), d.get());
  dyn.update(*d);
  EXPECT_EQ(dyn.gravity()[0], 0.0);
}

}  // namespace
}  // namespace mjarm
