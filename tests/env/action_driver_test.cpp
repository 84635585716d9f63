// ActionDriver through an Environment: every action space moves the arm as it says, within
// its bounds; the end-effector spaces keep the joint limits (the QP's box) when pushed past them.

#include "mjarm/env/action_driver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "env/env_test_support.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/tasks/approach_timing.hpp"

namespace mjarm {
namespace {

using test::reach_task;

EnvironmentOptions in_space(ActionSpace space) {
  EnvironmentOptions o;
  o.action_space = space;
  o.time_limit = 100.0;
  o.observations = {"joint_positions", "joint_velocities", "ee_pose", "ee_twist"};
  return o;
}

Eigen::Vector3d ee_position(const TimeStep& ts) {
  const std::span<const double> p = ts.observation["ee_pose"];
  return {p[0], p[1], p[2]};
}

TEST(ActionDriver, SpecsFollowTheSpace) {
  const std::unique_ptr<EnvTask> task = reach_task();
  const Chain& chain = task->chain();
  const ActionOptions o;
  const ActionDriver torques(ActionSpace::joint_torques, chain, o, 0.02);
  EXPECT_EQ(torques.spec().name, "action");
  ASSERT_EQ(torques.spec().size(), 7);
  EXPECT_EQ(torques.spec().maximum[0], 87.0);  // the panda's published limits
  EXPECT_EQ(torques.spec().minimum[6], -12.0);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(torques.spec().maximum[i], joint_torque_limit(chain, i));
  const ActionDriver positions(ActionSpace::joint_positions, chain, o, 0.02);
  EXPECT_EQ(positions.spec().minimum, chain.lower());
  EXPECT_EQ(positions.spec().maximum, chain.upper());
  const ActionDriver deltas(ActionSpace::joint_deltas, chain, o, 0.02);
  EXPECT_EQ(deltas.spec().maximum, Eigen::VectorXd::Constant(7, o.max_joint_delta));
  const ActionDriver pose(ActionSpace::ee_pose_deltas, chain, o, 0.02);
  ASSERT_EQ(pose.spec().size(), 6);
  EXPECT_EQ(pose.spec().maximum[2], o.max_translation);
  EXPECT_EQ(pose.spec().maximum[3], o.max_rotation);
  const ActionDriver velocity(ActionSpace::ee_velocities, chain, o, 0.02);
  EXPECT_EQ(velocity.spec().maximum[0], o.max_linear_speed);
  EXPECT_EQ(velocity.spec().maximum[5], o.max_angular_speed);
  EXPECT_NE(pose.ik_step(), nullptr);
  EXPECT_EQ(torques.ik_step(), nullptr);
}

TEST(ActionDriver, BadOptionsAreErrors) {
  const std::unique_ptr<EnvTask> task = reach_task();
  ActionOptions o;
  o.max_translation = 0.0;
  test::expect_error_containing(
      [&] { ActionDriver d(ActionSpace::ee_pose_deltas, task->chain(), o, 0.02); },
      {"max_translation", "positive"});
  o = ActionOptions{};
  o.osc.mode = TaskMode::position;
  test::expect_error_containing(
      [&] { ActionDriver d(ActionSpace::ee_pose_deltas, task->chain(), o, 0.02); }, {"osc.mode"});
  test::expect_error_containing(
      [&] { ActionDriver d(ActionSpace::joint_torques, task->chain(), ActionOptions{}, -1.0); },
      {"control period"});
  test::expect_error_containing([] { action_space("ee_pose_delta"); },
                                {"unknown action space 'ee_pose_delta'", "ee_pose_deltas"});
  EXPECT_EQ(action_space("joint_deltas"), ActionSpace::joint_deltas);
}

TEST(ActionDriver, TorquesAreWhatTheMotorsGet) {
  Environment env(reach_task(), in_space(ActionSpace::joint_torques));
  env.reset(2);
  const std::vector<double> tau{5.0, -3.0, 2.0, -1.0, 0.5, 0.25, -0.125};
  env.step(tau);
  const mjData& d = env.simulation().data();
  for (int i = 0; i < 7; ++i) EXPECT_EQ(d.ctrl[i], tau[static_cast<std::size_t>(i)]);  // gear 1
}

TEST(ActionDriver, JointPositionTargetsAreReached) {
  Environment env(reach_task(), in_space(ActionSpace::joint_positions));
  TimeStep ts = env.reset(2);
  std::vector<double> target(ts.observation["joint_positions"].begin(),
                             ts.observation["joint_positions"].end());
  target[0] += 0.3;
  target[3] -= 0.2;
  target[6] += 0.4;
  for (int k = 0; k < 100; ++k) ts = env.step(target);  // 2 s
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(ts.observation["joint_positions"][i], target[static_cast<std::size_t>(i)], 2e-3)
        << i;
  for (double v : ts.observation["joint_velocities"]) EXPECT_LT(std::abs(v), 1e-2);
}

TEST(ActionDriver, JointDeltasAccumulateAndStopAtTheLimits) {
  Environment env(reach_task(), in_space(ActionSpace::joint_deltas));
  TimeStep ts = env.reset(2);
  const double q0 = ts.observation["joint_positions"][0];
  std::vector<double> delta(7, 0.0);
  delta[0] = 0.02;
  for (int k = 0; k < 10; ++k) ts = env.step(delta);  // +0.2 rad requested over 0.2 s
  for (int k = 0; k < 50; ++k) ts = env.step(std::vector<double>(7, 0.0));
  EXPECT_NEAR(ts.observation["joint_positions"][0], q0 + 0.2, 2e-3);
  // joint 4 (upper limit −0.0698) pushed up for ever: the target stops at the limit
  delta.assign(7, 0.0);
  delta[3] = 0.05;
  for (int k = 0; k < 150; ++k) ts = env.step(delta);
  const double upper = env.task().chain().upper()[3];
  EXPECT_LE(ts.observation["joint_positions"][3], upper + 5e-3);
  EXPECT_GT(ts.observation["joint_positions"][3], upper - 0.05);
}

TEST(ActionDriver, EndEffectorDeltasMoveTheToolByThatMuch) {
  Environment env(reach_task(), in_space(ActionSpace::ee_pose_deltas));
  TimeStep ts = env.reset(3);
  const Eigen::Vector3d p0 = ee_position(ts);
  const std::vector<double> step{0.0, 0.01, -0.005, 0.0, 0.0, 0.0};
  for (int k = 0; k < 10; ++k) ts = env.step(step);  // 0.1 m in y, −0.05 m in z requested
  for (int k = 0; k < 40; ++k) ts = env.step(std::vector<double>(6, 0.0));
  const Eigen::Vector3d moved = ee_position(ts) - p0;
  EXPECT_NEAR(moved.y(), 0.1, 3e-3);
  EXPECT_NEAR(moved.z(), -0.05, 3e-3);
  EXPECT_NEAR(moved.x(), 0.0, 3e-3);
}

TEST(ActionDriver, EndEffectorVelocitiesIntegrateOverTheStep) {
  Environment env(reach_task(), in_space(ActionSpace::ee_velocities));
  TimeStep ts = env.reset(3);
  const Eigen::Vector3d p0 = ee_position(ts);
  const std::vector<double> v{0.2, 0.0, 0.0, 0.0, 0.0, 0.0};
  for (int k = 0; k < 25; ++k) ts = env.step(v);          // 0.5 s at 0.2 m/s
  EXPECT_NEAR(ts.observation["ee_twist"][0], 0.2, 0.02);  // moving at the commanded speed
  for (int k = 0; k < 40; ++k) ts = env.step(std::vector<double>(6, 0.0));
  EXPECT_NEAR((ee_position(ts) - p0).x(), 0.1, 3e-3);
}

TEST(ActionDriver, EndEffectorActionsKeepTheJointLimits) {
  // pushing the tool down into the floor and turning it for ever: the QP's steps (the reference
  // configuration) stay inside the limits exactly, even when the arm itself has been pushed past
  // one (the QP starts from the measured q clamped into the limits). The arm follows its
  // reference through the operational-space controller, which knows no joint limit, against
  // MuJoCo's soft limits: measured at most 0.057 rad past one (joint 6, into the floor).
  for (ActionSpace space : {ActionSpace::ee_pose_deltas, ActionSpace::ee_velocities}) {
    Environment env(reach_task(), in_space(space));
    env.reset(5);
    const Chain& chain = env.task().chain();
    std::vector<double> push(6, 0.0);
    push[2] = -env.action_spec().maximum[2];
    push[0] = env.action_spec().maximum[0];
    push[5] = env.action_spec().maximum[5];
    double past = 0.0;  // how far the arm went past a limit [rad]
    for (int k = 0; k < 150; ++k) {
      const TimeStep ts = env.step(push);
      const Eigen::VectorXd& q_next = env.action_driver().reference().joint.q;
      const std::span<const double> q = ts.observation["joint_positions"];
      for (int i = 0; i < chain.size(); ++i) {
        EXPECT_GE(q_next[i], chain.lower()[i] - 1e-9) << to_string(space) << " joint " << i;
        EXPECT_LE(q_next[i], chain.upper()[i] + 1e-9) << to_string(space) << " joint " << i;
        past = std::max({past, q[i] - chain.upper()[i], chain.lower()[i] - q[i]});
      }
    }
    EXPECT_LT(past, 0.08) << to_string(space);
  }
}

}  // namespace
}  // namespace mjarm
