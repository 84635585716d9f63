// The per-iteration observer of the local IK solvers (iteration_callback.hpp): one call per
// iterate, seed included, with the errors the solve ends on, and no heap allocation whether it
// is set or not.

#include "mjarm/ik/iteration_callback.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "ik/local_ik_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/ik/multi_target_ik.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"
#include "support/random_configurations.hpp"

namespace mjarm {
namespace {

/// What a callback saw during one solve (fixed capacity: recording allocates nothing).
struct IterationLog {
  static constexpr int kCapacity = 1024;
  int calls = 0;
  int expected_next = 0;  // the iteration index the next call must carry
  bool in_order = true;
  bool q_finite = true;
  double first_position = 0.0;
  IkIteration last;
  double positions[kCapacity] = {};

  void clear() { *this = IterationLog{}; }
  IkIterationCallback callback() {
    return [this](const IkIteration& it) {
      in_order = in_order && it.iteration == expected_next;
      expected_next = it.iteration + 1;
      q_finite = q_finite && it.q != nullptr && it.q->allFinite();
      if (calls == 0) first_position = it.position_error;
      if (calls < kCapacity) positions[calls] = it.position_error;
      ++calls;
      last = it;
    };
  }
};

/// Heap allocations made by @p f (named apart from the other files of this room: unity build).
template <class F>
std::uint64_t heap_calls_during(F&& f) {
  const std::uint64_t before = test::malloc_calls();
  f();
  return test::malloc_calls() - before;
}

TEST(IkIterationCallback, PositionIkReportsEveryIterate) {
  const Robot robot = Robot::bundled("arm6");
  const Chain chain(robot, "grip");
  IterationLog log;
  PositionIkOptions options;
  options.on_iteration = log.callback();
  PositionIk ik(chain, options);
  ChainKinematics fk(chain);
  std::mt19937 rng(3);
  IkResult result;
  for (int t = 0; t < 5; ++t) {
    const Eigen::Vector3d p_WT = fk.update(test::random_q(chain, rng)).p;
    const Eigen::VectorXd seed = chain.center();
    log.clear();
    ik.solve(p_WT, seed, result);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(log.calls, result.iterations + 1);
    EXPECT_TRUE(log.in_order);
    EXPECT_TRUE(log.q_finite);
    EXPECT_NEAR(log.first_position, (p_WT - fk.update(seed).p).norm(), 1e-12);
    EXPECT_EQ(log.last.iteration, result.iterations);
    EXPECT_NEAR(log.last.position_error, result.position_error, 1e-15);
    EXPECT_EQ(log.last.orientation_error, 0.0);
    EXPECT_GT(log.first_position, 100.0 * log.last.position_error);
  }
}

TEST(IkIterationCallback, PoseIkReportsBothErrors) {
  const Chain chain = test::chain_of("panda");
  IterationLog log;
  PoseIkOptions options;
  options.on_iteration = log.callback();
  PoseIk ik(chain, options);
  ChainKinematics fk(chain);
  std::mt19937 rng(4);
  for (int t = 0; t < 5; ++t) {
    const Eigen::VectorXd q_true = test::random_q(chain, rng, 0.1);
    const Pose X_WT = fk.update(q_true);
    log.clear();
    const IkResult r = ik.solve(X_WT, test::perturb(chain, q_true, rng, 0.3));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(log.calls, r.iterations + 1);
    EXPECT_TRUE(log.in_order);
    EXPECT_NEAR(log.last.position_error, r.position_error, 1e-15);
    EXPECT_NEAR(log.last.orientation_error, r.orientation_error, 1e-15);
    EXPECT_LE(log.last.orientation_error, options.orientation_tolerance);
  }
}

TEST(IkIterationCallback, MultiTargetIkReportsTheWorstTarget) {
  const Robot robot = Robot::from_string(test::kTwoBranch);
  const auto joints = test::two_branch_joints();
  IterationLog log;
  MultiTargetIkOptions options;
  options.on_iteration = log.callback();
  std::vector<FrameTarget> targets{{"right_tip", TargetKind::position, Pose{}, 1.0, 1.0, 0},
                                   {"left_tip", TargetKind::position, Pose{}, 1.0, 1.0, 0}};
  MultiTargetIk ik(robot, joints, targets, options);
  const Chain& chain = ik.chain();
  ChainKinematics right{Chain(robot, joints, "right_tip")}, left{Chain(robot, joints, "left_tip")};
  std::mt19937 rng(5);
  int solved = 0;
  for (int t = 0; t < 5; ++t) {
    const Eigen::VectorXd q_true = test::random_q(chain, rng, 0.05);
    ik.set_target(0, right.update(q_true));
    ik.set_target(1, left.update(q_true));
    log.clear();
    const IkResult r = ik.solve(test::perturb(chain, q_true, rng, 0.2));
    EXPECT_EQ(log.calls, r.iterations + 1);
    EXPECT_TRUE(log.in_order);
    if (!r.ok()) continue;
    ++solved;
    EXPECT_EQ(log.last.position_error,
              std::max(ik.target_errors(0).position, ik.target_errors(1).position));
  }
  EXPECT_GE(solved, 4);
}

TEST(IkIterationCallback, SetOrUnsetTheSolveAllocatesNothing) {
  const Robot robot = Robot::bundled("arm6");
  const Chain chain(robot, "grip");
  IterationLog log;
  PositionIkOptions with;
  with.on_iteration = log.callback();
  PositionIk observed(chain, with);
  PositionIk plain(chain);
  PoseIkOptions pose_with;
  pose_with.on_iteration = log.callback();
  PoseIk pose_observed(chain, pose_with);
  ChainKinematics fk(chain);
  std::mt19937 rng(6);
  IkResult result;
  const Eigen::VectorXd seed = chain.center();
  observed.solve(fk.update(test::random_q(chain, rng)).p, seed, result);  // sizes result.q
  for (int t = 0; t < 3; ++t) {
    const Pose X_WT = fk.update(test::random_q(chain, rng));
    log.clear();
    EXPECT_EQ(heap_calls_during([&] { observed.solve(X_WT.p, seed, result); }), 0u);
    EXPECT_GT(log.calls, 1);
    EXPECT_EQ(heap_calls_during([&] { plain.solve(X_WT.p, seed, result); }), 0u);
    log.clear();
    EXPECT_EQ(heap_calls_during([&] { pose_observed.solve(X_WT, seed, result); }), 0u);
    EXPECT_GT(log.calls, 1);
  }
}

}  // namespace
}  // namespace mjarm
