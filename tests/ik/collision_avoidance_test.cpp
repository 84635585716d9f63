#include "mjarm/ik/collision_avoidance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

// a planar 3-link arm in the xy plane (reach 0.65 m) ending in a sphere hand, a wall whose
// near face is the plane x = 0.48, and a free-standing sphere and capsule for the other pairs
constexpr const char* kWallArmXml = R"(
<mujoco model="wall_arm">
  <compiler angle="radian"/>
  <worldbody>
    <geom name="wall" type="box" pos="0.5 0 0" size="0.02 0.6 0.3"/>
    <geom name="ball" type="sphere" pos="-0.3 0.3 0" size="0.05"/>
    <geom name="post" type="capsule" fromto="-0.3 -0.3 -0.2 -0.3 -0.3 0.2" size="0.03"/>
    <body name="link1">
      <joint name="j1" type="hinge" axis="0 0 1" range="-3 3"/>
      <geom name="link1_geom" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
      <body name="link2" pos="0.3 0 0">
        <joint name="j2" type="hinge" axis="0 0 1" range="-2.8 2.8"/>
        <geom name="link2_geom" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <body name="hand_body" pos="0.3 0 0">
          <joint name="j3" type="hinge" axis="0 0 1" range="-2.5 2.5"/>
          <geom name="hand" type="sphere" pos="0.05 0 0" size="0.04"/>
          <site name="tip" pos="0.05 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>)";

Chain wall_arm_chain() { return Chain(Robot::from_string(kWallArmXml), "tip"); }

CollisionAvoidanceOptions hand_wall_options() {
  CollisionAvoidanceOptions options;
  options.pairs = {{"hand", "wall"}};
  options.min_distance = 0.01;
  options.detection_distance = 0.1;
  options.gain = 0.5;
  return options;
}

// hand in front of the wall, below the target's y
Eigen::VectorXd wall_arm_start() { return Eigen::Vector3d(-1.2, 2.0, 0.5); }

struct WallRun {
  double min_distance = 1e9;    // smallest hand–wall distance along the run [m]
  double final_distance = 0.0;  // at the end [m]
  Eigen::Vector3d final_tip;    // hand centre at the end [m]
  bool all_solved = true;
  int contact_step = -1;              // first step within 1 mm of the margin
  double y_error_at_contact = 0.0;    // |y − y_target| then [m]
  double largest_y_error_rise = 0.0;  // largest growth of |y − y_target| in a step after [m]
};

WallRun drive_into_wall(bool with_constraint, const Eigen::Vector3d& target, int steps) {
  const Chain chain = wall_arm_chain();
  DiffIkOptions options;
  options.dt = 0.01;
  options.velocity_limit = Eigen::VectorXd::Constant(3, 2.0);
  DiffIk ik(chain, options);
  const int task = ik.add_position_task("tip", 1.0, 0.5);
  ik.add_posture_task(chain.center(), 1e-4);
  if (with_constraint) {
    ik.add_constraint(std::make_unique<CollisionAvoidance>(chain, hand_wall_options()));
  }
  ik.set_target(task, target);
  CollisionAvoidance probe(chain, hand_wall_options());
  ChainKinematics kin(chain);
  Eigen::VectorXd q = wall_arm_start();
  WallRun run;
  for (int s = 0; s < steps; ++s) {
    const DiffIkStep& step = ik.step(q);
    run.all_solved = run.all_solved && step.qp_status == qp::QpStatus::solved;
    const double y_error_before = std::abs(kin.update(q).p.y() - target.y());
    q = step.q_next;
    const double d = probe.distance(q, 0);
    run.min_distance = std::min(run.min_distance, d);
    const double y_error = std::abs(kin.update(q).p.y() - target.y());
    if (run.contact_step < 0 && d < 0.011) {
      run.contact_step = s;
      run.y_error_at_contact = y_error;
    } else if (run.contact_step >= 0 && y_error_before > 2e-3) {
      // until it settles within 2 mm (the posture task shifts the optimum by ~0.75 mm)
      run.largest_y_error_rise = std::max(run.largest_y_error_rise, y_error - y_error_before);
    }
  }
  run.final_distance = probe.distance(q, 0);
  run.final_tip = kin.update(q).p;
  return run;
}

