#include "mjarm/ik/diff_ik.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/pose_error.hpp"
#include "mjarm/lie/so3.hpp"
#include "support/random_configurations.hpp"
#include "support/reference_linear_algebra.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

Chain panda_chain() { return Chain(Robot::bundled("panda"), "attachment_site"); }

TEST(DiffIk, UnconstrainedStepMatchesClosedFormLeastSquares) {
  // far from the limits the box is inactive: v = (Σ AᵀWA + λI)⁻¹ Σ AᵀW(α/dt)e
  const Chain chain = panda_chain();
  DiffIkOptions options;
  options.dt = 0.01;
  options.damping = 1e-3;
  DiffIk ik(chain, options);
  const int pose = ik.add_pose_task({}, 2.0, 0.5, 0.3);
  const Eigen::VectorXd q_ref = chain.center();
  const int posture = ik.add_posture_task(q_ref, 0.01, 0.5);
  ChainKinematics kin(chain);
  const Eigen::VectorXd q = chain.center() + Eigen::VectorXd::Constant(7, 0.05);
  Pose X_WT = kin.update(q);
  X_WT.p += Eigen::Vector3d(0.002, -0.001, 0.003);
  X_WT.R = X_WT.R * so3::exp(Eigen::Vector3d(0.002, 0.001, -0.003));
  ik.set_target(pose, X_WT);
  const DiffIkStep& step = ik.step(q);
  ASSERT_EQ(step.qp_status, qp::QpStatus::solved);

  kin.update(q);
  Matrix6Xd J(6, 7);
  kin.jacobian(J, JacobianFrame::local);
  const Vector6d e = log_error(kin.pose(), X_WT);
  const Matrix6Xd A = log_error_jacobian(e) * J;
  Vector6d w;
  w << 2, 2, 2, 0.5, 0.5, 0.5;
  Eigen::MatrixXd H = A.transpose() * w.asDiagonal() * A;
  H.diagonal().array() += 0.01 + 1e-3;
  const Eigen::VectorXd b =
      A.transpose() * w.asDiagonal() * (0.3 / 0.01 * e) + 0.01 * (0.5 / 0.01) * (q_ref - q);
  const Eigen::VectorXd v = test::solve_ldlt(H, b);
  EXPECT_LT((step.v - v).norm(), 1e-9 * (1.0 + v.norm()));
  EXPECT_LT((step.q_next - (q + 0.01 * v)).norm(), 1e-10);
  EXPECT_LT((ik.task_error(pose) - e).norm(), 1e-15);
  EXPECT_LT((ik.task_error(posture) - (q_ref - q)).norm(), 1e-15);
  EXPECT_FALSE(step.pulled_back);
}

TEST(DiffIk, ConstrainedStepIsOptimalOverTheBox) {
  // a position task pulling hard against tight velocity limits: the step must beat every
  // random feasible velocity on the QP's own cost
  const Chain chain = panda_chain();
  DiffIkOptions options;
  options.dt = 0.02;
  options.damping = 1e-4;
  options.velocity_limit = Eigen::VectorXd::Constant(7, 0.5);
  DiffIk ik(chain, options);
  const int task = ik.add_position_task({}, 1.0, 1.0);
  std::mt19937_64 rng(7);
  ChainKinematics kin(chain);
  Matrix6Xd J(6, 7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = test::random_q(chain, rng);
    const Eigen::Vector3d p_WT = kin.update(q).p + Eigen::Vector3d(0.3, -0.2, 0.1);
    ik.set_target(task, p_WT);
    const DiffIkStep& step = ik.step(q);
    kin.update(q);
    kin.jacobian(J);
    const Eigen::Vector3d b = (p_WT - kin.pose().p) / options.dt;
    const auto cost = [&](const Eigen::VectorXd& v) {
      return (J.topRows<3>() * v - b).squaredNorm() + options.damping * v.squaredNorm();
    };
    Eigen::VectorXd lo(7), hi(7);
    for (int i = 0; i < 7; ++i) {
      lo[i] = std::max((chain.lower()[i] - q[i]) / options.dt, -0.5);
      hi[i] = std::min((chain.upper()[i] - q[i]) / options.dt, 0.5);
    }
    ASSERT_TRUE((step.v.array() >= lo.array()).all() && (step.v.array() <= hi.array()).all());
    const double best = cost(step.v);
    int active = 0;
    for (int i = 0; i < 7; ++i) active += step.v[i] == lo[i] || step.v[i] == hi[i];
    EXPECT_GT(active, 0) << "the limits should bind for this target";
    for (int k = 0; k < 200; ++k) {
      // random points of the box and small moves from the optimum
      Eigen::VectorXd v(7);
      for (int i = 0; i < 7; ++i) v[i] = lo[i] + u(rng) * (hi[i] - lo[i]);
      if (k % 2 == 1) v = (step.v + 0.01 * (v - step.v)).eval();
      EXPECT_GE(cost(v), best - 1e-9 * (1.0 + best));
    }
  }
}

