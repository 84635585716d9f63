#include "mjarm/control/cartesian_impedance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include "control/compliance_test_support.hpp"
#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/control/hqp_ac.hpp"
#include "mjarm/kinematics/contacts.hpp"
#include "mjarm/lie/se3.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::Rig;
using test::VectorX;

/// A table whose top (z = 0.2 m) lies 5 cm under the tool tip at the iiwa14's home pose.
const char* kCicTable = R"(<geom name="table" type="box" pos="0.62 0 0.1" size="0.2 0.2 0.1"/>)";

/// A random state of @p rig and a target near it (0.1 m, 0.5 rad), moving.
Reference cic_random_reference(Rig& rig, std::mt19937_64& rng) {
  Reference ref;
  ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), rig.chain.frame().id), rng, 0.1, 0.5);
  ref.task.V_WE = test::random6(rng, 0.5);
  ref.task.A_WE = test::random6(rng, 2.0);
  ref.task.F_ext = test::random6(rng, 3.0);
  return ref;
}

TEST(CartesianImpedance, NaturalInertiaIsTheOperationalSpaceLawWithTaskInertia) {
  // no friction in the model (no integral, no feed-forward), natural inertia: exactly the
  // operational-space controller with M_d = Λ and the same gains
  Rig rig("iiwa14_torque", "attachment_site");
  std::mt19937_64 rng(3);
  CartesianImpedanceOptions o;
  o.nullspace_stiffness = 4.0;
  CartesianImpedanceController cic(rig.chain, o);
  EXPECT_FALSE(cic.integral_enabled());
  OperationalSpaceOptions p;
  p.task_inertia = true;
  p.stiffness = o.stiffness;
  p.nullspace_damping = o.nullspace_damping;
  p.nullspace_stiffness = o.nullspace_stiffness;
  OperationalSpaceController osc(rig.chain, p);
  JointCommand a{CommandKind::torque, VectorX::Zero(7)}, b = a;
  for (int k = 0; k < 20;) {
    if (!test::random_state(rig, rng)) continue;
    Reference ref = cic_random_reference(rig, rng);
    ref.joint.q = rig.chain.center();
    cic.compute(rig.d(), ref, a);
    osc.compute(rig.d(), ref, b);
    EXPECT_LE((a.value - b.value).norm(), 1e-12 * b.value.norm());
    EXPECT_EQ(cic.friction_torque().norm(), 0.0);
    ++k;
  }
}

TEST(CartesianImpedance, ExactInertiaFeedsTheSourceWrenchToTheLaw) {
  // exact inertia with the F/T sensor: the torque is the operational-space law with
  // wrench_feedback and M_d, given the wrench the source made of the sensor reading
  Rig rig(test::iiwa_ft_tool(), "tip");
  std::mt19937_64 rng(4);
  CartesianImpedanceOptions o;
  o.inertia = CicInertia::exact;
  o.force.kind = WrenchSourceKind::sensor;
  o.force.site = "ft";
  CartesianImpedanceController cic(rig.chain, o);
  OperationalSpaceOptions p;
  p.stiffness = o.stiffness;
  p.inertia = o.desired_inertia;
  p.wrench_feedback = true;
  OperationalSpaceController osc(rig.chain, p);
  WrenchSource source(rig.chain, o.force);
  JointCommand a{CommandKind::torque, VectorX::Zero(7)}, b = a;
  for (int k = 0; k < 10;) {
    if (!test::random_state(rig, rng)) continue;
    for (int i = 0; i < 6; ++i) rig.d().sensordata[i] = 5.0 * std::sin(3.0 * k + i);
    const Reference ref = cic_random_reference(rig, rng);
    cic.compute(rig.d(), ref, a);
    source.measure(rig.d(), test::site_pose(rig.d(), rig.chain.frame().id));
    ASSERT_GT(source.wrench().norm(), 1.0);
    EXPECT_LE((cic.measured_wrench() - source.wrench()).norm(), 1e-12);
    osc.set_measured_wrench(source.wrench());
    osc.compute(rig.d(), ref, b);
    EXPECT_LE((a.value - b.value).norm(), 1e-12 * b.value.norm());
    EXPECT_EQ(cic.status(), CicStatus::ok);
    ++k;
  }
}

