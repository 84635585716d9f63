#include "mjarm/dynamics/momentum_observer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "dynamics/dynamics_test_support.hpp"
#include "dynamics/sensing_test_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "support/error_message.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

// kinetic energy ½·q̇ᵀ·M(q)·q̇ of the chain's velocities at the chain configuration in @p scratch
double observer_kinetic_energy(const Chain& chain, mjData* scratch, const std::vector<double>& v) {
  const mjModel& m = chain.robot().model();
  mj_kinematics(&m, scratch);
  mj_comPos(&m, scratch);
  mj_crb(&m, scratch);
  std::vector<double> Mv(static_cast<std::size_t>(m.nv));
  mj_mulM(&m, scratch, Mv.data(), v.data());
  double T = 0.0;
  for (int i = 0; i < m.nv; ++i)
    T += 0.5 * v[static_cast<std::size_t>(i)] * Mv[static_cast<std::size_t>(i)];
  return T;
}

// third method: (Cᵀ·q̇)_i = ∂T/∂q_i at fixed q̇ (the Christoffel identity), central differences
Eigen::VectorXd coriolis_by_energy_gradient(const Chain& chain, const mjData& d) {
  const mjModel& m = chain.robot().model();
  DataPtr scratch = chain.robot().make_data();
  std::vector<double> v(static_cast<std::size_t>(m.nv), 0.0);
  for (int i = 0; i < chain.size(); ++i)
    v[static_cast<std::size_t>(chain.dof_address(i))] = d.qvel[chain.dof_address(i)];
  // T as a function of the chain joints (the other joints where d has them)
  const auto energy = [&](const Eigen::VectorXd& q) {
    mju_copy(scratch->qpos, d.qpos, m.nq);
    chain.scatter(q, scratch->qpos);
    return observer_kinetic_energy(chain, scratch.get(), v);
  };
  return finite_difference_jacobian(energy, chain.gather(d.qpos), 1e-5).row(0).transpose();
}

TEST(MomentumObserver, CoriolisTransposeAgreesThreeWays) {
  std::vector<Chain> chains;
  for (const auto& arm : test::dynamics_arms())
    chains.emplace_back(Robot::bundled(arm.robot), arm.frame);
  chains.emplace_back(Robot::from_string(test::kTrickyArm), "tool");
  std::mt19937 rng(13);
  double worst_difference = 0.0;
  double worst_energy = 0.0;
  for (const Chain& chain : chains) {
    SCOPED_TRACE(chain.robot().name());
    const mjModel& m = chain.robot().model();
    DataPtr d = chain.robot().make_data();
    DataPtr scratch = chain.robot().make_data();
    ChainDynamics dyn(chain);
    std::vector<double> body_work(static_cast<std::size_t>(6 * m.nbody));
    std::vector<double> mdv_work(static_cast<std::size_t>(2 * m.nv));
    Eigen::VectorXd exact(chain.size()), mdv(chain.size());
    for (int trial = 0; trial < 20; ++trial) {
      test::random_state(chain, d.get(), rng);
      // the methods assume the dofs outside the chain at rest
      std::vector<double> chain_qvel(static_cast<std::size_t>(m.nv), 0.0);
      for (int i = 0; i < chain.size(); ++i)
        chain_qvel[static_cast<std::size_t>(chain.dof_address(i))] = d->qvel[chain.dof_address(i)];
      mju_copy(d->qvel, chain_qvel.data(), m.nv);
      mj_forward(&m, d.get());
      dyn.update(*d);
      coriolis_transpose_velocity(chain, *d, body_work.data(), exact);
      mass_derivative_velocity(chain, *d, *scratch, mdv_work.data(), mdv);
      const Eigen::VectorXd by_difference = mdv - (dyn.bias() - dyn.gravity());
      const Eigen::VectorXd by_energy = coriolis_by_energy_gradient(chain, *d);
      const double scale = 1.0 + exact.cwiseAbs().maxCoeff();
      worst_difference =
          std::max(worst_difference, (exact - by_difference).cwiseAbs().maxCoeff() / scale);
      worst_energy = std::max(worst_energy, (exact - by_energy).cwiseAbs().maxCoeff() / scale);
      // and Ṁ·q̇ = C·q̇ + Cᵀ·q̇ (Ṁ = C + Cᵀ), with C·q̇ = h − g
      EXPECT_LT((mdv - (dyn.bias() - dyn.gravity()) - exact).norm(), 1e-6 * scale);
    }
  }
  std::printf(
      "Cᵀq̇: worst relative gap to the directional difference %.2e, to the energy gradient %.2e\n",
      worst_difference, worst_energy);
  EXPECT_LT(worst_difference, 1e-7);
  EXPECT_LT(worst_energy, 1e-7);
}

