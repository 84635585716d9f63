#include "mjarm/control/joint_limit_avoidance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/control/cartesian_impedance.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/control/se3_impedance.hpp"
#include "mjarm/random.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::Rig;
using test::VectorX;

JointLimitOptions jla_on() {
  JointLimitOptions o;
  o.enabled = true;
  return o;
}

TEST(JointLimitAvoidance, TorqueIsTheNegativeGradientOfThePotentialPlusDamping) {
  // random states with every joint inside its zone (either side): central differences of U(q)
  // give τ_U; the rest of τ is −b·s·q̇ towards the limit and nothing away from it
  Rig rig("panda_torque", "attachment_site");
  JointLimitOptions o = jla_on();
  o.margin = 0.3;
  o.gain = 15.0;
  o.damping = 4.0;
  JointLimitAvoidance limits(rig.chain, o);
  const VectorX& lo = rig.chain.lower();
  const VectorX& hi = rig.chain.upper();
  Random rng(5);
  const int n = rig.chain.size();
  for (int trial = 0; trial < 20; ++trial) {
    VectorX q(n), qd(n);
    for (int i = 0; i < n; ++i) {
      const double d =
          (0.05 + 0.9 * uniform(rng, 0.0, 1.0)) * o.margin;  // inside the zone, not at its ends
      q[i] = uniform(rng, 0.0, 1.0) < 0.5 ? hi[i] - d : lo[i] + d;
      qd[i] = 2.0 * uniform(rng, 0.0, 1.0) - 1.0;
    }
    limits.update(q, VectorX::Zero(n));
    const VectorX tau_u = limits.torque();
    const double h = 1e-6;
    for (int i = 0; i < n; ++i) {
      VectorX plus = q, minus = q;
      plus[i] += h;
      minus[i] -= h;
      const double gradient = (limits.potential(plus) - limits.potential(minus)) / (2.0 * h);
      EXPECT_NEAR(tau_u[i], -gradient, 1e-5 * std::max(1.0, std::abs(gradient)))
          << "joint " << i << " trial " << trial;
      // pushes away from the nearer limit
      EXPECT_LT(tau_u[i] * (q[i] - 0.5 * (lo[i] + hi[i])), 0.0);
    }
    limits.update(q, qd);
    for (int i = 0; i < n; ++i) {
      const double away = hi[i] - q[i] < q[i] - lo[i] ? -1.0 : 1.0;
      const double damping =
          qd[i] * away < 0.0 ? -o.damping * limits.full_weight()[i] * qd[i] : 0.0;
      EXPECT_NEAR(limits.torque()[i] - tau_u[i], damping, 1e-12);
      EXPECT_GT(limits.full_weight()[i], 0.0);
      EXPECT_LT(limits.full_weight()[i], 1.0);
    }
  }
  // outside every zone: nothing, and U = 0 (the term is C¹: its value and gradient vanish at the
  // zone's edge)
  const VectorX mid = 0.5 * (lo + hi);
  limits.update(mid, VectorX::Ones(n));
  EXPECT_EQ(limits.torque().norm(), 0.0);
  EXPECT_EQ(limits.potential(mid), 0.0);
  VectorX edge = mid;
  edge[3] = hi[3] - o.margin * (1.0 - 1e-9);
  limits.update(edge, VectorX::Zero(n));
  EXPECT_LT(std::abs(limits.torque()[3]), 1e-6);
  // past the limit the push keeps growing, in full
  VectorX past = mid;
  past[6] = hi[6] + 0.1;
  limits.update(past, VectorX::Zero(n));
  EXPECT_NEAR(limits.torque()[6], -o.gain * (o.margin + 0.1), 1e-12);
  EXPECT_EQ(limits.full_weight()[6], 1.0);
}