TEST(CartesianImpedance, NaturalInertiaSettlesAgainstATableExactWithTheSensorBounces) {
  // the tool pushed 1 cm into a table (K_z = 1000 N/m: 10 N expected) from 5 cm above. Natural
  // inertia settles on 10 N with either source. Exact inertia (M_d = 2 kg) feeds the one-step-
  // old sensor reading back with gain Λ·M_d⁻¹ − I: against the stiff table the tool bounces —
  // the reason natural is the default (docs/control.md)
  auto press = [](CicInertia inertia, WrenchSourceKind kind, double& lo, double& hi) {
    Rig rig(test::iiwa_ft_tool({}, kCicTable), "tip");
    const mjModel& m = rig.m();
    mjData& d = rig.d();
    mj_resetDataKeyframe(&m, &d, rig.robot.keyframe("home"));
    mj_forward(&m, &d);
    CartesianImpedanceOptions o;
    o.inertia = inertia;
    o.force.kind = kind;
    o.force.site = "ft";
    CartesianImpedanceController c(rig.chain, o);
    Reference ref;
    ref.task.X_WE = test::site_pose(d, rig.chain.frame().id);
    ref.task.X_WE.p.z() = 0.19;
    const int tool = mj_name2id(&m, mjOBJ_BODY, "tool");
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    lo = INFINITY;
    hi = -INFINITY;
    for (int k = 0; k < 2000; ++k) {  // 4 s, the last one judged
      mj_step1(&m, &d);
      c.compute(d, ref, command);
      EXPECT_TRUE(command.value.allFinite());
      test::apply_torque(rig.chain, command.value, d);
      mj_step2(&m, &d);
      if (k < 1500) continue;
      const double fz = contact_force_on_body(contact_forces(m, d), tool).z();
      lo = std::min(lo, fz);
      hi = std::max(hi, fz);
    }
  };
  double lo = 0, hi = 0;
  for (WrenchSourceKind kind : {WrenchSourceKind::sensor, WrenchSourceKind::observer}) {
    press(CicInertia::natural, kind, lo, hi);
    std::printf("cic natural, %s: table force in the last second [%.3f, %.3f] N\n", to_string(kind),
                lo, hi);
    EXPECT_GT(lo, 9.5) << to_string(kind);
    EXPECT_LT(hi, 10.5) << to_string(kind);
  }
  press(CicInertia::exact, WrenchSourceKind::sensor, lo, hi);
  std::printf("cic exact, sensor: table force in the last second [%.3f, %.3f] N\n", lo, hi);
  EXPECT_GT(hi - lo, 10.0) << "exact inertia with the sensor settled in [" << lo << ", " << hi
                           << "] N";
}

TEST(CartesianImpedance, IntegralRunsOnlyWithFrictionAndIsBounded) {
  const Robot plain = Robot::bundled("iiwa14_torque");
  const Robot rough = test::iiwa_torque_with_friction(test::franka_frictionloss());
  EXPECT_FALSE(CartesianImpedanceController(Chain(plain, "attachment_site")).integral_enabled());
  Rig rig(rough, "attachment_site");
  CartesianImpedanceController c(rig.chain);
  EXPECT_TRUE(c.integral_enabled());
  CartesianImpedanceOptions off;
  off.integral = CicIntegral::off;
  EXPECT_FALSE(CartesianImpedanceController(rig.chain, off).integral_enabled());
  CartesianImpedanceOptions on;
  on.integral = CicIntegral::on;
  EXPECT_TRUE(CartesianImpedanceController(Chain(plain, "attachment_site"), on).integral_enabled());
  // an unreachable target winds the integral up to its bound: k_i·∫e = ±10 N per axis, x y z only
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  ref.task.X_WE.p += Eigen::Vector3d(3.0, -3.0, 3.0);
  ref.task.X_WE.R = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitX()) * ref.task.X_WE.R;
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  for (int k = 0; k < 300; ++k) {
    rig.d().time = 0.01 * k;
    c.compute(rig.d(), ref, command);
  }
  const Vector6d& integral = c.impedance().integral();
  EXPECT_DOUBLE_EQ(150.0 * integral[0], 10.0);
  EXPECT_DOUBLE_EQ(150.0 * integral[1], -10.0);
  EXPECT_DOUBLE_EQ(150.0 * integral[2], 10.0);
  EXPECT_EQ(integral.tail<3>().norm(), 0.0);
}