TEST(MomentumObserver, StaysBelowMicroAtRest) {
  const Robot robot = Robot::bundled("iiwa14_torque");
  const Chain chain(robot, "attachment_site");
  for (const CoriolisMethod method :
       {CoriolisMethod::subtree_momentum, CoriolisMethod::directional_difference}) {
    test::ObserverRig rig(chain, {.coriolis = method});
    mj_resetDataKeyframe(&robot.model(), rig.d.get(), 0);
    double worst = 0.0;
    rig.run(
        1000, [](const ChainDynamics& dyn, double, Eigen::VectorXd& tau) { tau = dyn.bias(); },
        [&](const test::ObserverRig& r) {
          worst = std::max({worst, r.observer.residual().cwiseAbs().maxCoeff(),
                            r.observer.contact_residual().cwiseAbs().maxCoeff(),
                            r.observer.wrench().norm(), r.observer.contact_wrench().norm()});
        });
    EXPECT_LT(worst, 1e-6);
    EXPECT_LT(rig.dyn.qd().norm(), 1e-9);  // it did stay at rest
  }
}

// holds the keyframe with joint PD plus gravity compensation while a known wrench pushes the
// end-effector body; returns the relative error of the estimate once settled
void check_known_wrench(CoriolisMethod method) {
  const Robot robot = Robot::bundled("iiwa14_torque");
  const mjModel& m = robot.model();
  const Chain chain(robot, "attachment_site");
  test::ObserverRig rig(chain, {.coriolis = method});
  mj_resetDataKeyframe(&m, rig.d.get(), 0);
  const Eigen::VectorXd q0 = chain.gather(rig.d->qpos);
  const int body = m.site_bodyid[chain.frame().id];
  const Eigen::Vector3d f(12.0, -6.0, 9.0);
  const Eigen::Vector3d n(0.8, 1.2, -0.5);
  for (int k = 0; k < 3; ++k) {
    rig.d->xfrc_applied[6 * body + k] = f[k];
    rig.d->xfrc_applied[6 * body + 3 + k] = n[k];
  }
  rig.run(
      2000,
      [&](const ChainDynamics& dyn, double, Eigen::VectorXd& tau) {
        tau = dyn.bias() + 400.0 * (q0 - dyn.q()) - 40.0 * dyn.qd();
      },
      [](const test::ObserverRig&) {});
  // the wrench about E's origin, world axes; the force acts at the body's centre of mass
  mj_forward(&m, rig.d.get());
  const Eigen::Vector3d c(rig.d->xipos + 3 * body);
  const Eigen::Vector3d p_E(rig.d->site_xpos + 3 * chain.frame().id);
  Vector6d expected;
  expected << f, n + (c - p_E).cross(f);
  const double error = (rig.observer.wrench() - expected).norm() / expected.norm();
  const double contact_error = (rig.observer.contact_wrench() - expected).norm() / expected.norm();
  std::printf(
      "known wrench (%s): relative error %.2e, contact-only %.2e\n",
      method == CoriolisMethod::subtree_momentum ? "subtree momentum" : "directional difference",
      error, contact_error);
  EXPECT_LT(error, 0.02);
  EXPECT_LT(contact_error, 0.02);
  EXPECT_LT(rig.dyn.qd().norm(), 1e-4);  // settled
}

