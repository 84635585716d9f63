#include "mjarm/ik/pose_ik.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <random>

#include "ik/local_ik_support.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/targets.hpp"
#include "support/random_configurations.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

using test::ArmCase;

TEST(PoseIk, RoundTripsOnEveryBundledArm) {
  for (const ArmCase& arm : test::bundled_arms()) {
    if (arm.model == "planar2")
      continue;  // two joints cannot hold a 6-D pose (position tests cover it)
    SCOPED_TRACE(arm.model);
    const Robot robot = Robot::bundled(arm.model);
    const Chain chain(robot, arm.frame);
    PoseIk ik(chain);
    ChainKinematics fk(chain);
    std::mt19937 rng(21);
    const int trials = 100;
    int from_centre = 0, from_nearby = 0;
    for (int t = 0; t < trials; ++t) {
      const Eigen::VectorXd q_true = test::random_q(chain, rng, 0.02);
      const Pose X_WT = fk.update(q_true);
      for (const bool nearby : {false, true}) {
        const Eigen::VectorXd seed =
            nearby ? test::perturb(chain, q_true, rng, 0.2) : chain.center();
        const IkResult r = ik.solve(X_WT, seed);
        EXPECT_TRUE(chain.within_limits(r.q));
        // the reported errors are the true ones
        const FrameErrors f = frame_errors(fk.update(r.q), X_WT);
        EXPECT_NEAR(r.position_error, f.position, 1e-12);
        EXPECT_NEAR(r.orientation_error, f.orientation, 1e-12);
        if (r.ok()) {
          EXPECT_LE(f.position, ik.options().position_tolerance);
          EXPECT_LE(f.orientation, ik.options().orientation_tolerance);
          (nearby ? from_nearby : from_centre) += 1;
        }
      }
    }
    std::cout << "[ pose IK ] " << arm.model << ": converged " << from_centre << "/" << trials
              << " from the centre, " << from_nearby << "/" << trials << " from a nearby seed\n";
    // from the centre a local solver can land in another basin (that is what restarts are for)
    EXPECT_GE(from_nearby, 98);
    EXPECT_GE(from_centre, 75);
  }
}

TEST(PoseIk, ConvergesQuadraticallyNearTheTarget) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  ChainKinematics fk(chain);
  std::mt19937 rng(4);
  const Eigen::VectorXd q_true = test::random_q(chain, rng, 0.1);
  const Pose X_WT = fk.update(q_true);
  PoseIkOptions options;
  options.position_tolerance = 1e-12;
  options.orientation_tolerance = 1e-12;
  PoseIk ik(chain, options);
  const IkResult r = ik.solve(X_WT, test::perturb(chain, q_true, rng, 0.05));
  EXPECT_TRUE(r.ok());
  EXPECT_LE(r.iterations, 8);  // Newton-like: a handful of iterations down to 1e-12
}

TEST(PoseIk, WeightsTradePositionAgainstOrientation) {
  // the tricky arm has 5 joints: a generic pose is out of reach, the weights pick the compromise
  const Robot robot = Robot::from_string(test::kTrickyArm);
  const Chain chain(robot, "tool");
  ChainKinematics fk(chain);
  std::mt19937 rng(8);
  const Eigen::VectorXd q0 = test::random_q(chain, rng, 0.2);
  Pose X_WT = fk.update(q0);
  X_WT.R = X_WT.R *
           Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  X_WT.p += Eigen::Vector3d(0.03, -0.02, 0.04);
  PoseIkOptions favour_position, favour_orientation;
  favour_position.orientation_weight = 0.01;
  favour_orientation.position_weight = 0.01;
  const IkResult a = PoseIk(chain, favour_position).solve(X_WT, q0);
  const IkResult b = PoseIk(chain, favour_orientation).solve(X_WT, q0);
  EXPECT_EQ(a.status, IkStatus::not_converged);
  EXPECT_EQ(b.status, IkStatus::not_converged);
  EXPECT_LT(a.position_error, 0.5 * b.position_error);
  EXPECT_LT(b.orientation_error, 0.5 * a.orientation_error);
}

TEST(PoseIk, UnreachableTargetReturnsBestIterateWithoutThrowing) {
  const Robot robot = Robot::bundled("ur5e");
  const Chain chain(robot, "attachment_site");
  PoseIk ik(chain);
  const Pose X_WT = Pose::from_rpy(Eigen::Vector3d(3.0, 1.0, 0.5), Eigen::Vector3d(0.1, 0.2, 0.3));
  IkResult r;
  ASSERT_NO_THROW(r = ik.solve(X_WT, chain.center()));
  EXPECT_EQ(r.status, IkStatus::not_converged);
  EXPECT_GT(r.position_error, 2.0);  // the UR5e reaches about 0.85 m from its shoulder
  EXPECT_TRUE(chain.within_limits(r.q));
  ChainKinematics fk(chain);
  EXPECT_NEAR(r.position_error, frame_errors(fk.update(r.q), X_WT).position, 1e-12);
}