TEST(CartesianImpedance, IntegralIsHeldInContact) {
  // with friction in the joints the integral is on; pressed into a table, the measured force
  // exceeds 1 N and the integral stops moving, so it does not wind up against the table
  Rig rig(test::iiwa_ft_tool(test::franka_frictionloss(), kCicTable), "tip");
  const mjModel& m = rig.m();
  mjData& d = rig.d();
  mj_resetDataKeyframe(&m, &d, rig.robot.keyframe("home"));
  mj_forward(&m, &d);
  CartesianImpedanceOptions o;
  o.force.kind = WrenchSourceKind::sensor;
  o.force.site = "ft";
  CartesianImpedanceController c(rig.chain, o);
  ASSERT_TRUE(c.integral_enabled());
  Reference ref;
  ref.task.X_WE = test::site_pose(d, rig.chain.frame().id);
  ref.task.X_WE.p.z() = 0.19;
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  int held = 0;
  Vector6d integral_at_contact = Vector6d::Zero();
  double drift = 0.0;
  for (int k = 0; k < 1500; ++k) {
    mj_step1(&m, &d);
    c.compute(d, ref, command);
    test::apply_torque(rig.chain, command.value, d);
    mj_step2(&m, &d);
    if (k >= 1000) {
      ASSERT_EQ(c.internal_values()[7], 1.0) << "integral_held at tick " << k;
      if (held++ == 0) integral_at_contact = c.impedance().integral();
      drift = std::max(drift, (c.impedance().integral() - integral_at_contact).norm());
    }
  }
  EXPECT_EQ(held, 500);
  EXPECT_EQ(drift, 0.0);
  EXPECT_LE(std::abs(150.0 * integral_at_contact[2]), 10.0);
}

TEST(CartesianImpedance, FrictionFeedForwardIsTheModelsFrictionAndNeverTheDamping) {
  // velocity mode (default): f⊙tanh(q̇/v₀); torque mode: f⊙tanh(s·τ_m/f) on the moving part
  // τ_m = τ₁ − h + τ_passive. The law already cancels the joint damping, so the feed-forward adds
  // none (damping compensated once); without friction it changes nothing at all
  const auto f = test::franka_frictionloss();
  Rig rough(test::iiwa_torque_with_friction(f), "attachment_site");
  std::mt19937_64 rng(9);
  for (FrictionMode mode : {FrictionMode::velocity, FrictionMode::torque}) {
    CartesianImpedanceOptions with, without;
    with.integral = without.integral = CicIntegral::off;
    with.friction.mode = mode;
    without.friction_feed_forward = false;
    CartesianImpedanceController a(rough.chain, with), b(rough.chain, without);
    JointCommand ta{CommandKind::torque, VectorX::Zero(7)}, tb = ta;
    for (int k = 0; k < 10;) {
      if (!test::random_state(rough, rng)) continue;
      const Reference ref = cic_random_reference(rough, rng);
      a.compute(rough.d(), ref, ta);
      b.compute(rough.d(), ref, tb);
      for (int i = 0; i < 7; ++i) {
        const int dof = rough.chain.dof_address(i);
        const double moving = tb.value[i] - rough.d().qfrc_bias[dof] + rough.d().qfrc_passive[dof];
        const double expected = mode == FrictionMode::torque
                                    ? f[i] * std::tanh(2.0 * moving / f[i])
                                    : f[i] * std::tanh(rough.d().qvel[dof] / 0.01);
        EXPECT_NEAR(ta.value[i] - tb.value[i], expected, 1e-9);
        EXPECT_NEAR(a.friction_torque()[i], expected, 1e-9);
      }
      ++k;
    }
  }
  // no friction: bit for bit the same torque
  Rig plain("iiwa14_torque", "attachment_site");
  CartesianImpedanceOptions with, without;
  without.friction_feed_forward = false;
  CartesianImpedanceController c(plain.chain, with), e(plain.chain, without);
  JointCommand ta{CommandKind::torque, VectorX::Zero(7)}, tb = ta;
  for (int k = 0; k < 5;) {
    if (!test::random_state(plain, rng)) continue;
    const Reference ref = cic_random_reference(plain, rng);
    c.compute(plain.d(), ref, ta);
    e.compute(plain.d(), ref, tb);
    EXPECT_EQ(ta.value, tb.value);
    ++k;
  }
}

