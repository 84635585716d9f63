#include "mjarm/control/operational_space.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "support/reference_linear_algebra.hpp"

namespace mjarm {
namespace {

using test::MatrixX;
using test::Rig;
using test::run_closed_loop;
using test::VectorX;

/// Everything the independent formula needs besides the state.
struct OscCase {
  Reference ref;
  OperationalSpaceOptions options;
  Vector6d wrench = Vector6d::Zero();  // measured F_m (used with wrench_feedback)
};

/// τ of the operational-space law written straight from the docs with dense inverses.
/// @p integral is ∫e dt as the controller should hold it.
VectorX reference_osc_torque(const mjModel& m, const mjData& d, int site, const OscCase& c,
                             const Vector6d& integral) {
  const auto& o = c.options;
  const int rows = task_rows(o.mode);
  const MatrixX M = test::dense_mass(m, d);
  const MatrixX J = test::site_jacobian(m, d, site).topRows(rows);
  const VectorX qd = Eigen::Map<const VectorX>(d.qvel, m.nv);
  const VectorX q = Eigen::Map<const VectorX>(d.qpos, m.nq);
  const MatrixX Minv = test::inverse(M);
  const MatrixX Lambda = test::inverse(J * Minv * J.transpose());
  const VectorX jdot_qd = test::site_jdot_qdot(m, d, site).head(rows);

  const Vector6d e6 = test::reference_error(test::site_pose(d, site), c.ref.task.X_WE);
  const VectorX e = e6.head(rows);
  const VectorX e_dot = c.ref.task.V_WE.head(rows) - J * qd;
  VectorX K = o.stiffness.head(rows), Ki = o.integral_gain.head(rows), D(rows);
  for (int i = 0; i < rows; ++i) {
    const double mass = o.task_inertia ? Lambda(i, i) : o.inertia[i];
    D[i] = o.damping[i] >= 0.0 ? o.damping[i] : 2.0 * o.damping_ratio * std::sqrt(mass * K[i]);
  }
  const VectorX f =
      K.asDiagonal() * e + D.asDiagonal() * e_dot + Ki.asDiagonal() * integral.head(rows);
  // (each step into a named vector: GCC 12 reports a false use-after-free on the nested form)
  VectorX u = c.ref.task.A_WE.head(rows);
  const bool feedback = o.wrench_feedback && !o.task_inertia;
  VectorX pushed = f;
  if (feedback) pushed += c.wrench.head(rows) + c.ref.task.F_ext.head(rows);
  if (!o.task_inertia) u += o.inertia.head(rows).cwiseInverse().asDiagonal() * pushed;
  u -= jdot_qd;
  VectorX F = Lambda * u;
  if (o.task_inertia) F += f;
  if (feedback) {
    F -= c.wrench.head(rows);
  } else {
    F += c.ref.task.F_ext.head(rows);
  }

  const VectorX h = Eigen::Map<const VectorX>(d.qfrc_bias, m.nv);
  const VectorX passive = Eigen::Map<const VectorX>(d.qfrc_passive, m.nv);
  const MatrixX Jbar = Minv * J.transpose() * Lambda;
  const MatrixX N = MatrixX::Identity(m.nv, m.nv) - Jbar * J;
  VectorX tau0 = -o.nullspace_damping * qd;
  if (c.ref.joint.q.size() == m.nv) tau0 += o.nullspace_stiffness * (c.ref.joint.q - q);
  VectorX tau = J.transpose() * F + h + N.transpose() * tau0;
  if (o.compensate_passive) tau -= passive;
  return tau;
}

OscCase random_case(Rig& rig, std::mt19937_64& rng, TaskMode mode, bool task_inertia) {
  OscCase c;
  const int site = rig.chain.frame().id;
  c.ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), site), rng, 0.1, 0.5);
  c.ref.task.V_WE = test::random6(rng, 0.5);
  c.ref.task.A_WE = test::random6(rng, 2.0);
  c.ref.task.F_ext = test::random6(rng, 5.0);
  c.ref.joint.q = VectorX::Zero(rig.chain.size());
  for (int i = 0; i < rig.chain.size(); ++i) c.ref.joint.q[i] = rig.chain.center()[i];
  c.options.mode = mode;
  c.options.task_inertia = task_inertia;
  c.options.stiffness = test::random6(rng, 100.0).array().abs() + 50.0;
  if (task_inertia) c.options.stiffness *= 5.0;
  c.options.damping << 20.0, -1.0, 15.0, -1.0, 3.0, -1.0;  // explicit and automatic entries
  c.options.damping_ratio = 0.8;
  c.options.inertia << 2.0, 1.5, 1.0, 0.2, 0.3, 0.25;
  c.options.integral_gain = Vector6d::Constant(30.0);
  c.options.integral_limit = Vector6d::Constant(1e-3);
  c.options.nullspace_damping = 3.0;
  c.options.nullspace_stiffness = 7.0;
  return c;
}

