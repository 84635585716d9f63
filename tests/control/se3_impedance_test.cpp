#include "mjarm/control/se3_impedance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/pose_error.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/se3_jacobian.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {
namespace {

using test::Rig;
using test::VectorX;

/// A random symmetric positive definite 6×6 matrix with eigenvalues roughly in [lo, lo + s].
Matrix6d se3_random_spd(std::mt19937_64& rng, double lo, double s) {
  const Matrix6d B = Matrix6d::NullaryExpr(
      [&]() { return std::uniform_real_distribution<double>(-1.0, 1.0)(rng); });
  return lo * Matrix6d::Identity() + (s / 6.0) * B * B.transpose();
}

/// Writes the wrench F_E (E's axes, about E's origin) as MuJoCo's xfrc_applied of E's body
/// (world axes, force at the body's centre of mass).
void se3_apply_wrench(const Rig& rig, mjData& d, const Vector6d& F_E) {
  const int site = rig.chain.frame().id;
  const int body = rig.m().site_bodyid[site];
  const Pose X = test::site_pose(d, site);
  const Eigen::Vector3d f = X.R * F_E.head<3>();
  const Eigen::Vector3d com = Eigen::Map<const Eigen::Vector3d>(d.xipos + 3 * body);
  const Eigen::Vector3d t = X.R * F_E.tail<3>() + (X.p - com).cross(f);
  for (int i = 0; i < 3; ++i) {
    d.xfrc_applied[6 * body + i] = f[i];
    d.xfrc_applied[6 * body + 3 + i] = t[i];
  }
}

/// λ(t) = log(T(q(t))⁻¹·T_d(t)) along q(t) = q + q̇t + ½q̈t² and T_d(t) = T_d·exp(V_d t + ½V̇_d t²)
/// (body twist V_d and body acceleration V̇_d at t = 0), by forward kinematics on a scratch copy.
Vector6d se3_lambda_at(const Rig& rig, const mjData& d, const VectorX& qdd, const Pose& X_WD,
                       const Vector6d& V_d, const Vector6d& A_d, double t) {
  mjData* s = mj_makeData(&rig.m());
  mj_copyData(s, &rig.m(), &d);
  for (int i = 0; i < rig.chain.size(); ++i) {
    const int a = rig.chain.qpos_address(i), v = rig.chain.dof_address(i);
    s->qpos[a] = d.qpos[a] + d.qvel[v] * t + 0.5 * qdd[i] * t * t;
  }
  mj_kinematics(&rig.m(), s);
  const Pose X = test::site_pose(*s, rig.chain.frame().id);
  mj_deleteData(s);
  return se3::log(X.inverse() * (X_WD * se3::exp(V_d * t + 0.5 * A_d * t * t)));
}

TEST(Se3Impedance, ClosedLoopHoldsOnLambdaAtRandomStates) {
  // the torque of one tick, applied through MuJoCo's forward dynamics together with the measured
  // wrench (as xfrc_applied), gives joint accelerations whose λ(t) — differentiated numerically
  // from forward kinematics, sharing no code with the controller — obeys A·λ̈ + D·λ̇ + K·λ = γ
  Rig rig("iiwa14_torque", "attachment_site");
  std::mt19937_64 rng(13);
  const int n = rig.chain.size();
  int checked = 0;
  while (checked < 12) {
    if (!test::random_state(rig, rng)) continue;
    Se3ImpedanceOptions o;
    o.inertia = se3_random_spd(rng, 0.5, 3.0);
    o.damping = se3_random_spd(rng, 5.0, 30.0);
    o.stiffness = se3_random_spd(rng, 20.0, 300.0);
    o.nullspace_damping = 3.0;
    o.nullspace_stiffness = 4.0;
    Se3ImpedanceController c(rig.chain, o);
    Reference ref;
    const Pose X = test::site_pose(rig.d(), rig.chain.frame().id);
    ref.task.X_WE = test::nearby_pose(X, rng, 0.1, 1.5);
    const Vector6d V_d = test::random6(rng, 0.5), A_d = test::random6(rng, 2.0);
    const Eigen::Matrix3d& R_d = ref.task.X_WE.R;
    ref.task.V_WE << R_d * V_d.head<3>(), R_d * V_d.tail<3>();
    ref.task.A_WE << R_d * (A_d.head<3>() + V_d.tail<3>().cross(V_d.head<3>())),
        R_d * A_d.tail<3>();
    ref.joint.q = rig.chain.center();
    const Vector6d F_E = test::random6(rng, 5.0);
    c.set_measured_wrench(F_E);
    JointCommand command{CommandKind::torque, VectorX::Zero(n)};
    c.compute(rig.d(), ref, command);
    if (c.status() != Se3ImpedanceStatus::ok) continue;
    // forward dynamics under that torque and the wrench
    mjData& d = rig.d();
    // as qfrc_applied: the motors' ctrlrange would clip the torque of a random state
    for (int i = 0; i < n; ++i) {
      d.ctrl[*rig.chain.actuator(i)] = 0.0;
      d.qfrc_applied[rig.chain.dof_address(i)] = command.value[i];
    }
    se3_apply_wrench(rig, d, F_E);
    mj_forward(&rig.m(), &d);
    if (d.nefc > 0) continue;  // a joint limit or contact would add forces the law cannot know
    VectorX qdd(n);
    for (int i = 0; i < n; ++i) qdd[i] = d.qacc[rig.chain.dof_address(i)];
    const double h = 1e-3;
    auto lambda = [&](double t) { return se3_lambda_at(rig, d, qdd, ref.task.X_WE, V_d, A_d, t); };
    const Vector6d l0 = lambda(0.0), lp = lambda(h), lm = lambda(-h);
    const Vector6d lp2 = lambda(2 * h), lm2 = lambda(-2 * h);
    // fourth-order central differences
    const Vector6d l_dot = (8.0 * (lp - lm) - (lp2 - lm2)) / (12.0 * h);
    const Vector6d l_ddot = (16.0 * (lp + lm) - (lp2 + lm2) - 30.0 * l0) / (12.0 * h * h);
    EXPECT_LE((l0 - c.error()).norm(), 1e-12);
    EXPECT_LE((l_dot - c.error_rate()).norm(), 1e-6 * (1.0 + l_dot.norm()));
    const Vector6d gamma = -se3::left_jacobian(l0).transpose() * F_E;
    const Vector6d lhs = o.inertia * l_ddot + o.damping * l_dot + o.stiffness * l0;
    EXPECT_LE((lhs - gamma).norm(), 1e-5 * (o.stiffness * l0).norm())
        << "A·λ̈ + D·λ̇ + K·λ " << lhs.transpose() << "\nγ " << gamma.transpose();
    mju_zero(d.xfrc_applied, 6 * rig.m().nbody);
    mju_zero(d.qfrc_applied, rig.m().nv);
    ++checked;
  }
}

/// Free-space run of a torque-mode `Simulation` of iiwa14_torque from home (gravity on, 2 ms
/// Euler steps, one control tick per step: mj_step1 → compute → motors → mj_step2) with the
/// controller's isotropic A, D = K = 20 and a 0.10 m step of the target along world x. Returns
/// the overshoot [fraction of the step], the largest deviation [m] of the error along x from the
/// solution of A·ë + D·ė + K·e = 0, e(0) = 0.1, and the final distance [m].
struct Se3StepResult {
  double overshoot = 0.0;
  double deviation = 0.0;
  double final_error = 0.0;
  int saturated = 0;  // ticks with a clipped motor
};

Se3StepResult se3_step_response(double a, double seconds) {
  const Robot robot = Robot::bundled("iiwa14_torque");
  const Chain chain(robot, "attachment_site");
  Simulation sim(robot);  // torque mode, control period = timestep
  sim.reset("home");
  Se3ImpedanceOptions o;
  o.inertia = a * Matrix6d::Identity();
  o.damping = 20.0 * Matrix6d::Identity();
  o.stiffness = 20.0 * Matrix6d::Identity();
  Se3ImpedanceController c(chain, o);
  sim.add_controller(c);
  const int site = chain.frame().id;
  Reference ref;
  ref.task.X_WE = test::site_pose(sim.data(), site);
  ref.task.X_WE.p.x() += 0.10;
  const double dt = sim.control_period();
  // the scalar reference, integrated with a much finer step (semi-implicit Euler at dt/100:
  // exact to ~1e-6 m here)
  double e = 0.1, e_dot = 0.0;
  Se3StepResult r;
  const int steps = static_cast<int>(seconds / dt);
  for (int k = 0; k < steps; ++k) {
    // the pose the tick starts from (sim.data()'s kinematics belong to the start of the last
    // step, where e is)
    const TickResult t = sim.tick(ref);
    EXPECT_TRUE(t.ok());
    r.saturated += t.saturated > 0 ? 1 : 0;
    const double measured = ref.task.X_WE.p.x() - test::site_pose(sim.data(), site).p.x();
    r.overshoot = std::max(r.overshoot, -measured / 0.1);
    r.deviation = std::max(r.deviation, std::abs(measured - e));
    for (int j = 0; j < 100; ++j) {
      e_dot += -(20.0 * e_dot + 20.0 * e) / a * (dt / 100);
      e += e_dot * (dt / 100);
    }
  }
  sim.forward();
  r.final_error = (test::site_pose(sim.data(), site).p - ref.task.X_WE.p).norm();
  return r;
}

TEST(Se3Impedance, StepOvershootFollowsTheApparentInertia) {
  // ζ = D/(2√(A·K)): A = 0.5 → ζ = 3.16, A = 5 → ζ = 1 (no overshoot), A = 100 → ζ = 0.2236,
  // overshoot exp(−πζ/√(1 − ζ²)) = 48.6 %. Tolerance ±1 percentage point: the only departures
  // from the linear loop are the 2 ms zero-order hold (ω_n·dt ≤ 0.013) and MuJoCo's implicit
  // joint damping in the Euler step (adds dt·b ≤ 0.002 kg·m² to each joint's inertia); both move
  // ζ by well under 1 %, and d(overshoot)/dζ ≈ −1.65 at ζ = 0.2236.
  const double zeta = 20.0 / (2.0 * std::sqrt(100.0 * 20.0));
  const double expected = std::exp(-std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta));
  ASSERT_NEAR(expected, 0.486, 5e-4);
  const Se3StepResult soft = se3_step_response(100.0, 9.0);
  EXPECT_NEAR(soft.overshoot, expected, 0.01);
  EXPECT_EQ(soft.saturated, 0);
  EXPECT_LT(soft.deviation, 1e-3);
  for (double a : {0.5, 5.0}) {
    const Se3StepResult r = se3_step_response(a, 8.0);
    EXPECT_LT(r.overshoot, 1e-3) << "A = " << a;
    EXPECT_LT(r.deviation, 1e-3) << "A = " << a;
    EXPECT_LT(r.final_error, 1e-3) << "A = " << a;
  }
}