TEST(DiffIk, LimitsNeverViolatedOverLongRandomRuns) {
  // 20 000 steps chasing random moving targets, a third of them far outside the workspace,
  // starting with every joint on a limit: q stays in [lower, upper] exactly and |v| ≤ v_max
  const Chain chain = panda_chain();
  DiffIkOptions options;
  options.dt = 0.005;
  options.velocity_limit = Eigen::VectorXd::Constant(7, 2.0);
  options.velocity_limit[6] = 2.6;
  options.max_step = 0.008;
  DiffIk ik(chain, options);
  const int pose = ik.add_pose_task({}, 1.0, 0.5, 0.8);
  ik.add_posture_task(chain.center(), 1e-4);
  ChainKinematics kin(chain);
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q(7);
  for (int i = 0; i < 7; ++i) q[i] = i % 2 == 0 ? chain.lower()[i] : chain.upper()[i];
  Pose target;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  int outside_workspace = 0;
  for (int k = 0; k < 20000; ++k) {
    if (k % 250 == 0) {
      target = kin.update(test::random_q(chain, rng));
      if ((k / 250) % 3 == 0) {
        target.p *= 3.0;  // unreachable
        ++outside_workspace;
      }
      velocity = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.5;
    }
    target.p += velocity * options.dt;  // the target keeps moving
    ik.set_target(pose, target);
    const DiffIkStep& step = ik.step(q);
    for (int i = 0; i < 7; ++i) {
      ASSERT_GE(step.q_next[i], chain.lower()[i]) << "step " << k << " joint " << i;
      ASSERT_LE(step.q_next[i], chain.upper()[i]) << "step " << k << " joint " << i;
      ASSERT_LE(std::abs(step.v[i]), options.velocity_limit[i]) << "step " << k;
      ASSERT_LE(std::abs(step.v[i]) * options.dt, options.max_step * (1 + 1e-12));
      ASSERT_LE(std::abs(step.q_next[i] - q[i]), options.max_step * (1 + 1e-12) + 1e-15);
    }
    ASSERT_FALSE(step.pulled_back);
    ASSERT_EQ(step.qp_status, qp::QpStatus::solved);
    q = step.q_next;
  }
  EXPECT_GT(outside_workspace, 20);
}

TEST(DiffIk, ConvergesToReachableTargets) {
  const Chain chain = panda_chain();
  DiffIkOptions options;
  options.dt = 0.01;
  options.damping = 1e-6;
  DiffIk ik(chain, options);
  const int pose = ik.add_pose_task({}, 1.0, 1.0, 0.5);
  ChainKinematics kin(chain);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    // a target a moderate distance away from the start, reachable without crossing limits
    const Eigen::VectorXd q0 = chain.center();
    Eigen::VectorXd q_star = q0;
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    for (int i = 0; i < 7; ++i) q_star[i] += u(rng);
    q_star = chain.clamp(q_star);
    const Pose X_WT = kin.update(q_star);
    ik.set_target(pose, X_WT);
    Eigen::VectorXd q = q0;
    for (int k = 0; k < 200; ++k) q = ik.step(q).q_next;
    const Vector6d e = log_error(kin.update(q), X_WT);
    EXPECT_LT(e.head<3>().norm(), 1e-8) << "trial " << trial;
    EXPECT_LT(e.tail<3>().norm(), 1e-8) << "trial " << trial;
  }
}