void expect_close(const VectorX& actual, const VectorX& expected, double rel) {
  ASSERT_EQ(actual.size(), expected.size());
  EXPECT_LE((actual - expected).norm(), rel * expected.norm())
      << "actual   " << actual.transpose() << "\nexpected " << expected.transpose();
}

void check_against_formula(TaskMode mode, bool task_inertia, std::uint64_t seed,
                           bool wrench_feedback = false) {
  Rig rig("panda_torque", "attachment_site");
  std::mt19937_64 rng(seed);
  int checked = 0;
  while (checked < 25) {
    if (!test::random_state(rig, rng)) continue;
    OscCase c = random_case(rig, rng, mode, task_inertia);
    c.options.wrench_feedback = wrench_feedback;
    c.wrench = test::random6(rng, 8.0);
    OperationalSpaceController osc(rig.chain, c.options);
    osc.set_measured_wrench(c.wrench);
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    // first call: no integral yet
    osc.compute(rig.d(), c.ref, command);
    if (osc.task_space().status() != TaskSpaceStatus::ok) continue;  // formula assumes exact Λ
    const int site = rig.chain.frame().id;
    expect_close(command.value, reference_osc_torque(rig.m(), rig.d(), site, c, Vector6d::Zero()),
                 1e-8);
    // second call 5 ms later: the integral holds e·Δt, clamped to ±1e-3
    const Vector6d e = test::reference_error(test::site_pose(rig.d(), site), c.ref.task.X_WE);
    Vector6d integral = (e * 5e-3).cwiseMax(-1e-3).cwiseMin(1e-3);
    if (mode == TaskMode::position) integral.tail<3>().setZero();
    rig.d().time += 5e-3;
    osc.compute(rig.d(), c.ref, command);
    EXPECT_LE((osc.integral() - integral).norm(), 1e-15);
    expect_close(command.value, reference_osc_torque(rig.m(), rig.d(), site, c, integral), 1e-8);
    ++checked;
  }
}

TEST(OperationalSpace, MatchesIndependentFormulaPose) {
  check_against_formula(TaskMode::pose, false, 1);
}
TEST(OperationalSpace, MatchesIndependentFormulaPosition) {
  check_against_formula(TaskMode::position, false, 2);
}
TEST(OperationalSpace, MatchesIndependentFormulaTaskInertia) {
  check_against_formula(TaskMode::pose, true, 3);
  check_against_formula(TaskMode::position, true, 4);
}

TEST(OperationalSpace, MatchesIndependentFormulaWithWrenchFeedback) {
  check_against_formula(TaskMode::pose, false, 5, true);
  check_against_formula(TaskMode::position, false, 6, true);
  // with M_d = Λ there is nothing to render: the measured wrench changes nothing
  check_against_formula(TaskMode::pose, true, 7, true);
}