TEST(MomentumObserver, EstimatesAKnownWrenchWithinTwoPercent) {
  check_known_wrench(CoriolisMethod::subtree_momentum);
}

TEST(MomentumObserver, EstimatesAKnownWrenchWithTheDirectionalDifference) {
  check_known_wrench(CoriolisMethod::directional_difference);
}

TEST(MomentumObserver, ContactEstimateRejectsKnownJointFriction) {
  const Robot robot = test::iiwa_torque_with_friction(test::franka_frictionloss());
  const mjModel& m = robot.model();
  const Chain chain(robot, "attachment_site");
  test::ObserverRig rig(chain);
  mj_resetDataKeyframe(&m, rig.d.get(), 0);
  const Eigen::VectorXd q0 = chain.gather(rig.d->qpos);
  const double w = 2.0 * M_PI * 0.5;
  const double amplitude = 0.3;
  double raw_sq = 0.0, contact_sq = 0.0, raw_wrench = 0.0, contact_wrench = 0.0;
  int samples = 0;
  // computed torque on a sinusoid per joint (phases spread), free space: no contact at all
  rig.run(
      2000,
      [&](const ChainDynamics& dyn, double t, Eigen::VectorXd& tau) {
        Eigen::VectorXd e(chain.size()), ed(chain.size()), a(chain.size());
        for (int i = 0; i < chain.size(); ++i) {
          const double phase = w * t + 0.7 * i;
          e[i] = q0[i] + amplitude * std::sin(phase) - dyn.q()[i];
          ed[i] = amplitude * w * std::cos(phase) - dyn.qd()[i];
          a[i] = -amplitude * w * w * std::sin(phase);
        }
        tau = dyn.mass_matrix() * (a + 400.0 * e + 40.0 * ed) + dyn.bias();
      },
      [&](const test::ObserverRig& r) {
        if (r.d->time < 1.0) return;  // past the observer's start
        raw_sq += r.observer.residual().squaredNorm();
        contact_sq += r.observer.contact_residual().squaredNorm();
        raw_wrench += r.observer.wrench().head<3>().norm();
        contact_wrench += r.observer.contact_wrench().head<3>().norm();
        ++samples;
      });
  const double raw_rms = std::sqrt(raw_sq / samples);
  const double contact_rms = std::sqrt(contact_sq / samples);
  std::printf(
      "free motion with joint friction: residual RMS %.3f N·m, contact-only %.4f N·m; mean |f̂| "
      "%.2f N, "
      "contact-only %.3f N\n",
      raw_rms, contact_rms, raw_wrench / samples, contact_wrench / samples);
  EXPECT_GT(raw_rms, 1.0);                // the raw residual sees the friction ...
  EXPECT_LT(contact_rms, 0.1 * raw_rms);  // ... the contact-only one takes it out
  EXPECT_LT(contact_wrench / samples, 0.1 * raw_wrench / samples);
}

TEST(MomentumObserver, IntegralIsClippedPerJoint) {
  const Robot robot = Robot::bundled("iiwa14_torque");
  const Chain chain(robot, "attachment_site");
  DataPtr d = robot.make_data();
  mj_resetDataKeyframe(&robot.model(), d.get(), 0);
  mj_forward(&robot.model(), d.get());
  ChainDynamics dyn(chain);
  dyn.update(*d);
  MomentumObserver observer(chain);
  // a torque that never shows in the momentum, above K_i·limit = 800 N·m: ∫e saturates and the
  // proportional part takes over the rest
  Eigen::VectorXd tau = dyn.bias();
  tau[0] += 2000.0;
  tau[3] -= 1000.0;
  for (int k = 0; k < 5000; ++k)
    ASSERT_EQ(observer.update(*d, dyn, tau, 0.002), ObserverStatus::ok);
  EXPECT_DOUBLE_EQ(observer.integral()[0], -20.0);
  EXPECT_DOUBLE_EQ(observer.integral()[3], 20.0);
  EXPECT_NEAR(observer.integral()[1], 0.0, 1e-12);  // untouched, but for rounding
  EXPECT_NEAR(observer.residual()[0], -2000.0, 1e-6);
  EXPECT_NEAR(observer.residual()[3], 1000.0, 1e-6);
  EXPECT_TRUE(observer.residual().allFinite());
}