/// RMS position error [m] of @p c tracking a circle (r = 0.1 m, 0.2 Hz, y-z plane, starting at
/// home, full velocity from t = 0) for 5 s on @p rig, judged after the first second.
double cic_circle_rms(Rig& rig, Controller& c) {
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  const Pose X0 = test::site_pose(rig.d(), rig.chain.frame().id);
  Reference ref;
  ref.task.X_WE = X0;
  const double r = 0.1, w = 2 * std::numbers::pi * 0.2;
  JointCommand command{CommandKind::torque, VectorX::Zero(rig.chain.size())};
  double sum2 = 0.0;
  int count = 0;
  for (int k = 0; k < 2500; ++k) {
    mj_step1(&rig.m(), &rig.d());
    const double t = rig.d().time, c_t = std::cos(w * t), s_t = std::sin(w * t);
    ref.task.X_WE.p = X0.p + Eigen::Vector3d(0.0, r * (c_t - 1.0), r * s_t);
    ref.task.V_WE.head<3>() = Eigen::Vector3d(0.0, -r * w * s_t, r * w * c_t);
    ref.task.A_WE.head<3>() = Eigen::Vector3d(0.0, -r * w * w * c_t, -r * w * w * s_t);
    c.compute(rig.d(), ref, command);
    test::apply_torque(rig.chain, command.value, rig.d());
    if (t > 1.0) {
      sum2 += (test::site_pose(rig.d(), rig.chain.frame().id).p - ref.task.X_WE.p).squaredNorm();
      ++count;
    }
    mj_step2(&rig.m(), &rig.d());
  }
  return std::sqrt(sum2 / count);
}

TEST(CartesianImpedance, FrictionFeedForwardTracksACircleThroughJointFriction) {
  // Franka friction on the iiwa14: the velocity-mode feed-forward (the default) cuts the
  // tracking error several-fold; the torque mode, whose sign follows the moving torque (inertial
  // and coupling terms included), does much less — why velocity is the default here
  Rig rig(test::iiwa_torque_with_friction(test::franka_frictionloss()), "attachment_site");
  auto rms = [&](bool feed_forward, FrictionMode mode) {
    CartesianImpedanceOptions o;
    o.friction_feed_forward = feed_forward;
    o.friction.mode = mode;
    CartesianImpedanceController c(rig.chain, o);
    return cic_circle_rms(rig, c);
  };
  const double plain = rms(false, FrictionMode::velocity);
  const double velocity = rms(true, FrictionMode::velocity);
  const double torque = rms(true, FrictionMode::torque);
  Rig smooth("iiwa14_torque", "attachment_site");
  CartesianImpedanceController c(smooth.chain);
  const double frictionless = cic_circle_rms(smooth, c);
  std::printf(
      "cic circle RMS with joint friction: no feed-forward %.3f mm, velocity mode %.3f mm, "
      "torque mode %.3f mm; without friction %.4f mm\n",
      1e3 * plain, 1e3 * velocity, 1e3 * torque, 1e3 * frictionless);
  EXPECT_GT(plain, 3e-3);
  EXPECT_LT(velocity, 0.6e-3);
  EXPECT_LT(velocity, 0.5 * torque);
  EXPECT_LT(frictionless, 0.05e-3);  // the same circle without friction, for scale
}