TEST(PoseIk, InvalidInputThrows) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  PoseIk ik(chain);
  const Eigen::VectorXd q = chain.center();
  Pose X_WT = Pose::from_rpy(Eigen::Vector3d(0.4, 0.0, 0.4), Eigen::Vector3d(3.1, 0.0, 0.0));
  Pose bad = X_WT;
  bad.p.z() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ik.solve(bad, q), Error);
  bad = X_WT;
  bad.R(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ik.solve(bad, q), Error);
  bad = X_WT;
  bad.R *= 1.1;  // not a rotation
  EXPECT_THROW(ik.solve(bad, q), Error);
  EXPECT_THROW(ik.solve(X_WT, Eigen::VectorXd::Zero(6)), Error);
  PoseIkOptions options;
  options.orientation_weight = 0.0;
  EXPECT_THROW(PoseIk(chain, options), Error);
  options = {};
  options.posture.q_pref = Eigen::VectorXd::Zero(3);
  options.posture.gain = 0.1;
  EXPECT_THROW(PoseIk(chain, options), Error);
}

TEST(PoseIk, LimitsRespectedAndDeterministic) {
  const Robot robot = Robot::bundled("iiwa14");
  const Chain chain(robot, "attachment_site");
  PoseIk a(chain), b(chain);
  std::mt19937 rng(30);
  std::uniform_real_distribution<double> box(-1.5, 1.5);
  for (int t = 0; t < 30; ++t) {
    const Pose X_WT = Pose::from_rpy(Eigen::Vector3d(box(rng), box(rng), box(rng) + 0.5),
                                     Eigen::Vector3d(box(rng), box(rng), box(rng)));
    const Eigen::VectorXd seed = test::random_q(chain, rng);
    const IkResult r1 = a.solve(X_WT, seed);
    const IkResult r2 = b.solve(X_WT, seed);
    EXPECT_TRUE(chain.within_limits(r1.q));
    EXPECT_EQ(std::memcmp(r1.q.data(), r2.q.data(), sizeof(double) * r1.q.size()), 0);
    EXPECT_EQ(r1.iterations, r2.iterations);
    EXPECT_NE(r1.status, IkStatus::invalid_input);
  }
}

TEST(PoseIk, CallerDataIsUntouched) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  // the collision hook works on its own scratch data, never on the caller's
  PoseIkOptions options;
  options.collision.pairs = {{"link7", "link0"}};
  options.collision.geoms = {"flange"};
  CollisionGuard guard(chain, options.collision);
  std::mt19937 rng(12);
  Eigen::VectorXd q_start, q_goal;
  do {
    q_start = test::random_q(chain, rng, 0.1);
    q_goal = test::perturb(chain, q_start, rng, 0.2);
  } while (guard.in_contact(q_start) || guard.in_contact(q_goal));
  DataPtr d = robot.make_data();
  chain.scatter(q_start, d->qpos);
  mj_forward(&robot.model(), d.get());
  const std::vector<unsigned char> before(static_cast<unsigned char*>(d->buffer),
                                          static_cast<unsigned char*>(d->buffer) + d->nbuffer);
  ChainKinematics fk(chain);
  const IkResult r = PoseIk(chain, options).solve(fk.update(q_goal), chain.gather(d->qpos));
  EXPECT_NE(r.status, IkStatus::invalid_input);
  EXPECT_FALSE(guard.in_contact(r.q));
  EXPECT_EQ(std::memcmp(before.data(), d->buffer, before.size()), 0);
}

TEST(PoseIk, PostureActsInTheNullSpace) {
  // panda: 7 joints for a 6-D pose leave one self-motion for the posture term
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  ChainKinematics fk(chain);
  std::mt19937 rng(2);
  const Eigen::VectorXd q_true = test::random_q(chain, rng, 0.15);
  const Pose X_WT = fk.update(q_true);
  const Eigen::VectorXd seed = test::perturb(chain, q_true, rng, 0.3);
  Eigen::VectorXd q_pref = q_true;
  q_pref[2] += 0.8;  // joint 3 drives the elbow self-motion
  PoseIkOptions with_posture;
  with_posture.posture = {chain.clamp(q_pref), 0.5};
  const IkResult plain = PoseIk(chain).solve(X_WT, seed);
  const IkResult pulled = PoseIk(chain, with_posture).solve(X_WT, seed);
  ASSERT_TRUE(plain.ok());
  ASSERT_TRUE(pulled.ok());
  EXPECT_LE(pulled.position_error, with_posture.position_tolerance);
  EXPECT_LT((pulled.q - with_posture.posture.q_pref).norm(),
            (plain.q - with_posture.posture.q_pref).norm());
}

}  // namespace
}  // namespace mjarm