/// Runs @p c on @p rig for @p seconds as a split step; @p each(k) runs after mj_step1, before
/// compute (to set wrenches, read the state).
template <typename Each>
void se3_run(Rig& rig, Se3ImpedanceController& c, const Reference& ref, double seconds, Each each) {
  JointCommand command{CommandKind::torque, VectorX::Zero(rig.chain.size())};
  const int steps = static_cast<int>(seconds / rig.m().opt.timestep);
  for (int k = 0; k < steps; ++k) {
    mj_step1(&rig.m(), &rig.d());
    each(k);
    c.compute(rig.d(), ref, command);
    test::apply_torque(rig.chain, command.value, rig.d());
    mj_step2(&rig.m(), &rig.d());
  }
  mj_forward(&rig.m(), &rig.d());
}

TEST(Se3Impedance, RotationOf179DegreesConvergesWithoutFlipping) {
  // from home with joint 7 at −1.5 rad (room for +179° about the flange axis within ±175°), a
  // target turned 179° about E's z: λ's rotation angle falls monotonically to zero about the
  // same axis (the principal log never jumps to the other side of π)
  Rig rig("iiwa14_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  rig.d().qpos[rig.chain.qpos_address(6)] = -1.5;
  mj_forward(&rig.m(), &rig.d());
  const int site = rig.chain.frame().id;
  Reference ref;
  const Pose start = test::site_pose(rig.d(), site);
  const double angle = 179.0 * std::numbers::pi / 180.0;
  ref.task.X_WE = start * se3::exp((Vector6d() << 0, 0, 0, 0, 0, angle).finished());
  Se3ImpedanceOptions o;
  o.stiffness = 25.0 * Matrix6d::Identity();
  o.damping = 10.0 * Matrix6d::Identity();  // critical for A = I
  Se3ImpedanceController c(rig.chain, o);
  double previous = INFINITY;
  double worst_rise = 0.0, worst_axis = 1.0;
  int ticks = 0;
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  for (int k = 0; k < 2000; ++k) {  // 4 s
    mj_step1(&rig.m(), &rig.d());
    c.compute(rig.d(), ref, command);
    const Eigen::Vector3d w = c.error().tail<3>();
    if (k == 0) {
      EXPECT_NEAR(w.norm(), angle, 1e-9);
    }
    if (w.norm() > 1e-3) worst_axis = std::min(worst_axis, w.normalized().z());
    worst_rise = std::max(worst_rise, w.norm() - previous);
    previous = w.norm();
    EXPECT_EQ(c.status(), Se3ImpedanceStatus::ok);
    test::apply_torque(rig.chain, command.value, rig.d());
    mj_step2(&rig.m(), &rig.d());
    ++ticks;
  }
  mj_forward(&rig.m(), &rig.d());
  EXPECT_LE(worst_rise, 1e-9);   // monotone
  EXPECT_GT(worst_axis, 0.999);  // about +z of E all the way
  const Vector6d e = log_error(test::site_pose(rig.d(), site), ref.task.X_WE);
  EXPECT_LT(e.tail<3>().norm(), 1e-3);
  EXPECT_LT((test::site_pose(rig.d(), site).p - ref.task.X_WE.p).norm(), 1e-3);
}

TEST(Se3Impedance, ZeroStiffnessAxisYieldsToAPushWhileTheOthersHold) {
  // K = 400 except E's z (released, zero stiffness); a 5 N push along E's z at E's origin
  // (xfrc_applied), measured exactly: λ_z obeys A·λ̈ + D·λ̇ = −F (E drifts at F/D), every other
  // λ coordinate stays at zero
  Rig rig("iiwa14_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  const int site = rig.chain.frame().id;
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), site);
  Se3ImpedanceOptions o;
  o.inertia = 2.0 * Matrix6d::Identity();
  o.damping = 40.0 * Matrix6d::Identity();
  o.stiffness = 400.0 * Matrix6d::Identity();
  o.stiffness(2, 2) = 0.0;
  o.release.axes[2] = true;
  const Vector6d push = (Vector6d() << 0, 0, -5.0, 0, 0, 0).finished();  // up, away from the floor
  for (bool measured : {true, false}) {
    mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
    mj_forward(&rig.m(), &rig.d());
    Se3ImpedanceController c(rig.chain, o);
    double others = 0.0;
    se3_run(rig, c, ref, 1.0, [&](int) {
      se3_apply_wrench(rig, rig.d(), push);
      if (measured) c.set_measured_wrench(push);
      Vector6d l = log_error(test::site_pose(rig.d(), site), ref.task.X_WE);
      l[2] = 0.0;
      others = std::max(others, l.norm());
    });
    const double z = log_error(test::site_pose(rig.d(), site), ref.task.X_WE)[2];
    if (measured) {
      // λ_z(1 s) = (F/D)·(t − (A/D)(1 − e^(−D·t/A))) with F = 5, D = 40, A = 2
      const double expected = 5.0 / 40.0 * (1.0 - 2.0 / 40.0 * (1.0 - std::exp(-20.0)));
      EXPECT_NEAR(z, expected, 2e-3);
      // (not exactly zero: MuJoCo's Euler step treats joint damping implicitly, adding dt·b to
      // each joint's inertia, which the law does not model; measured ~1e-4)
      EXPECT_LT(others, 5e-4);
    } else {
      // unmeasured: the arm's own inertia meets the push (the stiffness felt is Λ·A⁻¹·K and
      // couples through Λ): the free axis still yields by centimetres, the stiff ones by
      // millimetres
      EXPECT_GT(z, 0.01);
      EXPECT_LT(others, 1e-2);
    }
    mju_zero(rig.d().xfrc_applied, 6 * rig.m().nbody);
  }
}

