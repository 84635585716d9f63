#include "mjarm/ik/global_ik.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "ik/local_ik_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

using std::chrono::milliseconds;

/// A budget no search here gets near, so that outcomes do not depend on the machine's speed or
/// load (Debug + sanitizers run ~100× slower than Release) ...
constexpr std::chrono::seconds kRoomy{60};
/// ... and a restart cap that ends every search that finds no solution before the clock could:
/// the most attempts any solvable target here needs is 13, and the cap's 201 attempts take well
/// under the budget even in a sanitized build.
constexpr int kRestartCap = 200;

using test::chain_of;

/// Reachable targets: forward kinematics of uniform configurations.
std::vector<Pose> reachable_targets(const Chain& chain, int count, std::uint64_t seed) {
  ChainKinematics kin(chain);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Pose> targets;
  Eigen::VectorXd q(chain.size());
  for (int k = 0; k < count; ++k) {
    for (int i = 0; i < chain.size(); ++i) {
      q[i] = chain.lower()[i] + u(rng) * (chain.upper()[i] - chain.lower()[i]);
    }
    targets.push_back(kin.update(q));
  }
  return targets;
}

/// The protocol's success test, by independent forward kinematics.
bool solves(const Chain& chain, const IkResult& r, const Pose& X_WT) {
  ChainKinematics kin(chain);
  return chain.within_limits(r.q) &&
         within_tolerance(target_frame_error(kin.update(r.q), X_WT), PoseTolerance{});
}

TEST(GlobalIk, TargetFrameErrorMatchesItsDefinition) {
  Pose X_WT = Pose::from_rpy(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.4, -0.5, 1.2));
  Pose X_WE = X_WT;
  X_WE.p += Eigen::Vector3d(1e-3, -2e-3, 3e-3);
  X_WE.R = X_WT.R * so3::exp(Eigen::Vector3d(1e-4, 2e-4, -3e-4));
  const Vector6d e = target_frame_error(X_WE, X_WT);
  EXPECT_LT((e.head<3>() - X_WT.R.transpose() * Eigen::Vector3d(1e-3, -2e-3, 3e-3)).norm(), 1e-15);
  EXPECT_LT((e.tail<3>() - Eigen::Vector3d(1e-4, 2e-4, -3e-4)).norm(), 1e-15);
  EXPECT_FALSE(within_tolerance(e, PoseTolerance{}));
  EXPECT_TRUE(within_tolerance(e, PoseTolerance::uniform(4e-3)));
  Vector6d nan = e;
  nan[4] = std::nan("");
  EXPECT_FALSE(within_tolerance(nan, PoseTolerance::uniform(1.0)));
}

TEST(GlobalIk, SolvesRandomReachablePosesOnEveryArm) {
  for (const char* robot : {"panda", "iiwa14", "ur5e"}) {
    const Chain chain = chain_of(robot);
    GlobalIkOptions options;
    options.timeout = kRoomy;
    options.max_restarts = kRestartCap;
    GlobalIk ik(chain, options);
    int solved = 0;
    const std::vector<Pose> targets = reachable_targets(chain, 40, 5);
    for (const Pose& X_WT : targets) {
      const IkResult r = ik.solve(X_WT, chain.center());
      EXPECT_TRUE(chain.within_limits(r.q)) << robot;
      if (r.ok()) {
        EXPECT_TRUE(solves(chain, r, X_WT)) << robot << ": status says converged, FK disagrees";
        EXPECT_LT(r.position_error, 2e-5);
        EXPECT_LT(r.orientation_error, 2e-5);
        ++solved;
      }
    }
    EXPECT_EQ(solved, 40) << robot;
  }
}

TEST(GlobalIk, EachLocalMethodSolvesOnItsOwn) {
  const Chain chain = chain_of("panda");
  for (GlobalIkMethods methods : {GlobalIkMethods::levenberg_marquardt, GlobalIkMethods::sqp}) {
    GlobalIkOptions options;
    options.methods = methods;
    options.timeout = kRoomy;
    options.max_restarts = kRestartCap;
    GlobalIk ik(chain, options);
    int solved = 0;
    for (const Pose& X_WT : reachable_targets(chain, 30, 9)) {
      const IkResult r = ik.solve(X_WT, chain.center());
      solved += r.ok() && solves(chain, r, X_WT);
      const GlobalIkStats& s = ik.stats();
      if (r.ok()) {
        EXPECT_EQ(s.solutions, 1);
        EXPECT_EQ(methods == GlobalIkMethods::sqp ? s.sqp_solutions : s.lm_solutions, 1);
      }
    }
    EXPECT_EQ(solved, 30) << to_string(methods);
  }
}