TEST(JointLimitAvoidance, BadOptionsThrowNamingThem) {
  Rig rig("panda_torque", "attachment_site");
  auto error = [&](auto edit) {
    JointLimitOptions o = jla_on();
    edit(o);
    return test::error_of([&] { JointLimitAvoidance limits(rig.chain, o); });
  };
  EXPECT_NE(error([](auto& o) { o.margin = 0.0; }).find("margin"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.margin = NAN; }).find("margin"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.gain = -1.0; }).find("gain"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.gain = NAN; }).find("gain"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.damping = 0.0; }).find("damping"), std::string::npos);
  // joint4's range is [−3.07, −0.07]: a 1.6 rad margin leaves it no free range
  const std::string wide = error([](auto& o) { o.margin = 1.6; });
  EXPECT_NE(wide.find("joint4"), std::string::npos) << wide;
  EXPECT_NE(wide.find("half the range"), std::string::npos) << wide;
  // the controllers refuse the same options before any run, naming the nested field
  OperationalSpaceOptions osc;
  osc.joint_limits.gain = 0.0;
  const std::string in_osc = test::error_of([&] { OperationalSpaceController c(rig.chain, osc); });
  EXPECT_NE(in_osc.find("joint limits: gain"), std::string::npos) << in_osc;
  Se3ImpedanceOptions se3;
  se3.joint_limits.margin = -0.1;
  const std::string in_se3 = test::error_of([&] { Se3ImpedanceController c(rig.chain, se3); });
  EXPECT_NE(in_se3.find("joint limits: margin"), std::string::npos) << in_se3;
  CartesianImpedanceOptions cic;
  cic.joint_limits.damping = NAN;
  const std::string in_cic =
      test::error_of([&] { CartesianImpedanceController c(rig.chain, cic); });
  EXPECT_NE(in_cic.find("damping"), std::string::npos) << in_cic;
}

constexpr double kJlaPosture = 10.0;  // K_n [N·m/rad]
constexpr double kJlaExcess = 0.3;    // how far beyond joint7's limit the target posture is [rad]

/// What a run towards a target beyond joint7's upper limit did to joint7.
struct JlaRun {
  double upper = 0.0;    // joint7's upper limit [rad]
  double max_q = 0.0;    // the largest q₇ reached [rad]
  double final_q = 0.0;  // q₇ at the end [rad]
  double final_qd = 0.0;
  int reversals = 0;  // sign changes of q̇₇ (|q̇₇| > 1e-3 rad/s) inside the last 0.3 rad
};

/// From the panda's home posture with q₇ = upper − 0.5 rad, drives E for 3 s to the pose of that
/// posture with q₇ = upper + kJlaExcess, the posture held in the null space (K_n, set by the
/// caller, towards the start): the self-motion absorbs only part of the turn about E's axis,
/// joint7 is asked to go through its limit.
JlaRun jla_drive_past_limit(Rig& rig, Controller& controller) {
  const int j = 6;
  const mjModel& m = rig.m();
  mjData& d = rig.d();
  JlaRun run;
  run.upper = rig.chain.upper()[j];
  const int a = rig.chain.qpos_address(j), v = rig.chain.dof_address(j);
  mj_resetDataKeyframe(&m, &d, rig.robot.keyframe("home"));
  d.qpos[a] = run.upper + kJlaExcess;
  mj_forward(&m, &d);
  Reference ref;
  ref.task.X_WE = test::site_pose(d, rig.chain.frame().id);
  mj_resetDataKeyframe(&m, &d, rig.robot.keyframe("home"));
  d.qpos[a] = run.upper - 0.5;
  mj_forward(&m, &d);
  ref.joint.q = VectorX(rig.chain.size());
  for (int i = 0; i < rig.chain.size(); ++i) ref.joint.q[i] = d.qpos[rig.chain.qpos_address(i)];
  controller.reset();
  JointCommand command{CommandKind::torque, VectorX::Zero(rig.chain.size())};
  run.max_q = d.qpos[a];
  int last_sign = 0;
  for (int k = 0; k < static_cast<int>(3.0 / m.opt.timestep); ++k) {
    mj_step1(&m, &d);
    controller.compute(d, ref, command);
    test::apply_torque(rig.chain, command.value, d);
    mj_step2(&m, &d);
    run.max_q = std::max(run.max_q, d.qpos[a]);
    const double qd = d.qvel[v];
    if (d.qpos[a] > run.upper - 0.3 && std::abs(qd) > 1e-3) {
      const int sign = qd > 0.0 ? 1 : -1;
      if (last_sign != 0 && sign != last_sign) ++run.reversals;
      last_sign = sign;
    }
  }
  run.final_q = d.qpos[a];
  run.final_qd = d.qvel[v];
  return run;
}