TEST(OperationalSpace, WrenchFeedbackRendersTheDesiredInertiaExactly) {
  // the torque of one tick and a wrench on E (xfrc_applied, measured exactly) through MuJoCo's
  // forward dynamics: E's acceleration is A_WD + M_d⁻¹·(K·e + D·ė + F_m + F_ext) — the arm
  // responds to the contact wrench with M_d, not with its own Λ
  Rig rig("panda_torque", "attachment_site");
  std::mt19937_64 rng(17);
  const int site = rig.chain.frame().id;
  const int body = rig.m().site_bodyid[site];
  int checked = 0;
  while (checked < 10) {
    if (!test::random_state(rig, rng)) continue;
    OscCase c = random_case(rig, rng, TaskMode::pose, false);
    c.options.wrench_feedback = true;
    c.options.damping << 20.0, 15.0, 10.0, 3.0, 2.0, 1.0;
    c.options.integral_gain.setZero();
    const Vector6d F_m = test::random6(rng, 10.0);
    OperationalSpaceController osc(rig.chain, c.options);
    osc.set_measured_wrench(F_m);
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    osc.compute(rig.d(), c.ref, command);
    if (osc.task_space().status() != TaskSpaceStatus::ok) continue;
    mjData& d = rig.d();
    const Pose X = test::site_pose(d, site);
    const Vector6d e = test::reference_error(X, c.ref.task.X_WE);
    const MatrixX J = test::site_jacobian(rig.m(), d, site);
    const VectorX qd = Eigen::Map<const VectorX>(d.qvel, rig.m().nv);
    const Vector6d e_dot = c.ref.task.V_WE - J * qd;
    const Vector6d jdot_qd = test::site_jdot_qdot(rig.m(), d, site);
    // the wrench F_m at E's origin, as xfrc_applied at the body's centre of mass
    const Eigen::Vector3d com = Eigen::Map<const Eigen::Vector3d>(d.xipos + 3 * body);
    for (int i = 0; i < 3; ++i) {
      d.xfrc_applied[6 * body + i] = F_m[i];
      d.xfrc_applied[6 * body + 3 + i] = F_m[3 + i] + (X.p - com).cross(F_m.head<3>())[i];
    }
    for (int i = 0; i < 7; ++i) {
      d.ctrl[*rig.chain.actuator(i)] = 0.0;
      d.qfrc_applied[rig.chain.dof_address(i)] = command.value[i];
    }
    mj_forward(&rig.m(), &d);
    const bool free = d.nefc == 0;  // a joint limit would add forces the law cannot know
    const VectorX qacc = Eigen::Map<const VectorX>(d.qacc, rig.m().nv);
    const Vector6d a = J * qacc + jdot_qd;
    const Vector6d f = c.options.stiffness.cwiseProduct(e) + c.options.damping.cwiseProduct(e_dot);
    const Vector6d expected =
        c.ref.task.A_WE + (f + F_m + c.ref.task.F_ext).cwiseQuotient(c.options.inertia);
    mju_zero(d.xfrc_applied, 6 * rig.m().nbody);
    mju_zero(d.qfrc_applied, rig.m().nv);
    if (!free) continue;
    EXPECT_LE((a - expected).norm(), 1e-6 * expected.norm())
        << "a " << a.transpose() << "\nexpected " << expected.transpose();
    ++checked;
  }
}

