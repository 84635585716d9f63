#include "mjarm/dynamics/friction_feed_forward.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "dynamics/sensing_test_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/control/operational_space.hpp"
#include "support/error_message.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

bool friction_bit_identical(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(FrictionFeedForward, ReadsTheModelAndAppliesBothModes) {
  const Robot robot = test::iiwa_torque_with_friction(test::franka_frictionloss());
  const Chain chain(robot, "attachment_site");
  const FrictionFeedForward torque_ff(chain);
  EXPECT_TRUE(torque_ff.active());
  const Eigen::VectorXd d = (Eigen::VectorXd(7) << 1, 1, 1, 1, 0.5, 0.5, 0.5).finished();
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(torque_ff.friction()[i], test::franka_frictionloss()[static_cast<std::size_t>(i)],
                1e-6);
    EXPECT_EQ(torque_ff.damping()[i], d[i]);
  }
  const Eigen::VectorXd qd =
      (Eigen::VectorXd(7) << 0.5, -0.004, 0.0, 2.0, -1.0, 0.01, -0.3).finished();
  const Eigen::VectorXd tau =
      (Eigen::VectorXd(7) << 3.0, -0.2, 0.0, -40.0, 0.1, 0.05, -1.0).finished();
  Eigen::VectorXd out = tau;
  torque_ff.apply(qd, out);
  const Eigen::VectorXd& f = torque_ff.friction();
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(out[i], tau[i] + f[i] * std::tanh(2.0 * tau[i] / f[i]) + d[i] * qd[i], 1e-14);

  FrictionFeedForwardOptions velocity;
  velocity.mode = FrictionMode::velocity;
  const FrictionFeedForward velocity_ff(chain, velocity);
  out = tau;
  velocity_ff.apply(qd, out);
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(out[i], tau[i] + f[i] * std::tanh(qd[i] / 0.01) + d[i] * qd[i], 1e-14);
  // a joint at rest gets no velocity-mode friction; a commanded torque at rest gets torque-mode
  EXPECT_NEAR(out[2], tau[2], 0.0);

  // the modelled resistance is the opposite of the velocity-mode compensation
  Eigen::VectorXd resistance(7);
  velocity_ff.model_force(qd, resistance);
  out = Eigen::VectorXd::Zero(7);
  velocity_ff.apply(qd, out);
  EXPECT_LT((resistance + out).norm(), 1e-14);
}

TEST(FrictionFeedForward, NoFrictionIsABitIdenticalNoOp) {
  // a model without friction or damping, and the iiwa14 (damping only) with damping left to
  // the controller: τ comes back bit for bit, negative zeros included
  const Robot tricky = Robot::from_string(test::kTrickyArm);
  const Robot iiwa = Robot::bundled("iiwa14_torque");
  const Chain tricky_chain(tricky, "tool");
  const Chain iiwa_chain(iiwa, "attachment_site");
  for (const FrictionMode mode : {FrictionMode::torque, FrictionMode::velocity}) {
    const FrictionFeedForward a(tricky_chain, friction_options_for(false, mode));
    const FrictionFeedForward b(iiwa_chain, friction_options_for(true, mode));
    for (const FrictionFeedForward* ff : {&a, &b}) {
      EXPECT_FALSE(ff->active());
      Eigen::VectorXd tau = Eigen::VectorXd::LinSpaced(ff->size(), -3.3, 7.1);
      tau[0] = -0.0;
      const Eigen::VectorXd qd = Eigen::VectorXd::LinSpaced(ff->size(), 1.7, -0.9);
      const Eigen::VectorXd before = tau;
      ff->apply(qd, tau);
      EXPECT_TRUE(friction_bit_identical(tau, before));
      EXPECT_TRUE(std::signbit(tau[0]));
    }
  }
}