/// A state at rest on the target for the unit checks.
struct Se3RestCase {
  Rig rig{"iiwa14_torque", "attachment_site"};
  Reference ref;
  Se3RestCase() {
    mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
    mj_forward(&rig.m(), &rig.d());
    ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
    ref.task.X_WE.p.y() += 0.02;
  }
};

TEST(Se3Impedance, ContactReleasesTheChosenAxesWithASmoothstep) {
  Se3RestCase s;
  Se3ImpedanceOptions o;
  o.stiffness(0, 2) = o.stiffness(2, 0) = 50.0;  // a coupling the release must scale too
  o.release.axes[2] = true;
  o.release.axes[5] = true;
  Se3ImpedanceController c(s.rig.chain, o);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  auto at = [&](double t) {
    s.rig.d().time = t;
    c.compute(s.rig.d(), s.ref, command);
  };
  c.set_measured_wrench((Vector6d() << 1.0, 1.0, 1.0, 9.0, 9.0, 9.0).finished());  // ‖f‖ < 2 N
  at(0.5);
  EXPECT_FALSE(c.release_started());
  EXPECT_EQ(c.release_fraction(), 0.0);
  c.set_measured_wrench((Vector6d() << 0.0, 0.0, 2.5, 0, 0, 0).finished());
  at(1.0);  // the contact: release starts now
  EXPECT_TRUE(c.release_started());
  EXPECT_EQ(c.release_fraction(), 0.0);
  c.set_measured_wrench(Vector6d::Zero());  // losing contact does not undo it
  at(1.0625);                               // x = 0.25: s = x²(3 − 2x) = 0.15625
  EXPECT_NEAR(c.release_fraction(), 0.15625, 1e-12);
  EXPECT_NEAR(c.stiffness()(2, 2), 400.0 * (1 - 0.15625) * (1 - 0.15625), 1e-9);
  EXPECT_NEAR(c.stiffness()(0, 2), 50.0 * (1 - 0.15625), 1e-9);
  EXPECT_EQ(c.stiffness()(1, 1), 400.0);
  at(1.125);
  EXPECT_NEAR(c.release_fraction(), 0.5, 1e-12);
  EXPECT_NEAR(c.internal_values()[15], 0.5, 1e-12);
  at(1.4);
  EXPECT_EQ(c.release_fraction(), 1.0);
  EXPECT_EQ(c.stiffness()(2, 2), 0.0);
  EXPECT_EQ(c.stiffness()(5, 5), 0.0);
  EXPECT_EQ(c.stiffness()(0, 2), 0.0);
  EXPECT_EQ(c.stiffness()(0, 0), 400.0);
  c.reset();
  EXPECT_FALSE(c.release_started());
  at(1.5);
  EXPECT_EQ(c.stiffness()(2, 2), 400.0);
  c.start_release(2.0);  // by hand
  at(2.25);
  EXPECT_EQ(c.release_fraction(), 1.0);
  // nothing to release: the trigger does nothing
  Se3ImpedanceController fixed(s.rig.chain);
  fixed.set_measured_wrench((Vector6d() << 0, 0, 50.0, 0, 0, 0).finished());
  fixed.compute(s.rig.d(), s.ref, command);
  EXPECT_FALSE(fixed.release_started());
}