TEST(OperationalSpace, IntegralIsHeldWhileTheMeasuredForceIsLarge) {
  Rig rig("panda_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  ref.task.X_WE.p.x() += 0.01;
  OperationalSpaceOptions o;
  o.integral_gain = Vector6d::Constant(10.0);
  o.integral_hold_force = 1.0;
  OperationalSpaceController osc(rig.chain, o);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  osc.compute(rig.d(), ref, command);
  rig.d().time += 0.01;
  osc.compute(rig.d(), ref, command);
  EXPECT_FALSE(osc.integral_held());
  const double before = osc.integral()[0];
  EXPECT_NEAR(before, 0.01 * 0.01, 1e-12);
  osc.set_measured_wrench((Vector6d() << 0.0, 0.6, 0.8, 5.0, 0.0, 0.0).finished());  // ‖f‖ = 1 N
  rig.d().time += 0.01;
  osc.compute(rig.d(), ref, command);
  EXPECT_TRUE(osc.integral_held());
  EXPECT_EQ(osc.integral()[0], before);
  osc.set_measured_wrench((Vector6d() << 0.0, 0.6, 0.7, 5.0, 0.0, 0.0).finished());  // below
  rig.d().time += 0.01;
  osc.compute(rig.d(), ref, command);
  EXPECT_FALSE(osc.integral_held());
  EXPECT_NEAR(osc.integral()[0], 2.0 * before, 1e-12);
  // a non-finite wrench is taken as zero: no hold, no NaN
  osc.set_measured_wrench(Vector6d::Constant(NAN));
  rig.d().time += 0.01;
  osc.compute(rig.d(), ref, command);
  EXPECT_FALSE(osc.integral_held());
  EXPECT_TRUE(command.value.allFinite());
  osc.reset();
  EXPECT_EQ(osc.measured_wrench().norm(), 0.0);
}

TEST(OperationalSpace, ZeroErrorAtRestHoldsAgainstGravity) {
  // at rest on target, τ = h − passive exactly: the arm is held, nothing else is commanded
  Rig rig("panda_torque", "attachment_site");
  std::mt19937_64 rng(5);
  test::random_state(rig, rng);
  mju_zero(rig.d().qvel, rig.m().nv);
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  OperationalSpaceController osc(rig.chain);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  osc.compute(rig.d(), ref, command);
  const VectorX h = Eigen::Map<const VectorX>(rig.d().qfrc_bias, 7);
  EXPECT_LE((command.value - h).norm(), 1e-9 * h.norm());
}

TEST(OperationalSpace, ConvergesOnPandaInSimulation) {
  Rig rig("panda_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  const Pose home = test::site_pose(rig.d(), rig.chain.frame().id);
  Reference ref;
  ref.task.X_WE.p = home.p + Eigen::Vector3d(0.12, -0.15, -0.1);
  ref.task.X_WE.R =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix() * home.R;
  OperationalSpaceController osc(rig.chain);
  const double error = run_closed_loop(rig, osc, ref, 2.0);
  EXPECT_LT(error, 1e-3);
  const Vector6d e =
      test::reference_error(test::site_pose(rig.d(), rig.chain.frame().id), ref.task.X_WE);
  EXPECT_LT(e.tail<3>().norm(), 1e-3);
  EXPECT_LT(osc.internal_values()[0], 1e-3);  // position_error internal agrees
}

TEST(OperationalSpace, IntegralRemovesAConstantDisturbance) {
  // a constant unmodelled force on the tool: without the integral a stiffness-sized offset
  // remains, with it the offset vanishes while the integral stays inside its clamp
  Rig rig("panda_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  const int body = rig.m().site_bodyid[rig.chain.frame().id];
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  auto offset = [&](const Vector6d& ki) {
    mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
    rig.d().xfrc_applied[6 * body + 2] = -10.0;  // 10 N downwards on the last link
    OperationalSpaceOptions o;
    o.integral_gain = ki;
    o.integral_limit = Vector6d::Constant(0.05);
    OperationalSpaceController osc(rig.chain, o);
    return run_closed_loop(rig, osc, ref, 4.0);
  };
  const double plain = offset(Vector6d::Zero());
  const double integral = offset(Vector6d::Constant(2000.0));
  EXPECT_GT(plain, 5e-3);  // about 10 N / 400 N/m... shaped by Λ: millimetres
  EXPECT_LT(integral, 1e-4);
}

TEST(OperationalSpace, AntiWindupClampsTheIntegral) {
  Rig rig("panda_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  ref.task.X_WE.p.z() += 5.0;  // unreachable: the error never closes
  OperationalSpaceOptions o;
  o.integral_gain = Vector6d::Constant(1.0);
  o.integral_limit << 0.01, 0.02, 0.03, 0.04, 0.05, 0.06;
  OperationalSpaceController osc(rig.chain, o);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  for (int k = 0; k < 200; ++k) {
    rig.d().time = 0.01 * k;
    osc.compute(rig.d(), ref, command);
  }
  EXPECT_DOUBLE_EQ(osc.integral()[2], 0.03);
  EXPECT_DOUBLE_EQ(osc.internal_values()[6], 0.03);  // integral_z
  osc.reset();
  EXPECT_EQ(osc.integral().norm(), 0.0);
  osc.compute(rig.d(), ref, command);  // first call after reset: Δt = 0
  EXPECT_EQ(osc.integral().norm(), 0.0);
}

TEST(OperationalSpace, InternalsAreNamedAndSized) {
  Rig rig("panda_torque", "attachment_site");
  // a regular configuration (at qpos0 the panda's wrist is singular: λ_min is 0)
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  OperationalSpaceController osc(rig.chain);
  ASSERT_EQ(osc.internal_names().size(), osc.internal_values().size());
  EXPECT_EQ(osc.internal_names()[2], "lambda_condition");
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  osc.compute(rig.d(), ref, command);
  EXPECT_GT(osc.internal_values()[2], 1.0);
  EXPECT_TRUE(std::isfinite(osc.internal_values()[2]));
  // lambda_condition is filled on reading, from the eigenvalues of J·M⁻¹·Jᵀ of the last compute
  const Eigen::VectorXd& eig = osc.task_space().eigenvalues();
  EXPECT_NEAR(osc.internal_values()[2], eig[eig.size() - 1] / eig[0],
              1e-9 * osc.internal_values()[2]);
  EXPECT_EQ(osc.name(), "osc");
  EXPECT_EQ(osc.command_kind(), CommandKind::torque);
}

TEST(OperationalSpace, ComputeAllocatesNothing) {
  Rig rig("panda_torque", "attachment_site");
  std::mt19937_64 rng(8);
  test::random_state(rig, rng);
  OscCase c = random_case(rig, rng, TaskMode::pose, false);
  for (bool task_inertia : {false, true}) {
    for (TaskMode mode : {TaskMode::pose, TaskMode::position}) {
      c.options.task_inertia = task_inertia;
      c.options.mode = mode;
      OperationalSpaceController osc(rig.chain, c.options);
      JointCommand command{CommandKind::torque, VectorX::Zero(7)};
      osc.compute(rig.d(), c.ref, command);  // warm-up
      const std::uint64_t before = test::malloc_calls();
      double condition = 0.0;
      for (int k = 0; k < 100; ++k) {
        rig.d().time += 1e-3;
        osc.compute(rig.d(), c.ref, command);
        condition += osc.internal_values()[2];  // the on-demand condition allocates nothing too
      }
      EXPECT_EQ(test::malloc_calls() - before, 0u);
      EXPECT_TRUE(std::isfinite(condition));
    }
  }
}

TEST(OperationalSpace, PositionModeOnPlanarArmConverges) {
  // 3 task rows, 2 joints: Λ is floored along the arm's normal, the reachable point is reached
  Rig rig("planar2_torque", "tip");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  // a reachable target: the tip at another configuration
  mjData* other = mj_makeData(&rig.m());
  other->qpos[0] = 0.2;
  other->qpos[1] = -1.4;
  mj_forward(&rig.m(), other);
  Reference ref;
  ref.task.X_WE = test::site_pose(*other, rig.chain.frame().id);
  mj_deleteData(other);
  OperationalSpaceOptions o;
  o.mode = TaskMode::position;
  OperationalSpaceController osc(rig.chain, o);
  EXPECT_LT(run_closed_loop(rig, osc, ref, 2.0), 1e-3);
}

TEST(OperationalSpace, BadOptionsThrow) {
  Rig rig("panda_torque", "attachment_site");
  auto expect_throw = [&](auto edit, const char* what) {
    OperationalSpaceOptions o;
    edit(o);
    try {
      OperationalSpaceController osc(rig.chain, o);
      ADD_FAILURE() << "no exception for " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_throw([](auto& o) { o.stiffness[0] = -1.0; }, "stiffness");
  expect_throw([](auto& o) { o.stiffness[4] = NAN; }, "stiffness");
  expect_throw([](auto& o) { o.damping[1] = INFINITY; }, "damping");
  expect_throw([](auto& o) { o.damping_ratio = 0.0; }, "damping_ratio");
  expect_throw([](auto& o) { o.inertia[3] = 0.0; }, "inertia");
  expect_throw([](auto& o) { o.integral_gain[2] = -3.0; }, "integral_gain");
  expect_throw([](auto& o) { o.integral_limit[0] = -1.0; }, "integral_limit");
  expect_throw([](auto& o) { o.nullspace_damping = -1.0; }, "nullspace_damping");
  expect_throw([](auto& o) { o.nullspace_stiffness = NAN; }, "nullspace_stiffness");
  expect_throw([](auto& o) { o.task_space.min_eigenvalue = 0.0; }, "min_eigenvalue");
  expect_throw([](auto& o) { o.integral_hold_force = 0.0; }, "integral_hold_force");
  expect_throw([](auto& o) { o.integral_hold_force = NAN; }, "integral_hold_force");
  // in position mode the rotational entries are not used, so they are not checked
  OperationalSpaceOptions o;
  o.mode = TaskMode::position;
  o.inertia[5] = 0.0;
  EXPECT_NO_THROW(OperationalSpaceController(rig.chain, o));
}

TEST(OperationalSpace, WrongCommandSizeIsLeftUntouched) {
  Rig rig("panda_torque", "attachment_site");
  OperationalSpaceController osc(rig.chain);
  Reference ref;
  JointCommand command{CommandKind::torque, VectorX::Constant(3, 7.0)};
  osc.compute(rig.d(), ref, command);
  EXPECT_EQ(command.value, VectorX::Constant(3, 7.0));
}

}  // namespace
}  // namespace mjarm
