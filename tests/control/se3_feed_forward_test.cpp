// Se3ImpedanceController's own feed-forwards: the desired wrench F_d through its spring and the
// friction of the model's dof_frictionloss (both were the docking wrapper's before).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "control/compliance_test_support.hpp"
#include "control/task_control_support.hpp"
#include "mjarm/control/se3_impedance.hpp"
#include "mjarm/lie/se3.hpp"

namespace mjarm {
namespace {

using test::Rig;
using test::VectorX;

VectorX se3ff_torque(Rig& rig, const Se3ImpedanceOptions& o, const Reference& ref) {
  Se3ImpedanceController c(rig.chain, o);
  JointCommand command{CommandKind::torque, VectorX::Zero(rig.chain.size())};
  c.compute(rig.d(), ref, command);
  EXPECT_NE(c.status(), Se3ImpedanceStatus::invalid_state);
  return command.value;
}

TEST(Se3FeedForward, DesiredWrenchIsTheTargetMovedThroughTheSpring) {
  // with the feed-forward, τ(T_d, F_d) = τ(T_d·exp(δ), 0) with δ_i = F_d,i/K_ii (D's axes) on
  // the kept axes, written here from the docs; released axes get no shift; off, F_d is ignored
  Rig rig("iiwa14_torque", "attachment_site");
  std::mt19937_64 rng(3);
  int checked = 0;
  while (checked < 5) {
    if (!test::random_state(rig, rng)) continue;
    Se3ImpedanceOptions o;
    o.stiffness = (Vector6d() << 800, 900, 1000, 50, 60, 70).finished().asDiagonal();
    o.release.axes = {true, true, false, false, false, false};
    Reference ref;
    ref.task.X_WE =
        test::nearby_pose(test::site_pose(rig.d(), rig.chain.frame().id), rng, 0.05, 0.3);
    ref.task.F_ext << 1.0, -2.0, -5.0, 0.1, 0.2, -0.3;
    Se3ImpedanceOptions off = o;
    const VectorX ignored = se3ff_torque(rig, off, ref);
    Reference plain = ref;
    plain.task.F_ext.setZero();
    EXPECT_LE((ignored - se3ff_torque(rig, off, plain)).norm(), 1e-12);

    o.wrench_feed_forward = true;
    const VectorX fed = se3ff_torque(rig, o, ref);
    const Eigen::Matrix3d R_DW = ref.task.X_WE.R.transpose();
    Vector6d delta;
    delta << 0.0, 0.0, (R_DW * ref.task.F_ext.head<3>()).z() / 1000.0,
        (R_DW * ref.task.F_ext.tail<3>()).cwiseQuotient(Eigen::Vector3d(50, 60, 70));
    Reference moved = plain;
    moved.task.X_WE = ref.task.X_WE * se3::exp(delta);
    const VectorX expected = se3ff_torque(rig, off, moved);
    EXPECT_LE((fed - expected).norm(), 1e-9 * (1.0 + expected.norm()));
    EXPECT_GT((fed - ignored).norm(), 1e-3);  // the feed-forward did something
    ++checked;
  }
}

TEST(Se3FeedForward, FrictionIsTheModelsFrictionAndOffByDefault) {
  // velocity mode: the torque grows by exactly f⊙tanh(q̇/v₀), f the chain's dof_frictionloss;
  // torque mode: by f⊙tanh(s·τ_m/f) on τ_m = τ − h + τ_passive; default off: nothing
  Rig rig(test::iiwa_ft_tool(test::franka_frictionloss()), "tip");
  std::mt19937_64 rng(8);
  while (!test::random_state(rig, rng)) {
  }
  const mjModel& m = rig.m();
  const mjData& d = rig.d();
  const int n = rig.chain.size();
  Reference ref;
  ref.task.X_WE = test::nearby_pose(test::site_pose(d, rig.chain.frame().id), rng, 0.05, 0.3);
  Se3ImpedanceOptions o;
  const VectorX plain = se3ff_torque(rig, o, ref);
  {
    Se3ImpedanceController c(rig.chain, o);
    JointCommand command{CommandKind::torque, VectorX::Zero(n)};
    c.compute(d, ref, command);
    EXPECT_EQ(c.friction_torque().norm(), 0.0);
  }
  o.friction_feed_forward = true;
  const VectorX velocity_mode = se3ff_torque(rig, o, ref);
  o.friction.mode = FrictionMode::torque;
  const VectorX torque_mode = se3ff_torque(rig, o, ref);
  for (int i = 0; i < n; ++i) {
    const int dof = rig.chain.dof_address(i);
    const double f = m.dof_frictionloss[dof];
    ASSERT_GT(f, 0.0);
    EXPECT_NEAR(velocity_mode[i] - plain[i], f * std::tanh(d.qvel[dof] / 0.01), 1e-9) << i;
    const double moving = plain[i] - d.qfrc_bias[dof] + d.qfrc_passive[dof];
    EXPECT_NEAR(torque_mode[i] - plain[i], f * std::tanh(2.0 * moving / f), 1e-9) << i;
  }
}

}  // namespace
}  // namespace mjarm