// the operational-space controller cancels qfrc_passive = −d⊙q̇: with it, the feed-forward must
// add friction only; without it, friction and d⊙q̇. Either way damping is compensated once.
TEST(FrictionFeedForward, DampingIsCompensatedOnceWithTheOperationalSpaceController) {
  const Robot robot = test::iiwa_torque_with_friction(test::franka_frictionloss());
  const mjModel& m = robot.model();
  const Chain chain(robot, "attachment_site");
  DataPtr d = robot.make_data();
  mj_resetDataKeyframe(&m, d.get(), 0);
  for (int i = 0; i < 7; ++i) d->qvel[i] = 0.4 - 0.15 * i;
  mj_forward(&m, d.get());

  OperationalSpaceOptions with_passive;
  with_passive.compensate_passive = true;
  OperationalSpaceOptions without_passive = with_passive;
  without_passive.compensate_passive = false;
  OperationalSpaceController osc_on(chain, with_passive);
  OperationalSpaceController osc_off(chain, without_passive);
  Reference reference;
  reference.task.X_WE.p =
      Eigen::Vector3d(d->site_xpos + 3 * chain.frame().id) + Eigen::Vector3d(0.02, 0, 0);
  reference.task.X_WE.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
      d->site_xmat + 9 * chain.frame().id);
  JointCommand on{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  JointCommand off{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  osc_on.compute(*d, reference, on);
  osc_off.compute(*d, reference, off);
  Eigen::VectorXd qd_chain(7);
  for (int i = 0; i < 7; ++i) qd_chain[i] = d->qvel[chain.dof_address(i)];

  const FrictionFeedForward by_controller(chain,
                                          friction_options_for(true, FrictionMode::velocity));
  const FrictionFeedForward feed_forward(chain,
                                         friction_options_for(false, FrictionMode::velocity));
  const Eigen::VectorXd& damping = by_controller.damping();
  // the controller's share: exactly d⊙q̇ (the iiwa14 has no springs)
  EXPECT_LT((on.value - off.value - damping.cwiseProduct(qd_chain)).norm(), 1e-12);
  // both correct pairings give the same torque
  Eigen::VectorXd total_on = on.value;
  by_controller.apply(qd_chain, total_on);
  Eigen::VectorXd total_off = off.value;
  feed_forward.apply(qd_chain, total_off);
  EXPECT_LT((total_on - total_off).norm(), 1e-12);
  // the wrong pairing would add d⊙q̇ twice
  Eigen::VectorXd twice = on.value;
  feed_forward.apply(qd_chain, twice);
  EXPECT_LT((twice - total_on - damping.cwiseProduct(qd_chain)).norm(), 1e-12);
  EXPECT_GT(damping.cwiseProduct(qd_chain).norm(), 0.1);
}

TEST(FrictionFeedForward, BadScalesThrowAndApplyAllocatesNothing) {
  const Robot robot = test::iiwa_torque_with_friction(test::franka_frictionloss());
  const Chain chain(robot, "attachment_site");
  FrictionFeedForwardOptions bad;
  bad.torque_sharpness = 0.0;
  const std::string sharp = test::error_of([&] { FrictionFeedForward(chain, bad); });
  EXPECT_NE(sharp.find("torque_sharpness must be positive and finite"), std::string::npos) << sharp;
  bad = {};
  bad.velocity_scale = std::numeric_limits<double>::infinity();
  const std::string scale = test::error_of([&] { FrictionFeedForward(chain, bad); });
  EXPECT_NE(scale.find("velocity_scale must be positive and finite [rad/s or m/s], got inf"),
            std::string::npos)
      << scale;

  const FrictionFeedForward ff(chain);
  Eigen::VectorXd tau = Eigen::VectorXd::Constant(7, 1.0);
  const Eigen::VectorXd qd = Eigen::VectorXd::Constant(7, 0.2);
  Eigen::VectorXd resistance(7);
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 100; ++k) {
    ff.apply(qd, tau);
    ff.model_force(qd, resistance);
  }
  EXPECT_EQ(test::malloc_calls(), before);
}

}  // namespace
}  // namespace mjarm
