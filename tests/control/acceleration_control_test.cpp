#include "mjarm/control/acceleration_control.hpp"

#include <gtest/gtest.h>

#include <random>

#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::MatrixX;
using test::Rig;
using test::run_closed_loop;
using test::VectorX;

/// Applies @p tau as qfrc_applied (no actuators) and returns MuJoCo's forward-dynamics qacc.
VectorX forward_acceleration(const mjModel& m, const mjData& d, const VectorX& tau) {
  mjData* s = mj_makeData(&m);
  mj_copyData(s, &m, &d);
  mju_zero(s->ctrl, m.nu);
  mju_copy(s->qfrc_applied, tau.data(), m.nv);
  mj_forward(&m, s);
  VectorX qacc = Eigen::Map<const VectorX>(s->qacc, m.nv);
  mj_deleteData(s);
  return qacc;
}

void check_task_acceleration(TaskMode mode, std::uint64_t seed) {
  Rig rig("panda_torque", "attachment_site");
  const int site = rig.chain.frame().id;
  const int rows = task_rows(mode);
  std::mt19937_64 rng(seed);
  int checked = 0;
  while (checked < 25) {
    if (!test::random_state(rig, rng)) continue;
    AccelerationControlOptions o;
    o.mode = mode;
    o.nullspace_stiffness = 20.0;
    Reference ref;
    ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), site), rng, 0.1, 0.5);
    ref.task.V_WE = test::random6(rng, 0.5);
    ref.task.A_WE = test::random6(rng, 2.0);
    ref.joint.q = rig.chain.center();
    AccelerationController accel(rig.chain, o);
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    accel.compute(rig.d(), ref, command);
    if (accel.internal_values()[3] != 0.0) continue;  // damped: exactness not promised

    // the commanded task acceleration, written plainly
    const MatrixX J = test::site_jacobian(rig.m(), rig.d(), site).topRows(rows);
    const VectorX qd = Eigen::Map<const VectorX>(rig.d().qvel, 7);
    const Vector6d e = test::reference_error(test::site_pose(rig.d(), site), ref.task.X_WE);
    const VectorX xdd = ref.task.A_WE.head(rows) +
                        o.stiffness.head(rows).asDiagonal() * e.head(rows) +
                        o.damping.head(rows).asDiagonal() * (ref.task.V_WE.head(rows) - J * qd);
    EXPECT_LE((accel.task_acceleration().head(rows) - xdd).norm(), 1e-10 * xdd.norm());

    // MuJoCo's forward dynamics under τ produce it: J·q̈ + J̇·q̇ = ẍ_d
    const VectorX qacc = forward_acceleration(rig.m(), rig.d(), command.value);
    const VectorX achieved = J * qacc + test::site_jdot_qdot(rig.m(), rig.d(), site).head(rows);
    EXPECT_LE((achieved - xdd).norm(), 1e-7 * xdd.norm())
        << "achieved " << achieved.transpose() << "\ncommanded " << xdd.transpose();
    // and the joint acceleration is the controller's own q̈
    EXPECT_LE((qacc - accel.joint_acceleration()).norm(), 1e-8 * qacc.norm());
    ++checked;
  }
}

TEST(AccelerationControl, ProducesTheCommandedTaskAccelerationPose) {
  check_task_acceleration(TaskMode::pose, 31);
}
TEST(AccelerationControl, ProducesTheCommandedTaskAccelerationPosition) {
  check_task_acceleration(TaskMode::position, 32);
}

TEST(AccelerationControl, NullSpaceDampingDoesNotDisturbTheTask) {
  // the same state with and without null-space terms: same task acceleration, different q̈
  Rig rig("panda_torque", "attachment_site");
  const int site = rig.chain.frame().id;
  std::mt19937_64 rng(33);
  while (!test::random_state(rig, rng)) {
  }
  Reference ref;
  ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), site), rng, 0.1, 0.3);
  ref.joint.q = rig.chain.center();
  AccelerationControlOptions plain;
  plain.nullspace_damping = 0.0;
  AccelerationControlOptions with_null = plain;
  with_null.nullspace_damping = 20.0;
  with_null.nullspace_stiffness = 50.0;
  AccelerationController a(rig.chain, plain), b(rig.chain, with_null);
  JointCommand ca{CommandKind::torque, VectorX::Zero(7)}, cb = ca;
  a.compute(rig.d(), ref, ca);
  b.compute(rig.d(), ref, cb);
  ASSERT_EQ(a.internal_values()[3], 0.0);
  const MatrixX J = test::site_jacobian(rig.m(), rig.d(), site);
  EXPECT_GT((a.joint_acceleration() - b.joint_acceleration()).norm(), 1e-2);
  EXPECT_LE((J * (a.joint_acceleration() - b.joint_acceleration())).norm(), 1e-9);
}