TEST(Se3Impedance, ADisarmedReleaseIsUndoneAndContactStartsNoneUntilArmedAgain) {
  Se3RestCase s;
  Se3ImpedanceOptions o;
  o.release.axes[2] = true;
  Se3ImpedanceController c(s.rig.chain, o);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  auto at = [&](double t) {
    s.rig.d().time = t;
    c.compute(s.rig.d(), s.ref, command);
  };
  const Vector6d contact = (Vector6d() << 0.0, 0.0, 2.5, 0, 0, 0).finished();
  c.set_measured_wrench(contact);
  at(1.0);
  at(1.125);
  ASSERT_NEAR(c.release_fraction(), 0.5, 1e-12);  // released half way
  c.set_release_armed(false);
  at(1.2);  // still in contact: full stiffness, no release
  EXPECT_FALSE(c.release_started());
  EXPECT_EQ(c.release_fraction(), 0.0);
  EXPECT_EQ(c.stiffness()(2, 2), 400.0);
  c.start_release(1.3);  // by hand, it still starts: disarming only stops contact
  at(1.3);
  EXPECT_TRUE(c.release_started());
  c.set_release_armed(false);
  c.set_release_armed(true);
  at(1.5);  // armed again and in contact: a new release from now
  EXPECT_TRUE(c.release_started());
  EXPECT_EQ(c.release_fraction(), 0.0);
  at(1.625);
  EXPECT_NEAR(c.release_fraction(), 0.5, 1e-12);
}