/// The checks shared by the three controllers: off, joint7 hits its limit; on, it settles short
/// of it without oscillating.
void jla_expect_stops_short(const JlaRun& off, const JlaRun& on, const char* name) {
  SCOPED_TRACE(name);
  // off: the task drives the joint into MuJoCo's limit constraint
  EXPECT_GT(off.max_q, off.upper - 2e-3);
  // on: never reaches the limit, comes to rest short of it, at most one reversal (no ringing)
  EXPECT_LT(on.max_q, on.upper - 0.01);
  EXPECT_LT(on.final_q, on.upper - 0.01);
  EXPECT_GT(on.final_q, on.upper - 0.2);  // still pressed into the zone by the task
  EXPECT_LT(std::abs(on.final_qd), 1e-3);
  EXPECT_LE(on.reversals, 1);
  std::printf("%s: off max q7 − upper = %+.4f rad; on max %+.4f, final %+.4f rad, reversals %d\n",
              name, off.max_q - off.upper, on.max_q - on.upper, on.final_q - on.upper,
              on.reversals);
}

TEST(JointLimitAvoidance, OperationalSpaceStopsShortOfTheLimit) {
  Rig rig("panda_torque", "attachment_site");
  OperationalSpaceOptions o;
  o.nullspace_stiffness = kJlaPosture;
  OperationalSpaceController off(rig.chain, o);
  const JlaRun run_off = jla_drive_past_limit(rig, off);
  o.joint_limits = jla_on();
  OperationalSpaceController on(rig.chain, o);
  jla_expect_stops_short(run_off, jla_drive_past_limit(rig, on), "osc");
}

TEST(JointLimitAvoidance, CartesianImpedanceStopsShortOfTheLimit) {
  Rig rig("panda_torque", "attachment_site");
  CartesianImpedanceOptions o;
  o.nullspace_stiffness = kJlaPosture;
  CartesianImpedanceController off(rig.chain, o);
  const JlaRun run_off = jla_drive_past_limit(rig, off);
  o.joint_limits = jla_on();
  CartesianImpedanceController on(rig.chain, o);
  jla_expect_stops_short(run_off, jla_drive_past_limit(rig, on), "cic");
}

TEST(JointLimitAvoidance, Se3ImpedanceStopsShortOfTheLimit) {
  Rig rig("panda_torque", "attachment_site");
  Se3ImpedanceOptions o;
  o.nullspace_stiffness = kJlaPosture;
  Se3ImpedanceController off(rig.chain, o);
  const JlaRun run_off = jla_drive_past_limit(rig, off);
  o.joint_limits = jla_on();
  Se3ImpedanceController on(rig.chain, o);
  jla_expect_stops_short(run_off, jla_drive_past_limit(rig, on), "se3");
}

TEST(JointLimitAvoidance, ComputeAllocatesNothingWithTheTermOn) {
  Rig rig("panda_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  rig.d().qpos[rig.chain.qpos_address(6)] = rig.chain.upper()[6] - 0.05;  // inside the zone
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  OperationalSpaceOptions osc;
  osc.joint_limits = jla_on();
  CartesianImpedanceOptions cic;
  cic.joint_limits = jla_on();
  Se3ImpedanceOptions se3;
  se3.joint_limits = jla_on();
  OperationalSpaceController a(rig.chain, osc);
  CartesianImpedanceController b(rig.chain, cic);
  Se3ImpedanceController c(rig.chain, se3);
  for (Controller* controller : std::initializer_list<Controller*>{&a, &b, &c}) {
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    controller->compute(rig.d(), ref, command);
    const std::uint64_t before = test::malloc_calls();
    for (int k = 0; k < 50; ++k) {
      rig.d().time += 0.002;
      controller->compute(rig.d(), ref, command);
    }
    EXPECT_EQ(test::malloc_calls() - before, 0u) << controller->name();
  }
  EXPECT_LT(a.joint_limits().applied()[6], 0.0);  // pushes joint7 down, away from its limit
  EXPECT_LT(c.joint_limits().applied()[6], 0.0);
}

}  // namespace
}  // namespace mjarm