TEST(DiffIk, PositionAndPostureTasksOnOtherFrames) {
  // position of an intermediate body (link4) plus the posture: both errors shrink
  const Chain chain = panda_chain();
  DiffIk ik(chain);
  const int elbow = ik.add_position_task("link4", 1.0, 0.5);
  const Eigen::VectorXd q_ref = chain.center();
  const int posture = ik.add_posture_task(q_ref, 1e-10, 0.5);  // light: no visible bias
  EXPECT_EQ(ik.task_kind(elbow), DiffIkTaskKind::position);
  EXPECT_EQ(ik.task_kind(posture), DiffIkTaskKind::posture);
  Chain link4(chain.robot(), chain.joint_names(), "link4");
  ChainKinematics kin(link4);
  Eigen::VectorXd q_goal = chain.center();
  q_goal.head<3>() += Eigen::Vector3d(0.3, 0.2, -0.2);
  const Eigen::Vector3d p_goal = kin.update(q_goal).p;
  ik.set_target(elbow, p_goal);
  Eigen::VectorXd q = chain.center();
  for (int k = 0; k < 100; ++k) q = ik.step(q).q_next;
  EXPECT_LT((kin.update(q).p - p_goal).norm(), 1e-6);
  EXPECT_LT((ik.task_error(elbow) - (p_goal - kin.update(q).p)).norm(), 1e-3);
  // joints 4..7 do not move link4: the posture keeps them at the reference
  EXPECT_LT((q.tail<4>() - q_ref.tail<4>()).norm(), 1e-6);
}

TEST(DiffIk, PullsBackInsideWhenStartingOutsideLimits) {
  const Chain chain = panda_chain();
  Eigen::VectorXd q = chain.center();
  q[1] = chain.upper()[1] + 0.295;
  q[3] = chain.lower()[3] - 0.205;
  // without velocity limits one step brings every joint back exactly inside
  {
    DiffIk ik(chain);
    ik.add_posture_task(q, 1.0);  // even with a task asking to stay outside
    const DiffIkStep& step = ik.step(q);
    EXPECT_TRUE(chain.within_limits(step.q_next));
    EXPECT_FALSE(step.pulled_back);
    EXPECT_DOUBLE_EQ(step.q_next[1], chain.upper()[1]);
    EXPECT_DOUBLE_EQ(step.q_next[3], chain.lower()[3]);
  }
  // with v_max = 1 rad/s and dt = 0.01 a joint heads back at exactly 0.01 rad per step until
  // one step can finish the way: 29 pulled-back steps for 0.295 rad, then inside
  DiffIkOptions options;
  options.dt = 0.01;
  options.velocity_limit = Eigen::VectorXd::Ones(7);
  DiffIk ik(chain, options);
  ik.add_posture_task(q, 1.0);
  int steps = 0;
  while (!chain.within_limits(q) && steps < 100) {
    const double gap1 = q[1] - chain.upper()[1];
    const DiffIkStep& step = ik.step(q);
    EXPECT_EQ(step.pulled_back, steps < 29) << "step " << steps;
    if (gap1 > 0.01 + 1e-9) {
      EXPECT_EQ(step.v[1], -1.0);
    }
    if (chain.lower()[3] - q[3] > 0.01 + 1e-9) {
      EXPECT_EQ(step.v[3], 1.0);
    }
    EXPECT_LT(step.q_next[1], q[1]);  // always closer
    q = step.q_next;
    ++steps;
  }
  EXPECT_EQ(steps, 30);
  for (int k = 0; k < 100; ++k) {
    const DiffIkStep& step = ik.step(q);
    EXPECT_FALSE(step.pulled_back);
    q = step.q_next;
    ASSERT_TRUE(chain.within_limits(q));
  }
}