TEST(Se3Impedance, BadGainsThrowNamingTheMatrix) {
  Se3RestCase s;
  auto expect_throw = [&](auto edit, const char* what) {
    Se3ImpedanceOptions o;
    edit(o);
    try {
      Se3ImpedanceController c(s.rig.chain, o);
      ADD_FAILURE() << "no exception for " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_throw([](auto& o) { o.inertia(0, 1) = 0.5; }, "inertia A must be symmetric");
  expect_throw([](auto& o) { o.inertia(3, 3) = -1.0; },
               "inertia A must be symmetric positive definite");
  expect_throw([](auto& o) { o.damping.setZero(); },
               "damping D must be symmetric positive definite");
  expect_throw([](auto& o) { o.damping(2, 2) = NAN; }, "damping D must be finite");
  expect_throw([](auto& o) { o.stiffness(1, 1) = -5.0; }, "positive semi-definite");
  expect_throw([](auto& o) { o.stiffness(4, 4) = 0.0; }, "not released [x, y, z, rx, ry, rz]");
  expect_throw([](auto& o) { o.stiffness(0, 1) = o.stiffness(1, 0) = 400.0; }, "not released");
  expect_throw([](auto& o) { o.release.duration = 0.0; }, "release.duration");
  expect_throw([](auto& o) { o.release.contact_force = NAN; }, "release.contact_force");
  expect_throw([](auto& o) { o.nullspace_damping = -1.0; }, "nullspace_damping");
  // zero stiffness on a released axis is allowed; so is a fully released K
  Se3ImpedanceOptions o;
  o.stiffness(4, 4) = 0.0;
  o.release.axes[4] = true;
  EXPECT_NO_THROW(Se3ImpedanceController(s.rig.chain, o));
  o.stiffness.setZero();
  o.release.axes.fill(true);
  EXPECT_NO_THROW(Se3ImpedanceController(s.rig.chain, o));
}

TEST(Se3Impedance, BadTargetsGetAnHonestStatusAndAFiniteHold) {
  Se3RestCase s;
  Se3ImpedanceController c(s.rig.chain);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  const mjData& d = s.rig.d();
  VectorX hold(7);
  for (int i = 0; i < 7; ++i) {
    hold[i] = d.qfrc_bias[i] - d.qfrc_passive[i] - 5.0 * d.qvel[i];
  }
  auto expect_hold = [&](const Reference& ref, const char* what) {
    command.value.setConstant(123.0);
    c.compute(d, ref, command);
    EXPECT_EQ(c.status(), Se3ImpedanceStatus::invalid_target) << what;
    EXPECT_TRUE(command.value.allFinite()) << what;
    EXPECT_LE((command.value - hold).norm(), 1e-12) << what;
    EXPECT_EQ(c.internal_values()[16], 2.0) << what;
  };
  Reference ref = s.ref;
  ref.task.X_WE.p.x() = NAN;
  expect_hold(ref, "NaN position");
  ref = s.ref;
  ref.task.X_WE.R(1, 2) = INFINITY;
  expect_hold(ref, "inf rotation");
  ref = s.ref;
  ref.task.X_WE.R *= 2.0;
  expect_hold(ref, "scaled rotation");
  ref = s.ref;
  ref.task.X_WE.R.col(0) *= -1.0;
  expect_hold(ref, "reflection");
  ref = s.ref;
  ref.task.V_WE[4] = NAN;
  expect_hold(ref, "NaN twist");
  ref = s.ref;
  ref.task.A_WE[0] = -INFINITY;
  expect_hold(ref, "inf acceleration");
  // a good target afterwards: back to ok
  c.compute(d, s.ref, command);
  EXPECT_EQ(c.status(), Se3ImpedanceStatus::ok);
}

TEST(Se3Impedance, TargetBeyondTwoPiIsItsPrincipalPose) {
  // a target built as exp(ξ) with ‖ω‖ = 2π + 0.3 is the same pose as ‖ω‖ = 0.3: the error is the
  // principal log (‖ω‖ ≤ π), reported as such with status ok, and the torque is that of 0.3 rad
  Se3RestCase s;
  const Pose X = test::site_pose(s.rig.d(), s.rig.chain.frame().id);
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  Vector6d far;
  far << 0.01, 0.02, -0.03, (2 * std::numbers::pi + 0.3) * axis;
  Pose near = se3::exp(far);
  near.R = Eigen::AngleAxisd(0.3, axis).toRotationMatrix();
  Reference a = s.ref, b = s.ref;
  a.task.X_WE = X * se3::exp(far);
  b.task.X_WE = X * near;
  Se3ImpedanceController c(s.rig.chain);
  JointCommand ta{CommandKind::torque, VectorX::Zero(7)}, tb = ta;
  c.compute(s.rig.d(), a, ta);
  EXPECT_EQ(c.status(), Se3ImpedanceStatus::ok);
  EXPECT_NEAR(c.error().tail<3>().norm(), 0.3, 1e-9);
  EXPECT_GT(c.error().tail<3>().normalized().dot(axis), 1.0 - 1e-9);
  c.compute(s.rig.d(), b, tb);
  EXPECT_LE((ta.value - tb.value).norm(), 1e-8 * tb.value.norm());
}

TEST(Se3Impedance, BadWrenchAndBadStateNeverGiveNaN) {
  Se3RestCase s;
  Se3ImpedanceController c(s.rig.chain);
  JointCommand clean{CommandKind::torque, VectorX::Zero(7)}, command = clean;
  c.compute(s.rig.d(), s.ref, clean);
  // a non-finite wrench reading is ignored this tick (the law runs as with zero wrench)
  c.set_measured_wrench((Vector6d() << 1.0, NAN, 0, 0, 0, 0).finished());
  c.compute(s.rig.d(), s.ref, command);
  EXPECT_EQ(c.status(), Se3ImpedanceStatus::invalid_wrench);
  EXPECT_EQ(std::string(to_string(c.status())), "invalid_wrench");
  EXPECT_LE((command.value - clean.value).norm(), 1e-12 * clean.value.norm());
  // a NaN joint speed: hold would be NaN, so zero torque
  c.reset();
  s.rig.d().qvel[3] = NAN;
  c.compute(s.rig.d(), s.ref, command);
  EXPECT_EQ(c.status(), Se3ImpedanceStatus::invalid_state);
  EXPECT_TRUE(command.value.allFinite());
  EXPECT_EQ(command.value.norm(), 0.0);
}

TEST(Se3Impedance, AtTheStretchedSingularityTheStatusSaysDamped) {
  // q = 0: the iiwa14 stands straight up, joints 1, 3, 5, 7 share one axis; Λ is floored
  Rig rig("iiwa14_torque", "attachment_site");
  mj_resetData(&rig.m(), &rig.d());
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  ref.task.X_WE.p.x() += 0.05;
  Se3ImpedanceController c(rig.chain);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  c.compute(rig.d(), ref, command);
  EXPECT_EQ(c.status(), Se3ImpedanceStatus::damped);
  EXPECT_EQ(c.internal_values()[14], 1.0);
  EXPECT_TRUE(command.value.allFinite());
  EXPECT_GT(c.internal_values()[13], 1e3);  // task_condition
}

TEST(Se3Impedance, InternalsAreNamedSizedAndFinite) {
  Se3RestCase s;
  Se3ImpedanceController c(s.rig.chain);
  ASSERT_EQ(c.internal_names().size(), c.internal_values().size());
  EXPECT_EQ(c.internal_names()[12], "dexp_condition");
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  c.compute(s.rig.d(), s.ref, command);
  const auto v = c.internal_values();
  EXPECT_NEAR(v[1], c.error()[1], 0.0);
  // λ = log_error of the target seen from E
  const Vector6d l = log_error(test::site_pose(s.rig.d(), s.rig.chain.frame().id), s.ref.task.X_WE);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(v[static_cast<std::size_t>(i)], l[i], 1e-12);
  EXPECT_GE(v[12], 1.0);  // cond(E) of a pure translation error: close to 1
  EXPECT_LT(v[12], 1.1);
  EXPECT_NEAR(v[13], c.task_space().eigenvalues()[5] / c.task_space().eigenvalues()[0],
              1e-9 * v[13]);
  EXPECT_EQ(c.name(), "se3");
  EXPECT_EQ(c.command_kind(), CommandKind::torque);
}

TEST(Se3Impedance, ComputeAllocatesNothing) {
  Rig rig("iiwa14_torque", "attachment_site");
  std::mt19937_64 rng(21);
  while (!test::random_state(rig, rng)) {
  }
  Se3ImpedanceOptions o;
  o.release.axes[2] = true;
  o.nullspace_stiffness = 3.0;
  Se3ImpedanceController c(rig.chain, o);
  Reference ref;
  ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), rig.chain.frame().id), rng, 0.1, 2.0);
  ref.task.V_WE = test::random6(rng, 0.5);
  ref.task.A_WE = test::random6(rng, 1.0);
  ref.joint.q = rig.chain.center();
  c.set_measured_wrench((Vector6d() << 0, 0, 3.0, 0.1, 0, 0).finished());  // triggers the release
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  c.compute(rig.d(), ref, command);  // warm-up
  const std::uint64_t before = test::malloc_calls();
  double sum = 0.0;
  for (int k = 0; k < 100; ++k) {
    rig.d().time += 1e-3;
    c.compute(rig.d(), ref, command);
    sum += c.internal_values()[12] + c.internal_values()[13];  // on-demand SVD/eigen too
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_TRUE(std::isfinite(sum));
  EXPECT_TRUE(c.release_started());
}

TEST(Se3Impedance, WrongCommandSizeIsLeftUntouched) {
  Se3RestCase s;
  Se3ImpedanceController c(s.rig.chain);
  JointCommand command{CommandKind::torque, VectorX::Constant(3, 7.0)};
  c.compute(s.rig.d(), s.ref, command);
  EXPECT_EQ(command.value, VectorX::Constant(3, 7.0));
}

}  // namespace
}  // namespace mjarm
