#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/tasks/shelf_pick/task.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {
namespace {

/// A goal between two configurations of @p chain (the target pose is FK at q_target).
ShelfPickGoal goal_between(const Chain& chain, const Eigen::VectorXd& q_start,
                           const Eigen::VectorXd& q_target, double T, bool position_only) {
  ChainKinematics kin(chain);
  ShelfPickGoal goal;
  goal.X_WS = kin.update(q_start);
  goal.X_WT = kin.update(q_target);
  goal.q_start = q_start;
  goal.q_target = q_target;
  goal.approach_time = T;
  goal.position_only = position_only;
  return goal;
}

struct Fixture {
  Robot robot;
  Chain chain;
  DataPtr data;
  explicit Fixture(const char* model, const char* frame)
      : robot(Robot::bundled(model)), chain(robot, frame), data(robot.make_data()) {}
  /// Puts the chain at @p q at time @p t, kinematics fresh.
  void place(const Eigen::VectorXd& q, double t) {
    chain.scatter(q, data->qpos);
    mj_forward(&robot.model(), data.get());
    data->time = t;
  }
};

Eigen::VectorXd panda_q(double a) {
  Eigen::VectorXd q(7);
  q << 0.1 + a, -0.6, 0.05, -2.2 + a, 0.1, 1.7, 0.7 - a;
  return q;
}

TEST(ShelfPickTask, ReferencesFollowTheMinimumJerkPathOfTheLibraryProfiles) {
  Fixture f("panda_torque", "attachment_site");
  const double T = 0.3;
  const ShelfPickGoal goal = goal_between(f.chain, panda_q(0.0), panda_q(0.25), T, false);
  ShelfPickTask task(f.chain, goal);
  Reference ref;
  f.place(goal.q_start, 0.0);

  const auto at = [&](double t) {
    f.data->time = t;
    task.update(*f.data, ref);
    return ref;
  };
  const Reference r0 = at(0.0);
  EXPECT_TRUE(r0.task.X_WE.is_approx(goal.X_WS, 1e-15));
  EXPECT_EQ(r0.task.V_WE.norm(), 0.0);
  EXPECT_TRUE(r0.joint.q.isApprox(goal.q_start));

  // finite differences of position, rotation and joints give the velocities
  const auto pose_at = [&](const Eigen::VectorXd& t) { return at(t[0]).task.X_WE; };
  for (double t : {0.05, 0.11, 0.15, 0.23, 0.29}) {
    // [ṗ; ω] of the reference pose (world-aligned), then the rates of the other signals
    const Matrix6Xd V = finite_difference_pose_jacobian(pose_at, Eigen::VectorXd::Constant(1, t));
    const Eigen::Vector3d v = V.col(0).head<3>();
    const Eigen::Vector3d w = V.col(0).tail<3>();
    const Reference c = at(t);
    EXPECT_LT((v - c.task.V_WE.head<3>()).norm(), 1e-6) << t;
    EXPECT_LT((w - c.task.V_WE.tail<3>()).norm(), 1e-6) << t;
    const Vector6d dv = finite_difference_derivative([&](double s) { return at(s).task.V_WE; }, t);
    EXPECT_LT((dv - c.task.A_WE).norm(), 1e-4) << t;
    const Eigen::VectorXd dq =
        finite_difference_derivative([&](double s) { return at(s).joint.q; }, t);
    const Eigen::VectorXd dqd =
        finite_difference_derivative([&](double s) { return at(s).joint.qd; }, t);
    EXPECT_LT((dq - c.joint.qd).norm(), 1e-6) << t;
    EXPECT_LT((dqd - c.joint.qdd).norm(), 1e-4) << t;
    // the path is straight: the position lies on the segment start → target
    const Eigen::Vector3d along = goal.X_WT.p - goal.X_WS.p;
    const Eigen::Vector3d off = c.task.X_WE.p - goal.X_WS.p;
    EXPECT_LT((off - off.dot(along) / along.squaredNorm() * along).norm(), 1e-12);
    // rest to rest the library's quintic and SE(3) interpolation are the minimum-jerk scaling
    // s = smootherstep(t/T): p = p_S + s·(p_T − p_S), R = exp(s·ω)·R_S, q = q_S + s·(q_T − q_S)
    const RampSample s = smootherstep(t / T);
    const Eigen::Vector3d omega = so3::log(goal.X_WT.R * goal.X_WS.R.transpose());
    EXPECT_LT((c.task.X_WE.p - (goal.X_WS.p + s.s * along)).norm(), 1e-14) << t;
    EXPECT_LT((c.task.X_WE.R - so3::exp(s.s * omega) * goal.X_WS.R).norm(), 1e-14) << t;
    EXPECT_LT((c.task.V_WE.tail<3>() - s.ds / T * omega).norm(), 1e-12) << t;
    EXPECT_LT((c.joint.q - (goal.q_start + s.s * (goal.q_target - goal.q_start))).norm(), 1e-14)
        << t;
  }
  const Reference end = at(T + 0.01);
  EXPECT_TRUE(end.task.X_WE.is_approx(goal.X_WT, 1e-12));
  EXPECT_EQ(end.task.V_WE.norm(), 0.0);
  EXPECT_EQ(end.task.A_WE.norm(), 0.0);
  EXPECT_TRUE(end.joint.q.isApprox(goal.q_target, 1e-15));
}

TEST(ShelfPickTask, VelocityReferencesLagByTheGivenTime) {
  Fixture f("panda_torque", "attachment_site");
  ShelfPickGoal goal = goal_between(f.chain, panda_q(0.0), panda_q(0.2), 0.25, false);
  ShelfPickTask plain(f.chain, goal);
  goal.velocity_lag = 0.001;
  ShelfPickTask lagged(f.chain, goal);
  Reference a, b, c;
  f.place(goal.q_start, 0.0);
  plain.update(*f.data, a);
  lagged.update(*f.data, b);
  f.data->time = 0.101;
  lagged.update(*f.data, b);
  f.data->time = 0.100;
  plain.update(*f.data, c);
  EXPECT_LT((b.task.V_WE - c.task.V_WE).norm(), 1e-15);
  EXPECT_LT((b.joint.qd - c.joint.qd).norm(), 1e-15);
  EXPECT_GT((b.task.X_WE.p - c.task.X_WE.p).norm(), 1e-5);  // positions are not shifted
}

TEST(ShelfPickTask, PhasesFollowTheTip) {
  // kinematic playback of the joint reference: the tip is exactly on the path
  Fixture f("planar2_torque", "tip");
  Eigen::VectorXd q0(2), q1(2);
  q0 << 0.5, -1.0;
  q1 << 0.9, -1.4;
  const double T = 0.25, dt = 0.002;
  ShelfPickTask task(f.chain, goal_between(f.chain, q0, q1, T, true));
  Reference ref;
  int k = 0;
  bool running = true;
  bool saw_hold_gripper = false;
  f.place(q0, 0.0);
  while (running && k < 1000) {
    running = task.update(*f.data, ref);
    if (task.phase() == PickPhase::hold) saw_hold_gripper = ref.gripper == 1.0;
    if (k * dt < T - 0.05) {
      EXPECT_EQ(task.phase(), PickPhase::approach) << k;
    }
    ++k;
    f.place(ref.joint.q, k * dt);
  }
  EXPECT_FALSE(running);
  EXPECT_EQ(task.phase(), PickPhase::release);
  EXPECT_TRUE(saw_hold_gripper);
  EXPECT_EQ(ref.gripper, 0.0);
  const PickMetrics& m = task.metrics();
  ASSERT_TRUE(m.held);
  EXPECT_LT(m.time_to_tolerance, T);  // on the path, the tip enters before the path ends
  EXPECT_NEAR(m.hold_end_time, m.time_to_tolerance + 0.2, 1e-9);
  EXPECT_LT(m.overshoot, 1e-12);  // the minimum-jerk path never passes its end
  EXPECT_LT(m.steady_state_max, 1e-12);
  EXPECT_EQ(m.exits, 0);
}

TEST(ShelfPickTask, WaitsInSettleWhenTheTipLags) {
  Fixture f("planar2_torque", "tip");
  Eigen::VectorXd q0(2), q1(2);
  q0 << 0.5, -1.0;
  q1 << 0.9, -1.4;
  ShelfPickTask task(f.chain, goal_between(f.chain, q0, q1, 0.1, true));
  Reference ref;
  f.place(q0, 0.0);  // the tip never moves
  for (int k = 0; k <= 100; ++k) {
    f.data->time = 0.002 * k;
    EXPECT_TRUE(task.update(*f.data, ref));
  }
  EXPECT_EQ(task.phase(), PickPhase::settle);
  EXPECT_FALSE(task.metrics().held);
  EXPECT_NEAR(task.metrics().final_error, task.distance(), 1e-12);
}

TEST(ShelfPickTask, UpdateAllocatesNothing) {
  Fixture f("panda_torque", "attachment_site");
  ShelfPickTask task(f.chain, goal_between(f.chain, panda_q(0.0), panda_q(0.2), 0.2, false));
  Reference ref;
  f.place(panda_q(0.0), 0.0);
  task.update(*f.data, ref);  // the first tick sizes the reference
  const std::uint64_t before = test::malloc_calls();
  for (int k = 1; k < 300; ++k) {
    f.data->time = 0.002 * k;
    task.update(*f.data, ref);
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

/// Keeps the times it saw (storage reserved up front: seeing a tick allocates nothing).
struct TimeLog final : TickObserver {
  std::vector<double> times;
  void on_tick(const mjData& data) noexcept override { times.push_back(data.time); }
};

TEST(ShelfPickTask, ObserverSeesEveryTickWithoutAllocating) {
  Fixture f("panda_torque", "attachment_site");
  ShelfPickTask task(f.chain, goal_between(f.chain, panda_q(0.0), panda_q(0.2), 0.2, false));
  TimeLog log;
  log.times.reserve(400);
  task.set_observer(&log);
  Reference ref;
  f.place(panda_q(0.0), 0.0);
  task.update(*f.data, ref);  // the first tick sizes the reference
  const std::uint64_t before = test::malloc_calls();
  for (int k = 1; k < 300; ++k) {
    f.data->time = 0.002 * k;
    task.update(*f.data, ref);
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  ASSERT_EQ(log.times.size(), 300u);
  for (std::size_t k = 0; k < log.times.size(); ++k)
    EXPECT_EQ(log.times[k], 0.002 * static_cast<double>(k));
  task.set_observer(nullptr);
  task.update(*f.data, ref);
  EXPECT_EQ(log.times.size(), 300u);
}

TEST(ShelfPickTask, RejectsBadGoals) {
  Fixture f("planar2_torque", "tip");
  Eigen::VectorXd q0(2), q1(2);
  q0 << 0.5, -1.0;
  q1 << 0.9, -1.4;
  const ShelfPickGoal good = goal_between(f.chain, q0, q1, 0.2, true);
  ShelfPickGoal bad = good;
  bad.q_target = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(ShelfPickTask(f.chain, bad), Error);
  bad = good;
  bad.approach_time = 0.0;
  EXPECT_THROW(ShelfPickTask(f.chain, bad), Error);
  bad = good;
  bad.X_WT.p.x() = std::nan("");
  EXPECT_THROW(ShelfPickTask(f.chain, bad), Error);
  bad = good;
  bad.velocity_lag = -0.001;
  EXPECT_THROW(ShelfPickTask(f.chain, bad), Error);
  bad = good;
  bad.criteria.tolerance = 0.0;
  EXPECT_THROW(ShelfPickTask(f.chain, bad), Error);
}

}  // namespace
}  // namespace mjarm