TEST(CollisionAvoidance, HandDrivenThroughAWallStopsAtTheMarginAndSlides) {
  const Eigen::Vector3d behind_wall(0.55, 0.15, 0.0);
  // without the rows the hand goes into the wall: the test below can fail
  const WallRun free = drive_into_wall(false, behind_wall, 400);
  EXPECT_LT(free.min_distance, -0.01);

  const WallRun guarded = drive_into_wall(true, behind_wall, 400);
  EXPECT_TRUE(guarded.all_solved);
  // never below the margin (linearisation error of one step only), and it ends on it
  EXPECT_GT(guarded.min_distance, 0.01 - 2e-4);
  EXPECT_NEAR(guarded.final_distance, 0.01, 2e-3);
  // it slid along the wall: its tangential coordinate reached the target's
  EXPECT_NEAR(guarded.final_tip.y(), 0.15, 5e-3);
  EXPECT_NEAR(guarded.final_tip.x(), 0.48 - 0.04 - 0.01, 2e-3);
}

TEST(CollisionAvoidance, TangentialCoordinateKeepsApproachingAlongTheWall) {
  // it meets the wall well short of the target's y, then the y error only falls
  const WallRun run = drive_into_wall(true, Eigen::Vector3d(0.55, 0.15, 0.0), 400);
  ASSERT_GE(run.contact_step, 0);
  EXPECT_GT(run.y_error_at_contact, 0.05);
  EXPECT_LT(run.largest_y_error_rise, 1e-9);
  EXPECT_LT(std::abs(run.final_tip.y() - 0.15), 1.5e-3);
}