TEST(CartesianImpedance, IntegralRemovesASteadyOffsetAgainstJointFriction) {
  // a constant 4 N push on the last link of the frictional arm holding still: the stiffness
  // alone leaves about F/K = 4 mm; the integral (k_i = 150 N/(m·s)) removes it with the time
  // constant K/k_i = 6.7 s: e^(−12/6.7) = 17 % of the offset is left after 12 s
  const Robot rough = test::iiwa_torque_with_friction(test::franka_frictionloss());
  auto offset = [&](CicIntegral integral) {
    Rig rig(rough, "attachment_site");
    mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
    mj_forward(&rig.m(), &rig.d());
    const int body = rig.m().site_bodyid[rig.chain.frame().id];
    rig.d().xfrc_applied[6 * body + 1] = 4.0;
    CartesianImpedanceOptions o;
    o.integral = integral;
    CartesianImpedanceController c(rig.chain, o);
    Reference ref;
    ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
    return test::run_closed_loop(rig, c, ref, 12.0);
  };
  const double plain = offset(CicIntegral::off);
  const double integral = offset(CicIntegral::automatic);
  std::printf("cic 4 N push, 12 s: offset %.3f mm without the integral, %.3f mm with\n",
              1e3 * plain, 1e3 * integral);
  EXPECT_GT(plain, 3e-3);
  EXPECT_LT(integral, 0.2 * plain);
}

TEST(CartesianImpedance, BadInputNeverGivesANonFiniteTorque) {
  Rig rig(test::iiwa_ft_tool(), "tip");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  CartesianImpedanceOptions o;
  o.force.kind = WrenchSourceKind::sensor;
  o.force.site = "ft";
  CartesianImpedanceController c(rig.chain, o);
  Reference ref;
  const Pose X = test::site_pose(rig.d(), rig.chain.frame().id);
  ref.task.X_WE = X;
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  // hold: h − τ_passive − D_n·q̇
  VectorX hold(7);
  for (int i = 0; i < 7; ++i) {
    const int dof = rig.chain.dof_address(i);
    hold[i] = rig.d().qfrc_bias[dof] - rig.d().qfrc_passive[dof] - 5.0 * rig.d().qvel[dof];
  }
  // non-finite wrench: ignored this tick, the law runs
  rig.d().sensordata[2] = NAN;
  c.compute(rig.d(), ref, command);
  EXPECT_EQ(c.status(), CicStatus::invalid_wrench);
  EXPECT_TRUE(command.value.allFinite());
  EXPECT_EQ(c.internal_values()[10], 0.0);  // wrench_valid
  rig.d().sensordata[2] = 0.0;
  // a target that is not a rotation, or not finite: the hold command
  ref.task.X_WE.R(0, 0) = 1.5;
  c.compute(rig.d(), ref, command);
  EXPECT_EQ(c.status(), CicStatus::invalid_target);
  EXPECT_LE((command.value - hold).norm(), 1e-12);
  ref.task.X_WE = X;
  ref.task.V_WE[3] = INFINITY;
  c.compute(rig.d(), ref, command);
  EXPECT_EQ(c.status(), CicStatus::invalid_target);
  ref.task.V_WE.setZero();
  // a target beyond 2π in the log domain is the pose of its principal angle: same torque
  const Vector6d xi = (Vector6d() << 0, 0, 0, 0, 0, 0.3).finished();
  Vector6d wrapped = xi;
  wrapped.tail<3>() *= (0.3 + 2.0 * std::numbers::pi) / 0.3;
  ref.task.X_WE = X * se3::exp(xi);
  c.reset();
  c.compute(rig.d(), ref, command);
  const VectorX principal = command.value;
  ref.task.X_WE = X * se3::exp(wrapped);
  c.reset();
  c.compute(rig.d(), ref, command);
  EXPECT_EQ(c.status(), CicStatus::ok);
  EXPECT_LE((command.value - principal).norm(), 1e-9 * principal.norm());
  EXPECT_NEAR(c.internal_values()[1], 0.3, 1e-9);
  // a state that is not finite: the hold command, zero where it is not finite either
  rig.d().qvel[3] = NAN;
  c.compute(rig.d(), ref, command);
  EXPECT_EQ(c.status(), CicStatus::invalid_state);
  EXPECT_TRUE(command.value.allFinite());
  EXPECT_EQ(command.value.norm(), 0.0);
  rig.d().qvel[3] = 0.0;
  // wrong command size: untouched
  JointCommand small{CommandKind::torque, VectorX::Constant(3, 7.0)};
  c.compute(rig.d(), ref, small);
  EXPECT_EQ(small.value, VectorX::Constant(3, 7.0));
}

