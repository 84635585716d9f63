#include "mjarm/ik/analytic_ik.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "ik/local_ik_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/global_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/model/dh_model.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

constexpr double kPi = std::numbers::pi;

/// The UR5e's published table (dh_model.hpp's example).
DhArm ur5e_table() {
  DhArm arm;
  arm.name = "ur5e_dh";
  arm.links = {{.d = 0.1625, .alpha = kPi / 2},
               {.a = -0.425},
               {.a = -0.3922},
               {.d = 0.1333, .alpha = kPi / 2},
               {.d = 0.0997, .alpha = -kPi / 2},
               {.d = 0.0996}};
  return arm;
}

/// PUMA 560 (standard DH, Corke's table); @p shoulder_offset is d₃ (0 puts the wrist centre's
/// plane through axis 1).
DhArm puma_table(double shoulder_offset = 0.15005) {
  DhArm arm;
  arm.name = "puma";
  arm.links = {{.alpha = kPi / 2},
               {.a = 0.4318},
               {.a = 0.0203, .d = shoulder_offset, .alpha = -kPi / 2},
               {.d = 0.4318, .alpha = kPi / 2},
               {.alpha = -kPi / 2},
               {}};
  return arm;
}

/// A KUKA-KR-like arm (offset shoulder a₁, elbow offset a₃), on a tilted base with a tool offset.
DhArm kuka_like_table() {
  DhArm arm;
  arm.name = "kuka_like";
  arm.links = {{.a = 0.025, .d = 0.4, .alpha = -kPi / 2},
               {.a = 0.455},
               {.a = 0.035, .alpha = -kPi / 2},
               {.d = 0.42, .alpha = kPi / 2},
               {.alpha = -kPi / 2},
               {.d = 0.08}};
  arm.base.block<3, 3>(0, 0) =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  arm.base.block<3, 1>(0, 3) = Eigen::Vector3d(0.1, -0.2, 0.3);
  arm.tool.block<3, 3>(0, 0) = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY()).toRotationMatrix();
  arm.tool.block<3, 1>(0, 3) = Eigen::Vector3d(0.02, 0.0, 0.12);
  return arm;
}

Chain dh_chain(const DhArm& arm) { return Chain(dh_robot(arm), "end"); }

/// Largest |q_a − q_b| modulo 2π.
double angle_gap(const Vector6d& a, const Vector6d& b) {
  double gap = 0.0;
  for (int i = 0; i < 6; ++i) gap = std::max(gap, std::abs(std::remainder(a[i] - b[i], 2 * kPi)));
  return gap;
}

struct RoundTrip {
  int samples = 0, recovered = 0, eight = 0, singular = 0;
  double worst_position = 0.0, worst_orientation = 0.0;
};

/// Random configurations in [−π, π) → MuJoCo FK → solve → MuJoCo FK of every branch.
RoundTrip round_trip(const Chain& chain, int samples, std::uint64_t seed) {
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  Random rng(seed);
  RoundTrip r;
  AnalyticIkSolution solution;
  for (int k = 0; k < samples; ++k) {
    Vector6d q;
    for (int i = 0; i < 6; ++i) q[i] = uniform(rng, -kPi, kPi);
    const Pose target = kin.update(q);
    ik.solve(target, solution);
    EXPECT_EQ(solution.status, AnalyticIkStatus::solved) << "sample " << k;
    ++r.samples;
    bool found = false, singular = false;
    for (int b = 0; b < solution.count; ++b) {
      const AnalyticIkBranch& branch = solution.branches[b];
      const Pose& X = kin.update(branch.q);
      r.worst_position = std::max(r.worst_position, (X.p - target.p).norm());
      const Eigen::AngleAxisd rel(X.R.transpose() * target.R);
      r.worst_orientation = std::max(r.worst_orientation, std::abs(rel.angle()));
      if (angle_gap(branch.q, q) < 1e-6) found = true;
      singular = singular || branch.singular;
      EXPECT_EQ(branch.within_limits, chain.within_limits(branch.q));
    }
    r.recovered += found;
    r.eight += solution.count == 8;
    r.singular += singular;
  }
  return r;
}