TEST(CollisionAvoidance, EveryRowMatchesFiniteDifferencesOfTheDistance) {
  // sphere–box, capsule–box, sphere–sphere, capsule–capsule, sphere–capsule and a pair of two
  // moving geoms; rows h(q) = d − d_min read back from b
  const Chain chain = wall_arm_chain();
  CollisionAvoidanceOptions options;
  options.pairs = {{"hand", "wall"},       {"link2_geom", "wall"}, {"hand", "ball"},
                   {"link1_geom", "post"}, {"hand", "post"},       {"hand", "link1_geom"}};
  options.min_distance = 0.0;
  options.detection_distance = 2.0;  // every pair a row
  options.gain = 1.0;
  CollisionAvoidance avoid(chain, options);
  const double dt = 1.0;  // so b = −(d − d_min)
  Eigen::MatrixXd C(avoid.max_rows(), 3);
  Eigen::VectorXd b(avoid.max_rows());
  Random rng(11);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::VectorXd q =
        Eigen::Vector3d(uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0));
    const int k = avoid.rows(q, dt, C, b);
    ASSERT_EQ(k, avoid.pair_count());
    for (int r = 0; r < k; ++r) {
      const int pair = avoid.row_pair(r);
      EXPECT_NEAR(-b[r], avoid.row_distance(r), 1e-15);
      if (std::abs(avoid.row_distance(r)) < 1e-3) continue;  // touching: no unique normal
      for (int i = 0; i < 3; ++i) {
        const double h = 1e-6;
        Eigen::VectorXd qp = q, qm = q;
        qp[i] += h;
        qm[i] -= h;
        const double fd = (avoid.distance(qp, pair) - avoid.distance(qm, pair)) / (2 * h);
        EXPECT_NEAR(C(r, i), fd, 1e-6) << "pair " << pair << " joint " << i << " trial " << trial;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(CollisionAvoidance, SolvedStepsHoldEveryRowTheyHad) {
  // random configurations and targets with robot-vs-scene pairs and tight velocity limits:
  // whenever the QP says solved, C·v ≥ b and the box hold at the returned v
  const Chain chain = wall_arm_chain();
  DiffIkOptions ik_options;
  ik_options.dt = 0.02;
  ik_options.velocity_limit = Eigen::VectorXd::Constant(3, 1.5);
  DiffIk ik(chain, ik_options);
  const int task = ik.add_position_task("tip", 1.0, 1.0);
  CollisionAvoidanceOptions options;
  options.robot_vs_scene = true;
  options.min_distance = 0.01;
  options.detection_distance = 0.3;
  ik.add_constraint(std::make_unique<CollisionAvoidance>(chain, options));
  Random rng(5);
  int solved = 0, with_rows = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::VectorXd q =
        Eigen::Vector3d(uniform(rng, -2.4, 2.4), uniform(rng, -2.4, 2.4), uniform(rng, -2.4, 2.4));
    ik.set_target(task, Eigen::Vector3d(uniform(rng, -0.7, 0.7), uniform(rng, -0.7, 0.7), 0.0));
    const DiffIkStep& step = ik.step(q);
    if (step.qp_status != qp::QpStatus::solved) continue;
    ++solved;
    with_rows += step.constraint_rows > 0 ? 1 : 0;
    const Eigen::VectorXd slack = ik.constraint_matrix() * step.v - ik.constraint_lower();
    for (Eigen::Index r = 0; r < slack.size(); ++r) {
      const double scale = 1.0 + std::abs(ik.constraint_lower()[r]);
      if (std::isfinite(ik.constraint_lower()[r])) EXPECT_GT(slack[r], -1e-9 * scale);
    }
    EXPECT_TRUE(chain.within_limits(step.q_next));
    EXPECT_LE(step.v.cwiseAbs().maxCoeff(), 1.5);
  }
  EXPECT_GT(solved, 200);
  EXPECT_GT(with_rows, 50);
}

TEST(CollisionAvoidance, RobotVsSceneWatchesMovingGeomsAgainstTheWorld) {
  const Chain chain = wall_arm_chain();
  CollisionAvoidanceOptions options;
  options.robot_vs_scene = true;
  const CollisionAvoidance avoid(chain, options);
  EXPECT_EQ(avoid.pair_count(), 3 * 3);  // {link1, link2, hand} × {wall, ball, post}
}

TEST(CollisionAvoidance, UnknownGeomNamesTheClosestOnes) {
  const Chain chain = wall_arm_chain();
  CollisionAvoidanceOptions options = hand_wall_options();
  options.pairs = {{"hnad", "wall"}};
  try {
    const CollisionAvoidance avoid(chain, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("hnad"), std::string::npos) << message;
    EXPECT_NE(message.find("hand"), std::string::npos) << message;
  }
}

TEST(CollisionAvoidance, BadOptionsAreNamed) {
  const Chain chain = wall_arm_chain();
  CollisionAvoidanceOptions options = hand_wall_options();
  options.detection_distance = 0.005;  // below min_distance
  EXPECT_THROW(CollisionAvoidance(chain, options), Error);
  options = hand_wall_options();
  options.gain = 0.0;
  EXPECT_THROW(CollisionAvoidance(chain, options), Error);
  options = hand_wall_options();
  options.pairs = {{"hand", "hand"}};
  EXPECT_THROW(CollisionAvoidance(chain, options), Error);
  options.pairs.clear();
  EXPECT_THROW(CollisionAvoidance(chain, options), Error);
}

TEST(CollisionAvoidance, StepWithCollisionRowsAllocatesNothing) {
  const Chain chain = wall_arm_chain();
  DiffIk ik(chain);
  const int task = ik.add_position_task("tip", 1.0, 0.5);
  CollisionAvoidanceOptions options = hand_wall_options();
  options.robot_vs_scene = true;
  ik.add_constraint(std::make_unique<CollisionAvoidance>(chain, options));
  ik.set_target(task, Eigen::Vector3d(0.55, 0.15, 0.0));
  Eigen::VectorXd q = wall_arm_start();
  q = ik.step(q).q_next;  // first step: warm-up
  const std::uint64_t before = test::malloc_calls();
  for (int s = 0; s < 200; ++s) q = ik.step(q).q_next;
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_GT(ik.last_step().constraint_rows, 0);
}

}  // namespace
}  // namespace mjarm

