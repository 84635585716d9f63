#include "mjarm/ik/multi_target_ik.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <random>

#include "ik/local_ik_support.hpp"
#include "mjarm/error.hpp"
#include "support/random_configurations.hpp"

namespace mjarm {
namespace {

/// Right hand: full pose, priority 0; left hand: position, priority 1.
std::vector<FrameTarget> hands(const std::string& right, const std::string& left) {
  FrameTarget r{right, TargetKind::pose, Pose{}, 1.0, 1.0, 0};
  FrameTarget l{left, TargetKind::position, Pose{}, 1.0, 1.0, 1};
  return {r, l};
}

/// Poses of both hands at q (shared joint order).
std::pair<Pose, Pose> hand_poses(const Robot& robot, const std::vector<std::string>& joints,
                                 const std::string& right, const std::string& left,
                                 const Eigen::VectorXd& q) {
  ChainKinematics kr{Chain(robot, joints, right)}, kl{Chain(robot, joints, left)};
  return {kr.update(q), kl.update(q)};
}

class MultiTargetIkModes : public ::testing::TestWithParam<MultiTargetMode> {};

TEST_P(MultiTargetIkModes, TwoBranchRoundTrip) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const auto joints = test::two_branch_joints();
  MultiTargetIkOptions options;
  options.mode = GetParam();
  MultiTargetIk ik(robot, joints, hands("right_tip", "left_tip"), options);
  const Chain& chain = ik.chain();
  std::mt19937 rng(17);
  int converged = 0;
  for (int t = 0; t < 50; ++t) {
    const Eigen::VectorXd q_true = test::random_q(chain, rng, 0.05);
    const auto [X_R, X_L] = hand_poses(robot, joints, "right_tip", "left_tip", q_true);
    ik.set_target(0, X_R);
    ik.set_target(1, X_L);
    const IkResult r = ik.solve(test::perturb(chain, q_true, rng, 0.2));
    EXPECT_TRUE(chain.within_limits(r.q));
    const auto [Y_R, Y_L] = hand_poses(robot, joints, "right_tip", "left_tip", r.q);
    EXPECT_NEAR(ik.target_errors(0).position, (Y_R.p - X_R.p).norm(), 1e-12);
    EXPECT_NEAR(ik.target_errors(1).position, (Y_L.p - X_L.p).norm(), 1e-12);
    if (r.ok()) {
      ++converged;
      EXPECT_LE((Y_R.p - X_R.p).norm(), options.position_tolerance);
      EXPECT_LE(frame_errors(Y_R, X_R).orientation, options.orientation_tolerance);
      EXPECT_LE((Y_L.p - X_L.p).norm(), options.position_tolerance);
    }
  }
  EXPECT_GE(converged, 49);
}

TEST_P(MultiTargetIkModes, DualArmRightPoseLeftPositionAndLift) {
  const Robot robot = Robot::bundled("dual_arm");
  const auto joints = test::dual_arm_joints();
  MultiTargetIkOptions options;
  options.mode = GetParam();
  MultiTargetIk ik(robot, joints, hands("right_hand", "left_hand"), options);
  const Chain& chain = ik.chain();
  ASSERT_EQ(chain.size(), 15);
  std::mt19937 rng(23);
  const int trials = 50;
  int converged = 0;
  bool lift_moved = false;
  for (int t = 0; t < trials; ++t) {
    const Eigen::VectorXd q_true = test::random_q(chain, rng, 0.05);
    const auto [X_R, X_L] = hand_poses(robot, joints, "right_hand", "left_hand", q_true);
    ik.set_target(0, X_R);
    ik.set_target(1, X_L);
    const Eigen::VectorXd seed = test::perturb(chain, q_true, rng, 0.2);
    const IkResult r = ik.solve(seed);
    EXPECT_TRUE(chain.within_limits(r.q));
    if (r.ok()) {
      ++converged;
      const auto [Y_R, Y_L] = hand_poses(robot, joints, "right_hand", "left_hand", r.q);
      EXPECT_LE((Y_R.p - X_R.p).norm(), options.position_tolerance);
      EXPECT_LE(frame_errors(Y_R, X_R).orientation, options.orientation_tolerance);
      EXPECT_LE((Y_L.p - X_L.p).norm(), options.position_tolerance);
      lift_moved = lift_moved || std::abs(r.q[0] - seed[0]) > 1e-3;
    }
  }
  std::cout << "[ multi-target ] dual_arm "
            << (GetParam() == MultiTargetMode::stacked ? "stacked" : "prioritized")
            << ": converged " << converged << "/" << trials << " from a nearby seed\n";
  EXPECT_GE(converged, 48);
  EXPECT_TRUE(lift_moved);  // the shared lift takes part
}

INSTANTIATE_TEST_SUITE_P(Modes, MultiTargetIkModes,
                         ::testing::Values(MultiTargetMode::stacked, MultiTargetMode::prioritized));

TEST(MultiTargetIk, PriorityKeepsTheHigherTaskExactWhenTasksConflict) {
  // both hands' heights are set by the shared lift alone: asking for hands 0.1 m apart in height
  // cannot be met; priorities keep the right hand exact, a stack splits the difference
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const auto joints = test::two_branch_joints();
  Eigen::VectorXd q(7);
  q << 0.0, 0.3, -0.4, 0.2, -0.3, 0.5, -0.2;
  auto [X_R, X_L] = hand_poses(robot, joints, "right_tip", "left_tip", q);
  X_L.p.z() += 0.1;
  const Eigen::VectorXd seed =
      (Eigen::VectorXd(7) << 0.05, 0.2, -0.3, 0.1, -0.2, 0.4, -0.1).finished();
  IkResult results[2];
  for (const MultiTargetMode mode : {MultiTargetMode::stacked, MultiTargetMode::prioritized}) {
    MultiTargetIkOptions options;
    options.mode = mode;
    MultiTargetIk ik(robot, joints, hands("right_tip", "left_tip"), options);
    ik.set_target(0, X_R);
    ik.set_target(1, X_L);
    const IkResult r = ik.solve(seed);
    EXPECT_EQ(r.status, IkStatus::not_converged);
    const FrameErrors right = ik.target_errors(0), left = ik.target_errors(1);
    if (mode == MultiTargetMode::prioritized) {
      EXPECT_LE(right.position, options.position_tolerance);
      EXPECT_LE(right.orientation, options.orientation_tolerance);
      EXPECT_NEAR(left.position, 0.1, 1e-4);  // all of the conflict lands on the left hand
    } else {
      EXPECT_GT(right.position, 0.03);  // the stack pulls the right hand off its target
      EXPECT_GT(left.position, 0.03);
    }
    results[mode == MultiTargetMode::prioritized] = r;
  }
  EXPECT_GT(std::abs(results[0].q[0] - results[1].q[0]), 0.03);  // different lift heights
}

TEST(MultiTargetIk, WeightsShiftTheStackedCompromise) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const auto joints = test::two_branch_joints();
  Eigen::VectorXd q(7);
  q << 0.0, 0.3, -0.4, 0.2, -0.3, 0.5, -0.2;
  auto [X_R, X_L] = hand_poses(robot, joints, "right_tip", "left_tip", q);
  X_L.p.z() += 0.1;
  MultiTargetIkOptions options;
  options.mode = MultiTargetMode::stacked;
  auto targets = hands("right_tip", "left_tip");
  targets[0].position_weight = 10.0;
  MultiTargetIk ik(robot, joints, targets, options);
  ik.set_target(0, X_R);
  ik.set_target(1, X_L);
  ik.solve(q);
  // weighted least squares on the lift: right share 1/(1 + 100) of the 0.1 m gap
  EXPECT_NEAR(ik.target_errors(0).position, 0.1 / 101.0, 1e-4);
  EXPECT_NEAR(ik.target_errors(1).position, 0.1 * 100.0 / 101.0, 1e-4);
}