TEST(GlobalIk, SameSeedSameBits) {
  const Chain chain = chain_of("panda");
  const std::vector<Pose> targets = reachable_targets(chain, 12, 21);
  for (GlobalIkMode mode : {GlobalIkMode::speed, GlobalIkMode::distance}) {
    GlobalIkOptions options;
    options.mode = mode;
    options.seed = 42;
    options.timeout = kRoomy;  // the restart cap ends distance mode
    options.max_restarts = 12;
    GlobalIk a(chain, options);
    GlobalIk b(chain, options);
    options.seed = 43;
    GlobalIk c(chain, options);
    int differs = 0;
    std::mt19937_64 rng(1);
    for (const Pose& X_WT : targets) {
      // random seeds so that the restarts matter
      Eigen::VectorXd seed = chain.center();
      for (int i = 0; i < 7; ++i) seed[i] += std::uniform_real_distribution<double>(-1, 1)(rng);
      const IkResult ra = a.solve(X_WT, seed);
      const IkResult rb = b.solve(X_WT, seed);
      const IkResult ra2 = a.solve(X_WT, seed);  // a second solve: nothing carries over
      ASSERT_EQ(ra.status, rb.status);
      EXPECT_EQ(ra.iterations, rb.iterations);
      EXPECT_EQ(ra.iterations, ra2.iterations);
      for (int i = 0; i < 7; ++i) {
        EXPECT_EQ(ra.q[i], rb.q[i]);  // bit for bit
        EXPECT_EQ(ra.q[i], ra2.q[i]);
      }
      differs += (c.solve(X_WT, seed).q - ra.q).norm() > 1e-6;
    }
    if (mode == GlobalIkMode::distance) {
      EXPECT_GT(differs, 0) << "another seed, other restarts";
    }
  }
}

TEST(GlobalIk, DistanceModeIsCloserToTheSeedThanSpeedMode) {
  const Chain chain = chain_of("panda");
  GlobalIkOptions options;
  options.timeout = kRoomy;
  options.max_restarts = 30;
  options.seed = 5;
  GlobalIk speed(chain, options);
  options.mode = GlobalIkMode::distance;
  GlobalIk distance(chain, options);
  options.mode = GlobalIkMode::manipulability;
  GlobalIk manip(chain, options);
  double sum_speed = 0.0, sum_distance = 0.0;
  std::mt19937_64 rng(8);
  for (const Pose& X_WT : reachable_targets(chain, 10, 33)) {
    Eigen::VectorXd seed = chain.center();
    for (int i = 0; i < 7; ++i) seed[i] += std::uniform_real_distribution<double>(-1, 1)(rng);
    const IkResult rs = speed.solve(X_WT, seed);
    const double m_speed = speed.stats().manipulability;
    const IkResult rd = distance.solve(X_WT, seed);
    const IkResult rm = manip.solve(X_WT, seed);
    ASSERT_TRUE(rs.ok() && rd.ok() && rm.ok());
    EXPECT_TRUE(solves(chain, rd, X_WT) && solves(chain, rm, X_WT));
    EXPECT_GT(distance.stats().solutions, 1);
    // the same restart sequence: distance mode saw speed mode's answer among its candidates
    const double ds = (rs.q - seed).norm(), dd = (rd.q - seed).norm();
    EXPECT_LE(dd, ds + 1e-12);
    EXPECT_GE(manip.stats().manipulability, m_speed - 1e-12);
    sum_speed += ds;
    sum_distance += dd;
  }
  EXPECT_LT(sum_distance, 0.9 * sum_speed);
}

TEST(GlobalIk, UnreachableTargetTimesOutWithTheBestError) {
  const Chain chain = chain_of("panda");
  Pose far;
  far.p = Eigen::Vector3d(2.0, 0.0, 0.5);  // the panda reaches about 0.86 m
  // a restart cap ends the search before the clock: not_converged, on a sequence of attempts
  // that does not depend on the machine's speed
  GlobalIkOptions options;
  options.max_restarts = 4;
  options.timeout = kRoomy;
  GlobalIk ik(chain, options);
  const IkResult r = ik.solve(far, chain.center());
  EXPECT_EQ(r.status, IkStatus::not_converged);
  EXPECT_EQ(ik.stats().attempts, 5);
  EXPECT_TRUE(chain.within_limits(r.q));
  // the best iterate: stretched towards the target, error = distance beyond the reach
  ChainKinematics kin(chain);
  const Pose X = kin.update(r.q);
  EXPECT_NEAR(r.position_error, (far.p - X.p).norm(), 1e-12);
  EXPECT_GT(r.position_error, 1.0);
  EXPECT_LT(r.position_error, 1.3);
  EXPECT_GT(r.iterations, 10);

  // the clock ends an unbounded search: timeout, once the budget is spent (however many attempts
  // that took on this machine), with its best iterate so far
  options.max_restarts = std::numeric_limits<int>::max();
  options.timeout = milliseconds(20);
  ik.set_options(options);
  const IkResult timed = ik.solve(far, chain.center());
  EXPECT_EQ(timed.status, IkStatus::timeout);
  EXPECT_GE(ik.stats().elapsed, 0.020);
  EXPECT_GE(ik.stats().attempts, 1);
  EXPECT_TRUE(chain.within_limits(timed.q));
  EXPECT_NEAR(timed.position_error, (far.p - kin.update(timed.q).p).norm(), 1e-12);
  EXPECT_GT(timed.position_error, 1.0);
}

TEST(GlobalIk, HugeTimeoutSaturatesInsteadOfOverflowing) {
  // 1e13 ms overflowed int64 nanoseconds in the deadline: `timeout` after 0 iterations
  const Chain chain = chain_of("panda");
  Pose far;
  far.p = Eigen::Vector3d(2.0, 0.0, 0.5);
  for (const double seconds : {1e10, 1e300, std::numeric_limits<double>::max()}) {
    GlobalIkOptions options;
    options.timeout = std::chrono::duration<double>(seconds);
    options.max_restarts = 2;  // the restart cap ends the search, not the clock
    GlobalIk ik(chain, options);
    const IkResult r = ik.solve(far, chain.center());
    EXPECT_EQ(r.status, IkStatus::not_converged) << seconds << " s";
    EXPECT_EQ(ik.stats().attempts, 3) << seconds << " s";
    EXPECT_GT(r.iterations, 10) << seconds << " s";
    const IkResult solved = ik.solve(reachable_targets(chain, 1, 8).front(), chain.center());
    EXPECT_TRUE(solved.ok()) << seconds << " s";
  }
}

TEST(GlobalIk, PositionTargetsSolveWithAnyOrientation) {
  for (const char* robot : {"panda", "ur5e", "planar2"}) {
    const Robot model = Robot::bundled(robot);
    const Chain chain(model, std::string(robot) == "planar2" ? "tip" : "attachment_site");
    GlobalIkOptions options;
    options.timeout = kRoomy;
    options.max_restarts = 200;
    GlobalIk ik(chain, options);
    ChainKinematics kin(chain);
    for (const Pose& X : reachable_targets(chain, 10, 21)) {
      const IkResult r = ik.solve_position(X.p, chain.center());
      ASSERT_TRUE(r.ok()) << robot;
      EXPECT_TRUE(chain.within_limits(r.q));
      const Eigen::Vector3d p = kin.update(r.q).p;
      EXPECT_NEAR(r.position_error, (p - X.p).norm(), 1e-12);
      EXPECT_LE((p - X.p).cwiseAbs().maxCoeff(), options.tolerance.bound[0]) << robot;
      EXPECT_EQ(r.orientation_error, 0.0);
    }
  }
  // a pose solve after a position solve uses the orientation again
  const Chain chain = chain_of("panda");
  GlobalIkOptions options;
  options.timeout = kRoomy;
  options.max_restarts = kRestartCap;
  GlobalIk ik(chain, options);
  const Pose X_WT = reachable_targets(chain, 1, 22).front();
  ik.solve_position(X_WT.p, chain.center());
  const IkResult pose = ik.solve(X_WT, chain.center());
  ASSERT_TRUE(pose.ok());
  EXPECT_TRUE(solves(chain, pose, X_WT));
  // unreachable: the restart cap reports not_converged with the closest point's error
  options.max_restarts = 3;
  ik.set_options(options);
  const IkResult far = ik.solve_position(Eigen::Vector3d(2.0, 0.0, 0.5), chain.center());
  EXPECT_EQ(far.status, IkStatus::not_converged);
  EXPECT_GT(far.position_error, 1.0);
  EXPECT_THROW(ik.solve_position(Eigen::Vector3d(std::nan(""), 0.0, 0.0), chain.center()), Error);
  // allocation-free once the result is sized
  const std::vector<Pose> targets = reachable_targets(chain, 5, 23);
  const Eigen::VectorXd seed = chain.center();
  IkResult result;
  ik.solve_position(X_WT.p, seed, result);
  const std::uint64_t before = test::malloc_calls();
  for (const Pose& X : targets) ik.solve_position(X.p, seed, result);
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(GlobalIk, SeedOutsideTheLimitsIsClippedAndTheAnswerStaysInside) {
  const Chain chain = chain_of("panda");
  GlobalIkOptions options;
  options.timeout = kRoomy;
  options.max_restarts = kRestartCap;
  GlobalIk ik(chain, options);
  Eigen::VectorXd seed = chain.upper() + Eigen::VectorXd::Constant(7, 0.5);
  for (const Pose& X_WT : reachable_targets(chain, 5, 77)) {
    const IkResult r = ik.solve(X_WT, seed);
    EXPECT_TRUE(r.ok());
    EXPECT_TRUE(chain.within_limits(r.q));
  }
}

TEST(GlobalIk, SolveAllocatesNothing) {
  const Chain chain = chain_of("panda");
  for (GlobalIkMode mode : {GlobalIkMode::speed, GlobalIkMode::manipulability}) {
    GlobalIkOptions options;
    options.mode = mode;
    options.max_restarts = 10;
    options.timeout = kRoomy;
    GlobalIk ik(chain, options);
    const std::vector<Pose> targets = reachable_targets(chain, 20, 3);
    const Eigen::VectorXd seed = chain.center();
    IkResult result;
    ik.solve(targets[0], seed, result);  // sizes result.q
    const std::uint64_t before = test::malloc_calls();
    int iterations = 0;
    for (const Pose& X_WT : targets) {
      ik.solve(X_WT, seed, result);
      iterations += result.iterations;
    }
    EXPECT_EQ(test::malloc_calls() - before, 0u);
    EXPECT_GT(iterations, 100);  // many iterations (both methods), QP solves included
  }
}

TEST(GlobalIk, WorksOnTheTrickyArm) {
  // 5 joints incl. a slide: 6-D poses reachable only on the arm's own 5-D set of poses
  const Robot robot = Robot::from_string(test::kTrickyArm);
  const Chain chain(robot, "tool");
  GlobalIkOptions options;
  options.timeout = kRoomy;
  options.max_restarts = kRestartCap;
  GlobalIk ik(chain, options);
  for (const Pose& X_WT : reachable_targets(chain, 10, 4)) {
    const IkResult r = ik.solve(X_WT, chain.center());
    EXPECT_TRUE(r.ok());
    EXPECT_TRUE(solves(chain, r, X_WT));
  }
}

TEST(GlobalIk, BadInputsThrow) {
  const Chain chain = chain_of("panda");
  GlobalIkOptions bad;
  bad.timeout = milliseconds(0);
  EXPECT_THROW(GlobalIk(chain, bad), Error);
  bad = GlobalIkOptions{};
  bad.max_restarts = -1;
  EXPECT_THROW(GlobalIk(chain, bad), Error);
  bad = GlobalIkOptions{};
  bad.tolerance.bound[3] = 0.0;
  EXPECT_THROW(GlobalIk(chain, bad), Error);
  bad = GlobalIkOptions{};
  bad.stall_ratio = 1.0;
  EXPECT_THROW(GlobalIk(chain, bad), Error);

  GlobalIk ik(chain);
  Pose nan_target;
  nan_target.p.y() = std::nan("");
  EXPECT_THROW(ik.solve(nan_target, chain.center()), Error);
  Pose not_rotation;
  not_rotation.R *= 2.0;
  EXPECT_THROW(ik.solve(not_rotation, chain.center()), Error);
  Pose ok;
  ok.p = Eigen::Vector3d(0.4, 0.0, 0.4);
  EXPECT_THROW(ik.solve(ok, Eigen::VectorXd::Zero(6)), Error);
  Eigen::VectorXd nan_seed = chain.center();
  nan_seed[0] = std::nan("");
  EXPECT_THROW(ik.solve(ok, nan_seed), Error);
  EXPECT_THROW(ik.set_options(bad), Error);
}

}  // namespace
}  // namespace mjarm