namespace mjarm {
namespace {

// the planar arm with a box hand, before a box wall, a cylinder and an ellipsoid: box–box goes
// through MuJoCo's box routine, the cylinder and the ellipsoid through its convex solver
constexpr const char* kBoxHandXml = R"(
<mujoco model="box_hand">
  <compiler angle="radian"/>
  <worldbody>
    <geom name="wall" type="box" pos="0.5 0 0" size="0.02 0.6 0.3" euler="0 0 0.3"/>
    <geom name="drum" type="cylinder" pos="-0.3 0.3 0" size="0.05 0.2"/>
    <geom name="egg" type="ellipsoid" pos="-0.3 -0.3 0.05" size="0.08 0.05 0.04"/>
    <body name="link1">
      <joint name="j1" type="hinge" axis="0 0 1" range="-3 3"/>
      <geom name="link1_geom" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
      <body name="link2" pos="0.3 0 0">
        <joint name="j2" type="hinge" axis="0 0 1" range="-2.8 2.8"/>
        <geom name="link2_geom" type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <body name="hand_body" pos="0.3 0 0">
          <joint name="j3" type="hinge" axis="0 0 1" range="-2.5 2.5"/>
          <geom name="hand" type="box" pos="0.05 0 0" size="0.04 0.03 0.02" euler="0.2 0.1 0.4"/>
          <site name="tip" pos="0.05 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>)";

/// Rows of the box hand's pairs against finite differences of their distances: how many were
/// compared, and how many disagreed by more than @p tolerance.
std::pair<int, int> box_hand_rows_against_differences(const std::string& other, double tolerance) {
  const Chain chain(Robot::from_string(kBoxHandXml), "tip");
  CollisionAvoidanceOptions options;
  options.pairs = {{"hand", other}};
  options.min_distance = 0.0;
  options.detection_distance = 2.0;
  options.gain = 1.0;
  CollisionAvoidance avoid(chain, options);
  Eigen::MatrixXd C(1, 3);
  Eigen::VectorXd b(1);
  Random rng(23);
  int compared = 0, disagreed = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Eigen::VectorXd q =
        Eigen::Vector3d(uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0));
    if (avoid.rows(q, 1.0, C, b) != 1 || avoid.row_distance(0) < 1e-3) continue;
    for (int i = 0; i < 3; ++i) {
      const double h = 1e-6;
      Eigen::VectorXd qp = q, qm = q;
      qp[i] += h;
      qm[i] -= h;
      const double fd = (avoid.distance(qp, 0) - avoid.distance(qm, 0)) / (2 * h);
      ++compared;
      if (!(std::abs(C(0, i) - fd) <= tolerance)) ++disagreed;
    }
  }
  return {compared, disagreed};
}

TEST(CollisionAvoidanceConvex, BoxAgainstBoxRowsMatchFiniteDifferences) {
  const auto [compared, disagreed] = box_hand_rows_against_differences("wall", 1e-8);
  EXPECT_GT(compared, 100);
  EXPECT_EQ(disagreed, 0) << "of " << compared;
}

// the convex solver's distance is exact to its tolerance (1e-6 by default), so central differences
// over h = 1e-6 carry up to ~1e-3 of noise: 5 of 177 comparisons differ by more than 1e-6, none
// by more than 1e-4
TEST(CollisionAvoidanceConvex, ConvexSolverPairsMatchFiniteDifferences) {
  for (const char* other : {"drum", "egg"}) {
    const auto [compared, disagreed] = box_hand_rows_against_differences(other, 1e-4);
    EXPECT_GT(compared, 100) << other;
    EXPECT_EQ(disagreed, 0) << other << ": of " << compared;
  }
}

}  // namespace
}  // namespace mjarm