TEST(AnalyticIkStructure, DetectsTheFamiliesOffTheModel) {
  EXPECT_EQ(AnalyticIk(test::chain_of("ur5e")).family(), AnalyticIkFamily::parallel_shoulder);
  EXPECT_EQ(AnalyticIk(dh_chain(ur5e_table())).family(), AnalyticIkFamily::parallel_shoulder);
  EXPECT_EQ(AnalyticIk(dh_chain(puma_table())).family(), AnalyticIkFamily::spherical_wrist);
  EXPECT_EQ(AnalyticIk(dh_chain(kuka_like_table())).family(), AnalyticIkFamily::spherical_wrist);
}

TEST(AnalyticIkStructure, RefusesWithTheReason) {
  const auto refusal = [](const Chain& chain) {
    try {
      AnalyticIk ik(chain);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal(test::chain_of("panda")).find("7 joints"), std::string::npos);
  DhArm prismatic = puma_table();
  prismatic.links[2].prismatic = true;
  prismatic.links[2].lower = 0.0;
  prismatic.links[2].upper = 0.3;
  EXPECT_NE(refusal(dh_chain(prismatic)).find("not revolute"), std::string::npos);
  // the UR table with a twisted, offset wrist: neither family
  DhArm skewed = ur5e_table();
  skewed.links[4].a = 0.05;
  skewed.links[3].alpha = 1.2;
  const std::string reason = refusal(dh_chain(skewed));
  EXPECT_NE(reason.find("no closed-form family"), std::string::npos) << reason;
  EXPECT_FALSE(analyze_analytic_ik(dh_chain(skewed)).solvable);
}

TEST(AnalyticIkStructure, PoeFormMatchesMujoco) {
  const Chain chain = dh_chain(kuka_like_table());
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  Random rng(3);
  for (int k = 0; k < 50; ++k) {
    Vector6d q;
    for (int i = 0; i < 6; ++i) q[i] = uniform(rng, -3.0, 3.0);
    const Pose& mj = kin.update(q);
    const Pose poe = ik.forward(q);
    EXPECT_LT((mj.p - poe.p).norm(), 1e-13);
    EXPECT_LT((mj.R - poe.R).norm(), 1e-13);
  }
}

/// @p min_eight: the least fraction of samples with all 8 branches (the rest have fewer real
/// solutions: `FewerThanEightAreAllThereIs` checks that by a numeric search).
void expect_round_trip(const Chain& chain, int samples, std::uint64_t seed, double min_eight) {
  const RoundTrip r = round_trip(chain, samples, seed);
  EXPECT_LT(r.worst_position, 1e-10);
  EXPECT_LT(r.worst_orientation, 1e-10);
  EXPECT_EQ(r.recovered, r.samples);
  EXPECT_GE(r.eight, min_eight * r.samples);
  EXPECT_EQ(r.singular, 0);
}

TEST(AnalyticIkSolve, BundledUr5eEveryBranchReproducesThePose) {
  expect_round_trip(test::chain_of("ur5e"), 3000, 11, 0.7);
}

TEST(AnalyticIkSolve, Ur5eDhTableEveryBranchReproducesThePose) {
  expect_round_trip(dh_chain(ur5e_table()), 1000, 12, 0.7);
}

TEST(AnalyticIkSolve, PumaEveryBranchReproducesThePose) {
  expect_round_trip(dh_chain(puma_table()), 3000, 13, 0.0);
}

TEST(AnalyticIkSolve, KukaLikeOnTiltedBaseEveryBranchReproducesThePose) {
  expect_round_trip(dh_chain(kuka_like_table()), 2000, 14, 0.0);
}

/// Every branch of @p solution reproduces @p target by MuJoCo's FK to 1e-10.
void expect_branches_reach(const Chain& chain, const AnalyticIkSolution& solution,
                           const Pose& target) {
  ChainKinematics kin(chain);
  for (int b = 0; b < solution.count; ++b) {
    const Pose& X = kin.update(solution.branches[b].q);
    EXPECT_LT((X.p - target.p).norm(), 1e-10) << "branch " << b;
    EXPECT_LT(std::abs(Eigen::AngleAxisd(X.R.transpose() * target.R).angle()), 1e-10)
        << "branch " << b;
  }
}

TEST(AnalyticIkSingular, Ur5eWristAtAndNearZero) {
  const Chain chain = test::chain_of("ur5e");
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  for (const double theta5 : {0.0, 1e-9, 1e-5}) {
    Vector6d q;
    q << 0.4, -1.1, 1.3, -0.7, theta5, 0.9;  // wrist_2 = 0: axis 6 parallel to axes 2, 3, 4
    const Pose target = kin.update(q);
    const AnalyticIkSolution solution = ik.solve(target);
    ASSERT_EQ(solution.status, AnalyticIkStatus::solved);
    EXPECT_EQ(solution.dropped, 0) << theta5;
    expect_branches_reach(chain, solution, target);
    bool flagged = false, original = false;
    for (int b = 0; b < solution.count; ++b) {
      flagged = flagged || solution.branches[b].singular;
      original = original || angle_gap(solution.branches[b].q, q) < 1e-6;
    }
    EXPECT_EQ(flagged, theta5 < 1e-6) << theta5;
    // θ5 = 0 lies on the shoulder's both branches (ω₂·ω₆ is kept): a representative each
    if (theta5 < 1e-6) EXPECT_LT(solution.count, 8) << theta5;
    // within the tolerance the representative is one member of the family (θ4, θ6 traded)
    if (theta5 > 1e-6) EXPECT_TRUE(original) << theta5;
  }
}

TEST(AnalyticIkSingular, Ur5eStretchedElbowIsFlaggedAndReproduced) {
  const Chain chain = test::chain_of("ur5e");
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  Vector6d q;
  q << -0.3, -0.8, 0.0, 1.2, 0.9, -0.4;  // elbow = 0: upper arm and forearm in line
  const Pose target = kin.update(q);
  const AnalyticIkSolution solution = ik.solve(target);
  ASSERT_EQ(solution.status, AnalyticIkStatus::solved);
  expect_branches_reach(chain, solution, target);
  bool original = false, flagged = false;
  for (int b = 0; b < solution.count; ++b) {
    original = original || angle_gap(solution.branches[b].q, q) < 1e-6;
    flagged = flagged || solution.branches[b].singular;
  }
  EXPECT_TRUE(original);
  EXPECT_TRUE(flagged);
}

TEST(AnalyticIkSingular, PumaWristAtZeroAndNearZero) {
  const Chain chain = dh_chain(puma_table());
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  for (const double theta5 : {0.0, 1e-9, 1e-5, 1e-3}) {
    Vector6d q;
    q << 0.5, 0.3, -0.6, 0.8, theta5, -1.2;
    const Pose target = kin.update(q);
    const AnalyticIkSolution solution = ik.solve(target);
    ASSERT_EQ(solution.status, AnalyticIkStatus::solved) << theta5;
    EXPECT_EQ(solution.dropped, 0) << theta5;
    expect_branches_reach(chain, solution, target);
    bool flagged = false;
    for (int b = 0; b < solution.count; ++b) flagged = flagged || solution.branches[b].singular;
    // at and within the tolerance of θ5 = 0 that branch's wrist pair is one flagged
    // representative (the other shoulder and elbow branches have their wrists elsewhere)
    EXPECT_EQ(flagged, theta5 < 1e-6) << theta5;
    EXPECT_EQ(solution.count, theta5 < 1e-6 ? 7 : 8) << theta5;
    bool original = false;
    for (int b = 0; b < solution.count; ++b) {
      original = original || angle_gap(solution.branches[b].q, q) < 1e-6;
    }
    if (theta5 > 1e-6) EXPECT_TRUE(original) << theta5;
  }
}

TEST(AnalyticIkSingular, WristCentreOnTheShoulderAxis) {
  // without the shoulder offset the wrist centre can sit on axis 1: θ1 is then free
  const Chain chain = dh_chain(puma_table(0.0));
  const AnalyticIk ik(chain);
  const AnalyticIkGeometry& g = ik.geometry();
  // a target whose wrist centre lies 0.5 m up axis 1 from the shoulder, any orientation
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  Pose target;
  target.R = R;
  const Eigen::Matrix3d Rg = R * g.M.R.transpose();
  const Eigen::Vector3d P = g.anchor[0] + 0.5 * g.axis[0];
  target.p = P - Rg * g.wrist + Rg * g.M.p;
  const AnalyticIkSolution solution = ik.solve(target);
  ASSERT_EQ(solution.status, AnalyticIkStatus::solved);
  EXPECT_GT(solution.count, 0);
  expect_branches_reach(chain, solution, target);
  for (int b = 0; b < solution.count; ++b) EXPECT_TRUE(solution.branches[b].singular);
}

TEST(AnalyticIkSolve, FewerThanEightAreAllThereIs) {
  // where the UR gets fewer than 8 branches, a numeric search from many random starts finds no
  // solution that is not among them
  const Chain chain = test::chain_of("ur5e");
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  GlobalIkOptions numeric;
  numeric.analytic = false;
  numeric.timeout = std::chrono::seconds(60);
  numeric.max_restarts = 50;
  numeric.tolerance = PoseTolerance::uniform(1e-9);
  GlobalIk search(chain, numeric);
  Random rng(21);
  int checked = 0, found = 0;
  for (int k = 0; k < 400 && checked < 3; ++k) {
    Vector6d q;
    for (int i = 0; i < 6; ++i) q[i] = uniform(rng, -kPi, kPi);
    const Pose target = kin.update(q);
    const AnalyticIkSolution solution = ik.solve(target);
    if (solution.count == 8) continue;
    ++checked;
    for (int start = 0; start < 60; ++start) {
      Eigen::VectorXd seed(6);
      for (int i = 0; i < 6; ++i) seed[i] = uniform(rng, -kPi, kPi);
      const IkResult r = search.solve(target, seed);
      if (!r.ok()) continue;
      ++found;
      double nearest = INFINITY;
      for (int b = 0; b < solution.count; ++b) {
        nearest = std::min(nearest, angle_gap(solution.branches[b].q, r.q));
      }
      EXPECT_LT(nearest, 1e-4) << "sample " << k << ": a solution no branch gives";
    }
  }
  EXPECT_EQ(checked, 3);
  EXPECT_GT(found, 60);  // the search did find solutions to compare
}

TEST(AnalyticIkSolve, OutOfReachGivesNoBranchAndSaysWhy) {
  for (const Chain& chain : {test::chain_of("ur5e"), dh_chain(puma_table())}) {
    const AnalyticIk ik(chain);
    Pose far;
    far.p = Eigen::Vector3d(3.0, 1.0, 0.5);
    AnalyticIkSolution solution = ik.solve(far);
    EXPECT_EQ(solution.status, AnalyticIkStatus::out_of_reach);
    EXPECT_EQ(solution.count, 0);
    EXPECT_STREQ(to_string(solution.status), "out_of_reach");
  }
  // the UR's shoulder offset: a wrist point on axis 1 cannot be reached
  const AnalyticIk ur(test::chain_of("ur5e"));
  const AnalyticIkGeometry& g = ur.geometry();
  Pose inside;  // R = M.R: the wrist point then moves by p_T − p_M
  inside.R = g.M.R;
  inside.p = g.anchor[0] + 0.3 * g.axis[0] - g.wrist + g.M.p;
  EXPECT_EQ(ur.solve(inside).status, AnalyticIkStatus::out_of_reach);
}

TEST(AnalyticIkSolve, UncheckedBranchesAreTheSameWithoutErrors) {
  const Chain chain = dh_chain(kuka_like_table());
  AnalyticIkOptions options;
  options.check_branches = false;
  const AnalyticIk checked(chain), unchecked(chain, options);
  ChainKinematics kin(chain);
  Vector6d q;
  q << 0.3, -0.5, 0.9, 1.1, -0.7, 2.0;
  const Pose target = kin.update(q);
  const AnalyticIkSolution a = checked.solve(target), b = unchecked.solve(target);
  ASSERT_EQ(a.count, b.count);
  for (int k = 0; k < a.count; ++k) {
    EXPECT_EQ(a.branches[k].q, b.branches[k].q);
    EXPECT_TRUE(std::isnan(b.branches[k].position_error));
  }
}

TEST(AnalyticIkSolve, RejectsANonFiniteTarget) {
  const AnalyticIk ik(test::chain_of("ur5e"));
  Pose bad;
  bad.p.x() = std::nan("");
  EXPECT_THROW(ik.solve(bad), Error);
}

TEST(AnalyticIkSolve, SolveAllocatesNothing) {
  const Chain chain = test::chain_of("ur5e");
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  std::vector<Pose> targets;
  Random rng(5);
  for (int k = 0; k < 50; ++k) {
    Vector6d q;
    for (int i = 0; i < 6; ++i) q[i] = uniform(rng, -kPi, kPi);
    targets.push_back(kin.update(q));
  }
  AnalyticIkSolution solution;
  Eigen::VectorXd seed = Eigen::VectorXd::Zero(6), q(6);
  int solved = 0;
  const std::uint64_t before = test::malloc_calls();
  for (const Pose& target : targets) {
    ik.solve(target, solution);
    solved += ik.closest_to(solution, seed, q) >= 0;
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_EQ(solved, 50);
}

TEST(AnalyticIkSolve, ClosestToTheSeedShiftsByTurnsWithinTheLimits) {
  const Chain chain = test::chain_of("ur5e");  // limits ±2π: two turns per joint
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  Vector6d q_true;
  q_true << 4.0, -1.0, 1.5, -5.0, 2.0, 5.5;  // beyond ±π: found only by shifting a turn
  const AnalyticIkSolution solution = ik.solve(kin.update(q_true));
  Eigen::VectorXd seed = q_true + Eigen::VectorXd::Constant(6, 0.05), q(6);
  const int index = ik.closest_to(solution, seed, q);
  ASSERT_GE(index, 0);
  EXPECT_LT((q - q_true).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_TRUE(chain.within_limits(q));
  // a seed a turn away on joint 1 picks the other turn, still the same branch
  seed[0] -= 2 * kPi;
  ik.closest_to(solution, seed, q);
  EXPECT_NEAR(q[0], q_true[0] - 2 * kPi, 1e-9);
}

TEST(AnalyticIkSolve, LimitsFlagFollowsTheJointRanges) {
  DhArm arm = puma_table();
  arm.links[2].lower = -0.5;  // a narrow elbow: some branches fall outside
  arm.links[2].upper = 0.5;
  const Chain chain = dh_chain(arm);
  const AnalyticIk ik(chain);
  ChainKinematics kin(chain);
  Vector6d q;
  q << 0.2, 0.4, 0.1, -0.3, 0.7, 0.2;
  const AnalyticIkSolution solution = ik.solve(kin.update(q));
  int inside = 0, outside = 0;
  for (int b = 0; b < solution.count; ++b) {
    const bool in = solution.branches[b].within_limits;
    EXPECT_EQ(in, chain.within_limits(solution.branches[b].q));
    (in ? inside : outside) += 1;
  }
  EXPECT_GT(inside, 0);
  EXPECT_GT(outside, 0);
  Eigen::VectorXd out(6);
  const int index = ik.closest_to(solution, q, out);
  ASSERT_GE(index, 0);
  EXPECT_LT((out - Eigen::VectorXd(q)).norm(), 1e-6);
}

TEST(AnalyticIkInGlobalIk, TriesTheClosedFormFirstAndCanBeTurnedOff) {
  const Chain chain = test::chain_of("ur5e");
  ChainKinematics kin(chain);
  Vector6d q_true;
  q_true << 0.3, -1.2, 1.1, -0.4, 0.8, -0.6;
  const Pose target = kin.update(q_true);
  const Eigen::VectorXd seed = q_true + Eigen::VectorXd::Constant(6, 0.1);
  GlobalIkOptions options;
  options.mode = GlobalIkMode::distance;
  options.max_restarts = 20;
  options.timeout = std::chrono::seconds(60);
  GlobalIk global(chain, options);
  const IkResult analytic = global.solve(target, seed);
  ASSERT_TRUE(analytic.ok());
  EXPECT_TRUE(global.stats().analytic);
  EXPECT_EQ(global.stats().attempts, 0);
  EXPECT_LT((analytic.q - Eigen::VectorXd(q_true)).norm(), 1e-9);  // the branch nearest the seed
  EXPECT_LT(analytic.position_error, 1e-10);

  options.analytic = false;
  global.set_options(options);
  const IkResult numeric = global.solve(target, seed);
  ASSERT_TRUE(numeric.ok());
  EXPECT_FALSE(global.stats().analytic);
  EXPECT_GE(global.stats().attempts, 1);

  // no closed form on the panda: the restarts run as before
  GlobalIkOptions panda_options;
  panda_options.max_restarts = 20;
  panda_options.timeout = std::chrono::seconds(60);
  const Chain panda = test::chain_of("panda");
  GlobalIk panda_ik(panda, panda_options);
  ChainKinematics panda_kin(panda);
  panda_ik.solve(panda_kin.update(panda.center()), panda.center());
  EXPECT_FALSE(panda_ik.stats().analytic);
}

TEST(AnalyticIkInGlobalIk, FallsBackWhenNoBranchIsWithinTheLimits) {
  DhArm arm = puma_table();
  arm.links[2].lower = -0.5;
  arm.links[2].upper = 0.5;
  const Chain chain = dh_chain(arm);
  ChainKinematics kin(chain);
  Vector6d q;
  q << 0.2, 0.4, 0.1, -0.3, 0.7, 0.2;
  GlobalIkOptions options;
  options.max_restarts = 50;
  options.timeout = std::chrono::seconds(60);
  GlobalIk global(chain, options);
  // reachable within the limits: the closed form answers
  EXPECT_TRUE(global.solve(kin.update(q), chain.center()).ok());
  EXPECT_TRUE(global.stats().analytic);
  // a pose whose every branch needs the elbow beyond its narrow range: the search runs and fails
  q[2] = 2.5;
  Eigen::VectorXd unlimited = q;
  DhArm free_arm = puma_table();
  const Chain free_chain = dh_chain(free_arm);
  ChainKinematics free_kin(free_chain);
  const Pose beyond = free_kin.update(unlimited);
  const AnalyticIk ik(chain);
  const AnalyticIkSolution branches = ik.solve(beyond);
  int inside = 0;
  for (int b = 0; b < branches.count; ++b) inside += branches.branches[b].within_limits;
  ASSERT_EQ(inside, 0);
  const IkResult r = global.solve(beyond, chain.center());
  EXPECT_FALSE(global.stats().analytic);
  EXPECT_GE(global.stats().attempts, 1);
  EXPECT_TRUE(chain.within_limits(r.q));
}

}  // namespace
}  // namespace mjarm
