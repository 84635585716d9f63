#include "mjarm/control/task_pd.hpp"

#include <gtest/gtest.h>

#include <random>

#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using test::MatrixX;
using test::Rig;
using test::VectorX;

/// g(q) from MuJoCo: qfrc_bias of the same positions with zero velocity.
VectorX gravity_torques(const mjModel& m, const mjData& d) {
  mjData* s = mj_makeData(&m);
  mju_copy(s->qpos, d.qpos, m.nq);
  mju_zero(s->qvel, m.nv);
  mj_forward(&m, s);
  VectorX g = Eigen::Map<const VectorX>(s->qfrc_bias, m.nv);
  mj_deleteData(s);
  return g;
}

TEST(TaskPd, MatchesIndependentFormula) {
  Rig rig("panda_torque", "attachment_site");
  const int site = rig.chain.frame().id;
  std::mt19937_64 rng(21);
  int checked = 0;
  while (checked < 40) {
    if (!test::random_state(rig, rng)) continue;
    TaskPdOptions o;
    o.mode = checked % 2 ? TaskMode::position : TaskMode::pose;
    o.stiffness = test::random6(rng, 500.0).cwiseAbs();
    o.damping = test::random6(rng, 50.0).cwiseAbs();
    o.joint_damping = checked % 3 ? 0.0 : 1.5;
    o.gravity_compensation = checked % 5 != 0;
    const int rows = task_rows(o.mode);
    Reference ref;
    ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), site), rng, 0.2, 1.0);
    ref.task.V_WE = test::random6(rng, 0.5);
    TaskPdController pd(rig.chain, o);
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    pd.compute(rig.d(), ref, command);

    const MatrixX J = test::site_jacobian(rig.m(), rig.d(), site).topRows(rows);
    const VectorX qd = Eigen::Map<const VectorX>(rig.d().qvel, 7);
    const Vector6d e = test::reference_error(test::site_pose(rig.d(), site), ref.task.X_WE);
    const VectorX e_dot = ref.task.V_WE.head(rows) - J * qd;
    VectorX expected = J.transpose() * (o.stiffness.head(rows).asDiagonal() * e.head(rows) +
                                        o.damping.head(rows).asDiagonal() * e_dot);
    if (o.gravity_compensation) expected += gravity_torques(rig.m(), rig.d());
    expected -= o.joint_damping * qd;
    EXPECT_LE((command.value - expected).norm(), 1e-8 * expected.norm())
        << command.value.transpose() << "\n" << expected.transpose();
    EXPECT_NEAR(pd.internal_values()[0], e.head<3>().norm(), 1e-12);
    ++checked;
  }
}

TEST(TaskPd, ConvergesOnPandaInSimulation) {
  Rig rig("panda_torque", "attachment_site");
  mj_resetDataKeyframe(&rig.m(), &rig.d(), rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &rig.d());
  const int site = rig.chain.frame().id;
  const Pose home = test::site_pose(rig.d(), site);
  Reference ref;
  ref.task.X_WE.p = home.p + Eigen::Vector3d(0.1, 0.1, -0.12);
  ref.task.X_WE.R = Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix() * home.R;
  TaskPdOptions o;
  o.joint_damping = 1.0;  // the self-motion has only the joints' own damping otherwise
  TaskPdController pd(rig.chain, o);
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  for (int k = 0; k < 2500; ++k) {
    mj_step1(&rig.m(), &rig.d());
    pd.compute(rig.d(), ref, command);
    test::apply_torque(rig.chain, command.value, rig.d());
    mj_step2(&rig.m(), &rig.d());
  }
  mj_forward(&rig.m(), &rig.d());
  const Vector6d e = test::reference_error(test::site_pose(rig.d(), site), ref.task.X_WE);
  EXPECT_LT(e.head<3>().norm(), 1e-3);
  EXPECT_LT(e.tail<3>().norm(), 1e-2);
}

TEST(TaskPd, ComputeAllocatesNothing) {
  Rig rig("panda_torque", "attachment_site");
  std::mt19937_64 rng(22);
  test::random_state(rig, rng);
  Reference ref;
  ref.task.X_WE = test::nearby_pose(test::site_pose(rig.d(), rig.chain.frame().id), rng, 0.1, 0.3);
  for (TaskMode mode : {TaskMode::pose, TaskMode::position}) {
    TaskPdOptions o;
    o.mode = mode;
    o.joint_damping = 1.0;
    TaskPdController pd(rig.chain, o);
    JointCommand command{CommandKind::torque, VectorX::Zero(7)};
    pd.compute(rig.d(), ref, command);
    const std::uint64_t before = test::malloc_calls();
    for (int k = 0; k < 100; ++k) pd.compute(rig.d(), ref, command);
    EXPECT_EQ(test::malloc_calls() - before, 0u);
  }
}

TEST(TaskPd, BadGainsThrow) {
  Rig rig("panda_torque", "attachment_site");
  TaskPdOptions o;
  o.stiffness[1] = -5.0;
  EXPECT_THROW(TaskPdController(rig.chain, o), Error);
  o = {};
  o.damping[5] = NAN;
  EXPECT_THROW(TaskPdController(rig.chain, o), Error);
  o.mode = TaskMode::position;  // rotational gains unused, unchecked
  EXPECT_NO_THROW(TaskPdController(rig.chain, o));
  o = {};
  o.joint_damping = -1.0;
  try {
    TaskPdController pd(rig.chain, o);
    ADD_FAILURE() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("joint_damping"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjarm
