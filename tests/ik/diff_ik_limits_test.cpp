// The box-tightening and barrier constraints of DiffIk: configuration limits with a margin and
// the manipulability barrier, alone and composed with collision rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/collision_avoidance.hpp"
#include "mjarm/ik/configuration_limit.hpp"
#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/ik/manipulability_barrier.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "support/random_configurations.hpp"

namespace mjarm {
namespace {

Chain limits_panda_chain() { return Chain(Robot::bundled("panda"), "attachment_site"); }

TEST(ConfigurationLimit, JointsKeepTheMarginAndTheBoxQpStays) {
  // a posture target beyond every joint's limits: each joint ends at its limit minus the margin
  const Chain chain = limits_panda_chain();
  DiffIk ik(chain);
  const double margin = 0.1;
  const Eigen::VectorXd beyond = chain.upper().array() + 1.0;
  ik.add_posture_task(beyond, 1.0, 1.0);
  ik.add_constraint(
      std::make_unique<ConfigurationLimit>(chain, ConfigurationLimitOptions{margin, 0.5}));
  Eigen::VectorXd q = chain.center();
  double worst = 1e9;
  for (int s = 0; s < 200; ++s) {
    const DiffIkStep& step = ik.step(q);
    EXPECT_EQ(step.constraint_rows, 0);
    q = step.q_next;
    worst = std::min(worst, (chain.upper().array() - margin - q.array()).minCoeff());
  }
  EXPECT_GT(worst, -1e-12);  // never inside the margin
  EXPECT_LT((chain.upper().array() - margin - q.array()).abs().maxCoeff(), 1e-6);  // on it
  // without it the joints reach the limits themselves
  DiffIk bare(chain);
  bare.add_posture_task(beyond, 1.0, 1.0);
  Eigen::VectorXd q_bare = chain.center();
  for (int s = 0; s < 200; ++s) q_bare = bare.step(q_bare).q_next;
  EXPECT_LT((chain.upper() - q_bare).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ConfigurationLimit, StartingInsideTheMarginPushesOut) {
  const Chain chain = limits_panda_chain();
  DiffIk ik(chain);
  ik.add_posture_task(chain.upper(), 1.0, 1.0);
  ik.add_constraint(
      std::make_unique<ConfigurationLimit>(chain, ConfigurationLimitOptions{0.1, 0.5}));
  Eigen::VectorXd q = chain.upper().array() - 0.02;  // 8 cm inside the margin
  for (int s = 0; s < 50; ++s) q = ik.step(q).q_next;
  EXPECT_LT((chain.upper().array() - 0.1 - q.array()).abs().maxCoeff(), 1e-6);
}

TEST(ConfigurationLimit, AMarginWiderThanARangeIsNamed) {
  const Chain chain = limits_panda_chain();
  try {
    const ConfigurationLimit limit(chain, ConfigurationLimitOptions{2.0, 0.5});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("joint"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ConfigurationLimit(chain, ConfigurationLimitOptions{-0.1, 0.5}), Error);
}

double position_manipulability(const Chain& chain, const Eigen::VectorXd& q) {
  return manipulability(chain, q, ManipulabilityOptions{.block = JacobianBlock::position})
      .manipulability;
}

TEST(ManipulabilityBarrier, RowMatchesFiniteDifferences) {
  const Chain chain = limits_panda_chain();
  ManipulabilityBarrier barrier(chain, ManipulabilityBarrierOptions{});
  Eigen::MatrixXd C(1, 7);
  Eigen::VectorXd b(1);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = test::random_q(chain, rng, 0.01);
    ASSERT_EQ(barrier.rows(q, 1.0, C, b), 1);
    const double w = position_manipulability(chain, q);
    EXPECT_NEAR(-b[0], 0.5 * (w - 1e-3), 1e-14);  // gain 0.5, dt 1
    for (int i = 0; i < 7; ++i) {
      const double h = 1e-6;
      Eigen::VectorXd qp = q, qm = q;
      qp[i] += h;
      qm[i] -= h;
      const double fd =
          (position_manipulability(chain, qp) - position_manipulability(chain, qm)) / (2 * h);
      EXPECT_NEAR(C(0, i), fd, 1e-6 * (1.0 + std::abs(fd)));
    }
  }
}

// drives the panda's flange to an unreachable target (the arm stretches towards a singularity)
// and returns the smallest position manipulability along the way
double stretch_min_manipulability(double w_min) {
  const Chain chain = limits_panda_chain();
  DiffIkOptions options;
  options.velocity_limit = Eigen::VectorXd::Constant(7, 2.0);
  DiffIk ik(chain, options);
  const int task = ik.add_position_task({}, 1.0, 0.3);
  ik.add_posture_task(chain.center(), 1e-4);
  if (w_min > 0.0) {
    ManipulabilityBarrierOptions barrier;
    barrier.min_manipulability = w_min;
    ik.add_constraint(std::make_unique<ManipulabilityBarrier>(chain, barrier));
  }
  ChainKinematics kin(chain);
  Eigen::VectorXd q = chain.center();
  ik.set_target(task, Eigen::Vector3d(1.5, 0.3, 0.5));
  double lowest = 1e9;
  for (int s = 0; s < 400; ++s) {
    q = ik.step(q).q_next;
    lowest = std::min(lowest, position_manipulability(chain, q));
  }
  return lowest;
}

TEST(ManipulabilityBarrier, KeepsTheArmAwayFromTheStretchedSingularity) {
  const double w_start =
      position_manipulability(limits_panda_chain(), limits_panda_chain().center());
  const double free_lowest = stretch_min_manipulability(0.0);
  const double w_min = 0.5 * (w_start + free_lowest);
  ASSERT_LT(free_lowest, 0.6 * w_min);  // unguarded, it goes well below (the test can fail)
  const double guarded_lowest = stretch_min_manipulability(w_min);
  EXPECT_GT(guarded_lowest, w_min * (1.0 - 1e-3));
}

TEST(DiffIkConstraints, ComposeAndStepAllocatesNothing) {
  const Chain chain = limits_panda_chain();
  DiffIkOptions options;
  options.velocity_limit = Eigen::VectorXd::Constant(7, 1.0);
  DiffIk ik(chain, options);
  const int task = ik.add_pose_task({}, 1.0, 0.5, 0.5);
  ik.add_constraint(
      std::make_unique<ConfigurationLimit>(chain, ConfigurationLimitOptions{0.05, 0.5}));
  ik.add_constraint(std::make_unique<ManipulabilityBarrier>(chain, ManipulabilityBarrierOptions{}));
  EXPECT_EQ(ik.constraint_count(), 2);
  EXPECT_EQ(ik.constraint_matrix().rows(), 1);
  EXPECT_THROW(ik.constraint(2), Error);
  EXPECT_THROW(ik.add_constraint(nullptr), Error);
  ChainKinematics kin(chain);
  Pose X = kin.update(chain.center());
  X.p += Eigen::Vector3d(0.1, 0.05, -0.05);
  ik.set_target(task, X);
  Eigen::VectorXd q = chain.center();
  q = ik.step(q).q_next;
  const std::uint64_t before = test::malloc_calls();
  for (int s = 0; s < 200; ++s) q = ik.step(q).q_next;
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_EQ(ik.last_step().qp_status, qp::QpStatus::solved);
  EXPECT_LT((kin.update(q).p - X.p).norm(), 1e-4);
}

TEST(DiffIkConstraints, ABoxOnlyConstraintKeepsTheBoxQpResultsBitForBit) {
  // a configuration limit with margin 0 and gain 1 is the hard box again: same bits
  const Chain chain = limits_panda_chain();
  DiffIk plain(chain), limited(chain);
  const Eigen::VectorXd beyond = chain.upper().array() + 1.0;
  plain.add_posture_task(beyond, 1.0, 1.0);
  limited.add_posture_task(beyond, 1.0, 1.0);
  limited.add_constraint(
      std::make_unique<ConfigurationLimit>(chain, ConfigurationLimitOptions{0.0, 1.0}));
  Eigen::VectorXd q1 = chain.center(), q2 = chain.center();
  for (int s = 0; s < 20; ++s) {
    q1 = plain.step(q1).q_next;
    q2 = limited.step(q2).q_next;
    ASSERT_EQ(q1, q2) << "step " << s;
  }
}

}  // namespace
}  // namespace mjarm