TEST(DiffIk, StepAllocatesNothing) {
  const Chain chain = panda_chain();
  DiffIkOptions options;
  options.velocity_limit = Eigen::VectorXd::Constant(7, 1.5);
  options.max_step = 0.01;
  DiffIk ik(chain, options);
  const int pose = ik.add_pose_task();
  const int elbow = ik.add_position_task("link4", 0.1);
  ik.add_posture_task(chain.center(), 1e-3);
  ChainKinematics kin(chain);
  std::mt19937_64 rng(11);
  const Pose X_WT = kin.update(test::random_q(chain, rng));
  const Eigen::Vector3d p_elbow(0.1, 0.1, 0.5);
  Eigen::VectorXd q = chain.center();
  ik.set_target(pose, X_WT);
  ik.set_target(elbow, p_elbow);
  q = ik.step(q).q_next;  // warm-up
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 1000; ++k) {
    ik.set_target(pose, X_WT);
    q = ik.step(q).q_next;
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  // the counter does see allocations (the object and its coefficients). Not zeros: with the
  // counter in another file, malloc is the compiler's builtin here, and malloc + memset(0) becomes
  // calloc, which the counter does not see.
  const std::uint64_t probe = test::malloc_calls();
  auto heap = std::make_unique<Eigen::VectorXd>(Eigen::VectorXd::Constant(100, 0.5));
  EXPECT_GE(test::malloc_calls() - probe, 2u);
  (*heap)[0] = 1.0;
  EXPECT_EQ((*heap)[0], 1.0);
}

TEST(DiffIk, WorksOnTheTrickyArm) {
  // slide joint, non-zero joint reference, rotated site: the pose still converges
  const Robot robot = Robot::from_string(test::kTrickyArm);
  const Chain chain(robot, "tool");
  DiffIk ik(chain);
  const int pose = ik.add_pose_task({}, 1.0, 1.0, 0.5);
  ChainKinematics kin(chain);
  Eigen::VectorXd q_star = chain.center();
  q_star << 0.3, 0.2, 0.05, -0.4, 0.6;
  const Pose X_WT = kin.update(q_star);
  ik.set_target(pose, X_WT);
  Eigen::VectorXd q = chain.center();
  for (int k = 0; k < 300; ++k) q = ik.step(q).q_next;
  const Vector6d e = log_error(kin.update(q), X_WT);
  EXPECT_LT(e.norm(), 1e-7);
  EXPECT_TRUE(chain.within_limits(q));
}

TEST(DiffIk, BadInputsThrow) {
  const Chain chain = panda_chain();
  DiffIkOptions bad;
  bad.dt = 0.0;
  EXPECT_THROW(DiffIk(chain, bad), Error);
  bad = DiffIkOptions{};
  bad.velocity_limit = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(DiffIk(chain, bad), Error);
  bad.velocity_limit = -Eigen::VectorXd::Ones(7);
  EXPECT_THROW(DiffIk(chain, bad), Error);
  bad = DiffIkOptions{};
  bad.max_step = 0.0;
  EXPECT_THROW(DiffIk(chain, bad), Error);

  DiffIk ik(chain);
  EXPECT_THROW(ik.add_pose_task("no_such_frame"), Error);
  EXPECT_THROW(ik.add_pose_task({}, -1.0), Error);
  EXPECT_THROW(ik.add_position_task({}, 1.0, 1.5), Error);
  EXPECT_THROW(ik.add_posture_task(Eigen::VectorXd::Zero(3)), Error);
  const int pose = ik.add_pose_task();
  const int posture = ik.add_posture_task(chain.center());
  Pose nan_pose;
  nan_pose.p.x() = std::nan("");
  EXPECT_THROW(ik.set_target(pose, nan_pose), Error);
  Pose skew;
  skew.R(0, 1) = 0.5;
  EXPECT_THROW(ik.set_target(pose, skew), Error);
  EXPECT_THROW(ik.set_target(posture, Pose{}), Error);
  EXPECT_THROW(ik.set_target(7, Pose{}), Error);
  EXPECT_THROW(ik.set_posture(pose, chain.center()), Error);
  EXPECT_THROW(ik.set_weight(pose, std::nan("")), Error);
  EXPECT_THROW(ik.task_error(-1), Error);
  Eigen::VectorXd q = chain.center();
  q[2] = std::nan("");
  EXPECT_THROW(ik.step(q), Error);
  EXPECT_THROW(ik.step(Eigen::VectorXd::Zero(6)), Error);
}

}  // namespace
}  // namespace mjarm