TEST(CartesianImpedance, BadOptionsThrowNamingThem) {
  const Robot bare = Robot::bundled("iiwa14_torque");
  const Chain chain(bare, "attachment_site");
  auto error = [&](auto edit) {
    CartesianImpedanceOptions o;
    edit(o);
    return test::error_of([&] { CartesianImpedanceController c(chain, o); });
  };
  EXPECT_NE(error([](auto& o) { o.stiffness[4] = 0.0; }).find("cic: stiffness[4] must be positive"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.stiffness[0] = -5.0; }).find("stiffness"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.desired_inertia[1] = 0.0; }).find("desired_inertia[1]"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.integral_gain = 0.0; }).find("integral_gain"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.integral_bound = NAN; }).find("integral_bound"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.integral_hold_force = -1.0; }).find("integral_hold_force"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.damping_ratio = 0.0; }).find("damping_ratio"), std::string::npos);
  // a sensor-based controller on a model without the sensor: the error names the site
  const std::string missing = error([](auto& o) {
    o.force.kind = WrenchSourceKind::sensor;
    o.force.site = "attachment_site";
  });
  EXPECT_NE(missing.find("site 'attachment_site'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("force sensor"), std::string::npos) << missing;
}

TEST(CartesianImpedance, ComputeAllocatesNothing) {
  Rig rig(test::iiwa_ft_tool(test::franka_frictionloss()), "tip");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  ref.task.X_WE.p.x() += 0.02;
  for (WrenchSourceKind kind : {WrenchSourceKind::sensor, WrenchSourceKind::observer}) {
    for (CicInertia inertia : {CicInertia::natural, CicInertia::exact}) {
      CartesianImpedanceOptions o;
      o.force.kind = kind;
      o.force.site = "ft";
      o.inertia = inertia;
      CartesianImpedanceController c(rig.chain, o);
      JointCommand command{CommandKind::torque, VectorX::Zero(7)};
      c.compute(rig.d(), ref, command);
      const std::uint64_t before = test::malloc_calls();
      for (int k = 0; k < 100; ++k) {
        rig.d().time += 0.002;
        c.compute(rig.d(), ref, command);
      }
      EXPECT_EQ(test::malloc_calls() - before, 0u);
      EXPECT_EQ(c.internal_names().size(), c.internal_values().size());
    }
  }
  EXPECT_STREQ(to_string(CicStatus::invalid_wrench), "invalid_wrench");
  EXPECT_STREQ(to_string(CicInertia::natural), "natural");
  EXPECT_STREQ(to_string(CicIntegral::automatic), "automatic");
}

}  // namespace
}  // namespace mjarm