TEST(MomentumObserver, BadInputGivesAStatusAndChangesNothing) {
  const Robot robot = Robot::bundled("iiwa14_torque");
  const Chain chain(robot, "attachment_site");
  DataPtr d = robot.make_data();
  mj_resetDataKeyframe(&robot.model(), d.get(), 0);
  d->qvel[1] = 0.5;
  mj_forward(&robot.model(), d.get());
  ChainDynamics dyn(chain);
  dyn.update(*d);
  MomentumObserver observer(chain);
  Eigen::VectorXd tau = dyn.bias();
  ASSERT_EQ(observer.update(*d, dyn, tau, 0.002), ObserverStatus::ok);
  const Eigen::VectorXd p_hat = observer.momentum_estimate();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double dt : {0.0, -0.002, nan, std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(observer.update(*d, dyn, tau, dt), ObserverStatus::bad_input);
  }
  tau[2] = nan;
  EXPECT_EQ(observer.update(*d, dyn, tau, 0.002), ObserverStatus::bad_input);
  EXPECT_EQ(observer.update(*d, dyn, Eigen::VectorXd::Zero(3), 0.002), ObserverStatus::bad_input);
  EXPECT_EQ(observer.momentum_estimate(), p_hat);
  // a state gone bad
  tau = dyn.bias();
  d->qvel[1] = nan;
  dyn.update(*d);
  EXPECT_EQ(observer.update(*d, dyn, tau, 0.002), ObserverStatus::non_finite);
  EXPECT_EQ(observer.momentum_estimate(), p_hat);
  EXPECT_STREQ(to_string(ObserverStatus::bad_input), "bad_input");

  const std::string kp = test::error_of([&] { MomentumObserver(chain, {.kp = 0.0}); });
  EXPECT_NE(kp.find("kp must be positive and finite [1/s], got 0"), std::string::npos) << kp;
  const std::string ki = test::error_of([&] { MomentumObserver(chain, {.ki = -1.0}); });
  EXPECT_NE(ki.find("ki must be finite and ≥ 0 [1/s²], got -1"), std::string::npos) << ki;
  const std::string limit =
      test::error_of([&] { MomentumObserver(chain, {.integral_limit = nan}); });
  EXPECT_NE(limit.find("integral_limit"), std::string::npos) << limit;
  const std::string eps = test::error_of([&] { MomentumObserver(chain, {.wrench_damping = 0.0}); });
  EXPECT_NE(eps.find("wrench_damping"), std::string::npos) << eps;
  const Chain shorter(robot, "link6");
  const std::string mismatch =
      test::error_of([&] { MomentumObserver(chain, FrictionFeedForward(shorter)); });
  EXPECT_NE(mismatch.find("friction model has 6 dofs, the chain 7"), std::string::npos) << mismatch;
}

TEST(MomentumObserver, UpdateAllocatesNothing) {
  const Robot robot = Robot::bundled("iiwa14_torque");
  const Chain chain(robot, "attachment_site");
  for (const CoriolisMethod method :
       {CoriolisMethod::subtree_momentum, CoriolisMethod::directional_difference}) {
    DataPtr d = robot.make_data();
    mj_resetDataKeyframe(&robot.model(), d.get(), 0);
    for (int i = 0; i < 7; ++i) d->qvel[i] = 0.3 * (i + 1);
    mj_forward(&robot.model(), d.get());
    ChainDynamics dyn(chain);
    dyn.update(*d);
    MomentumObserver observer(chain, {.coriolis = method});
    const Eigen::VectorXd tau = dyn.bias();
    observer.update(*d, dyn, tau, 0.002);
    const std::uint64_t before = test::malloc_calls();
    for (int k = 0; k < 100; ++k) observer.update(*d, dyn, tau, 0.002);
    EXPECT_EQ(test::malloc_calls(), before);
  }
}

}  // namespace
}  // namespace mjarm