TEST(MultiTargetIk, InvalidInputThrows) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const auto joints = test::two_branch_joints();
  EXPECT_THROW(MultiTargetIk(robot, joints, {}), Error);
  EXPECT_THROW(MultiTargetIk(robot, joints, hands("right_tip", "no_such_site")), Error);
  EXPECT_THROW(MultiTargetIk(robot, {"lift", "nope"}, hands("right_tip", "left_tip")), Error);
  // a frame none of the joints moves
  EXPECT_THROW(MultiTargetIk(robot, {"l_yaw1", "l_yaw2"}, hands("right_tip", "left_tip")), Error);
  auto targets = hands("right_tip", "left_tip");
  targets[1].priority = -1;
  EXPECT_THROW(MultiTargetIk(robot, joints, targets), Error);
  targets = hands("right_tip", "left_tip");
  targets[0].orientation_weight = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MultiTargetIk(robot, joints, targets), Error);
  MultiTargetIk ik(robot, joints, hands("right_tip", "left_tip"));
  Pose bad;
  bad.p.x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ik.set_target(0, bad), Error);
  EXPECT_THROW(ik.set_target(2, Pose{}), Error);
  EXPECT_THROW(ik.solve(Eigen::VectorXd::Zero(6)), Error);
  Eigen::VectorXd nan_seed = Eigen::VectorXd::Zero(7);
  nan_seed[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ik.solve(nan_seed), Error);
}

TEST(MultiTargetIk, DeterministicAndCallerDataUntouched) {
  const Robot robot = Robot::bundled("dual_arm");
  const auto joints = test::dual_arm_joints();
  MultiTargetIkOptions options;
  options.posture.gain = 0.1;  // towards the centre of the ranges
  options.limits = {0.05, 0.2, 0.15};
  MultiTargetIk a(robot, joints, hands("right_hand", "left_hand"), options);
  MultiTargetIk b(robot, joints, hands("right_hand", "left_hand"), options);
  std::mt19937 rng(31);
  const Eigen::VectorXd q_true = test::random_q(a.chain(), rng, 0.1);
  const auto [X_R, X_L] = hand_poses(robot, joints, "right_hand", "left_hand", q_true);
  DataPtr d = robot.make_data();
  a.chain().scatter(test::perturb(a.chain(), q_true, rng, 0.2), d->qpos);
  mj_forward(&robot.model(), d.get());
  const std::vector<unsigned char> before(static_cast<unsigned char*>(d->buffer),
                                          static_cast<unsigned char*>(d->buffer) + d->nbuffer);
  for (MultiTargetIk* ik : {&a, &b}) {
    ik->set_target(0, X_R);
    ik->set_target(1, X_L);
  }
  const IkResult r1 = a.solve(a.chain().gather(d->qpos));
  const IkResult r2 = b.solve(b.chain().gather(d->qpos));
  EXPECT_TRUE(r1.ok());
  EXPECT_EQ(std::memcmp(r1.q.data(), r2.q.data(), sizeof(double) * r1.q.size()), 0);
  EXPECT_EQ(std::memcmp(before.data(), d->buffer, before.size()), 0);
}

}  // namespace
}  // namespace mjarm