TEST(AccelerationControl, StaysBoundedAtASingularity) {
  // panda stretched straight up (joints 2, 4, 6 at their straightest): the damped inverse keeps
  // the torque finite and bounded while an undamped inverse would blow up
  Rig rig("panda_torque", "attachment_site");
  mj_resetData(&rig.m(), &rig.d());
  const double q[7] = {0.0, 0.0, 0.0, -0.0698, 0.0, 0.0, 0.0};
  for (int i = 0; i < 7; ++i) rig.d().qpos[i] = q[i];
  mj_forward(&rig.m(), &rig.d());
  Reference ref;
  ref.task.X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  ref.task.X_WE.p.x() += 0.05;
  AccelerationController accel(rig.chain);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  accel.compute(rig.d(), ref, command);
  EXPECT_LT(accel.internal_values()[2], accel.options().manipulability_threshold);
  EXPECT_GT(accel.internal_values()[3], 0.0);
  EXPECT_TRUE(command.value.allFinite());
  EXPECT_LT(command.value.cwiseAbs().maxCoeff(), 1e3);
}

TEST(AccelerationControl, ConvergesOnPandaInSimulation) {
  Rig rig("panda_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  const Pose home = test::site_pose(rig.d(), rig.chain.frame().id);
  Reference ref;
  ref.task.X_WE.p = home.p + Eigen::Vector3d(-0.1, 0.15, 0.1);
  ref.task.X_WE.R = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()).toRotationMatrix() * home.R;
  AccelerationController accel(rig.chain);
  EXPECT_LT(run_closed_loop(rig, accel, ref, 2.0), 1e-3);
  EXPECT_LT(accel.internal_values()[1], 1e-3);
}

TEST(AccelerationControl, PositionModeOnPlanarArmConverges) {
  Rig rig("planar2_torque", "tip");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  mjData* other = mj_makeData(&rig.m());
  other->qpos[0] = 0.9;
  other->qpos[1] = -0.6;
  mj_forward(&rig.m(), other);
  Reference ref;
  ref.task.X_WE = test::site_pose(*other, rig.chain.frame().id);
  mj_deleteData(other);
  AccelerationControlOptions o;
  o.mode = TaskMode::position;
  AccelerationController accel(rig.chain, o);
  EXPECT_LT(run_closed_loop(rig, accel, ref, 2.0), 1e-3);
}

TEST(AccelerationControl, ComputeAllocatesNothing) {
  Rig rig("panda_torque", "attachment_site");
  std::mt19937_64 rng(34);
  test::random_state(rig, rng);
  Reference ref;
  ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), rig.chain.frame().id), rng, 0.1, 0.3);
  ref.joint.q = rig.chain.center();
  for (TaskMode mode : {TaskMode::pose, TaskMode::position}) {
    AccelerationControlOptions o;
    o.mode = mode;
    o.nullspace_stiffness = 5.0;
    o.manipulability_threshold = 10.0;  // always damped: the refactoring path too
    AccelerationController accel(rig.chain, o);
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    accel.compute(rig.d(), ref, command);
    const std::uint64_t before = test::malloc_calls();
    for (int k = 0; k < 100; ++k) accel.compute(rig.d(), ref, command);
    EXPECT_EQ(test::malloc_calls() - before, 0u);
  }
}

TEST(AccelerationControl, BadGainsThrow) {
  Rig rig("panda_torque", "attachment_site");
  auto throws = [&](auto edit) {
    AccelerationControlOptions o;
    edit(o);
    EXPECT_THROW(AccelerationController(rig.chain, o), Error);
  };
  throws([](auto& o) { o.stiffness[0] = -1.0; });
  throws([](auto& o) { o.damping[3] = NAN; });
  throws([](auto& o) { o.manipulability_threshold = 0.0; });
  throws([](auto& o) { o.max_damping = -0.1; });
  throws([](auto& o) { o.nullspace_damping = INFINITY; });
  throws([](auto& o) { o.nullspace_stiffness = -2.0; });
}

}  // namespace
}  // namespace mjarm
