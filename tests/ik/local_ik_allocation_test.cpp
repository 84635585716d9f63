// The local IK solvers allocate nothing during a solve once constructed and warmed up. Counts
// come from the room's malloc counter (ik/malloc_counter.hpp): Eigen allocates with malloc and
// libstdc++'s operator new goes through malloc, so both kinds of heap allocation are seen.

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "ik/local_ik_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/ik/collision_guard.hpp"
#include "mjarm/ik/multi_target_ik.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"
#include "support/random_configurations.hpp"

namespace mjarm {
namespace {

/// Heap allocations made by @p f.
template <class F>
std::uint64_t allocations_during(F&& f) {
  const std::uint64_t before = test::malloc_calls();
  f();
  return test::malloc_calls() - before;
}

TEST(LocalIkAllocation, CounterSeesOperatorNew) {
  const std::uint64_t n = allocations_during([] {
    auto p = std::make_unique<double[]>(100);
    p[0] = 1.0;
    EXPECT_EQ(p[0], 1.0);
  });
  EXPECT_GE(n, 1u);
}

TEST(LocalIkAllocation, PositionIkSolvesWithoutAllocating) {
  const Robot robot = Robot::bundled("arm6");
  const Chain chain(robot, "grip");
  PositionIkOptions options;
  options.posture.gain = 0.1;
  PositionIk ik(chain, options);
  ChainKinematics fk(chain);
  std::mt19937 rng(1);
  IkResult result;
  ik.solve(fk.update(test::random_q(chain, rng)).p, chain.center(), result);  // warm-up
  for (int t = 0; t < 5; ++t) {
    const Eigen::Vector3d p_WT = fk.update(test::random_q(chain, rng)).p;
    const Eigen::VectorXd seed = chain.center();
    EXPECT_EQ(allocations_during([&] { ik.solve(p_WT, seed, result); }), 0u);
    EXPECT_GT(result.iterations, 0);
  }
}

TEST(LocalIkAllocation, PoseIkSolvesWithoutAllocating) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  PoseIkOptions options;
  options.limits = {0.05, 0.2, 0.15};
  options.posture.gain = 0.1;
  PoseIk ik(chain, options);
  ChainKinematics fk(chain);
  std::mt19937 rng(2);
  IkResult result;
  ik.solve(fk.update(test::random_q(chain, rng)), chain.center(), result);
  for (int t = 0; t < 5; ++t) {
    const Pose X_WT = fk.update(test::random_q(chain, rng));
    const Eigen::VectorXd seed = chain.center();
    EXPECT_EQ(allocations_during([&] { ik.solve(X_WT, seed, result); }), 0u);
    EXPECT_GT(result.iterations, 0);
  }
}

TEST(LocalIkAllocation, MultiTargetIkSolvesWithoutAllocating) {
  const Robot robot = Robot::bundled("dual_arm");
  const auto joints = test::dual_arm_joints();
  for (const MultiTargetMode mode : {MultiTargetMode::stacked, MultiTargetMode::prioritized}) {
    MultiTargetIkOptions options;
    options.mode = mode;
    options.limits = {0.05, 0.2, 0.15};
    options.posture.gain = 0.1;
    const std::vector<FrameTarget> targets{
        {"right_hand", TargetKind::pose, Pose{}, 1.0, 1.0, 0},
        {"left_hand", TargetKind::position, Pose{}, 1.0, 1.0, 1}};
    MultiTargetIk ik(robot, joints, targets, options);
    ChainKinematics right{Chain(robot, joints, "right_hand")},
        left{Chain(robot, joints, "left_hand")};
    std::mt19937 rng(3);
    IkResult result;
    for (int t = 0; t < 4; ++t) {
      const Eigen::VectorXd q = test::random_q(ik.chain(), rng, 0.1);
      const Eigen::VectorXd seed = test::perturb(ik.chain(), q, rng, 0.2);
      const std::uint64_t n = allocations_during([&] {
        ik.set_target(0, right.update(q));
        ik.set_target(1, left.update(q));
        ik.solve(seed, result);
      });
      if (t > 0) {
        EXPECT_EQ(n, 0u);  // t = 0 is the warm-up
      }
      EXPECT_GT(result.iterations, 0);
    }
  }
}

TEST(LocalIkAllocation, CollisionChecksDoNotAllocate) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const Chain chain(robot, "right_tip");
  CollisionSpec spec{{{"r_link2", "post"}}, {"r_link3"}, 0.01, 4};
  CollisionGuard guard(chain, spec);
  const Eigen::VectorXd q = (Eigen::VectorXd(4) << 0.0, -0.855, 0.0, 0.0).finished();
  guard.in_contact(q);
  EXPECT_EQ(allocations_during([&] { EXPECT_TRUE(guard.in_contact(q)); }), 0u);

  // and a guarded solve whose steps get rolled back
  PositionIkOptions options;
  options.collision = spec;
  PositionIk ik(chain, options);
  ChainKinematics fk(chain);
  const Eigen::Vector3d p_WT = fk.update((Eigen::VectorXd(4) << 0.0, -1.4, 0.0, 0.0).finished()).p;
  const Eigen::VectorXd seed = Eigen::VectorXd::Zero(4);
  IkResult result;
  ik.solve(p_WT, seed, result);
  EXPECT_EQ(allocations_during([&] { ik.solve(p_WT, seed, result); }), 0u);
  EXPECT_EQ(result.status, IkStatus::not_converged);
}

}  // namespace
}  // namespace mjarm
