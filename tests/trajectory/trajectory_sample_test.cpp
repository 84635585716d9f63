// trajectory_sample.hpp and pose_sample.hpp: every profile of the room meets its concept, and
// each one's at(t, sample) is its own sample, written without allocating once the sample is
// sized.

#include "mjarm/trajectory/trajectory_sample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/trajectory/cartesian_trapezoid.hpp"
#include "mjarm/trajectory/joint_move.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/pose_sample.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/smooth_ramp_trajectory.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {
namespace {

// n coordinates
static_assert(TrajectoryProfile<SyncedTrapezoid>);
static_assert(TrajectoryProfile<QuinticTrajectory>);
static_assert(TrajectoryProfile<SmoothRampTrajectory>);
static_assert(TrajectoryProfile<JerkLimitedGenerator>);
static_assert(TrajectoryProfile<JointMove>);
// one coordinate
static_assert(TrajectoryProfile<TrapezoidProfile>);
static_assert(TrajectoryProfile<Quintic>);
static_assert(TrajectoryProfile<SmoothRamp>);
static_assert(TrajectoryProfile<JerkProfile>);
// SE(3)
static_assert(PoseProfile<Se3Interpolation>);
static_assert(PoseProfile<CartesianTrapezoid>);
static_assert(!TrajectoryProfile<Se3Interpolation>);
static_assert(!PoseProfile<SyncedTrapezoid>);

const Eigen::VectorXd kSampleStart = Eigen::VectorXd::LinSpaced(3, -0.4, 0.6);
const Eigen::VectorXd kSampleGoal = Eigen::VectorXd::LinSpaced(3, 0.5, -0.2);

// every sample of @p profile at a few instants, through the concept
template <TrajectoryProfile P>
std::vector<TrajectorySample> samples_of(const P& profile) {
  std::vector<TrajectorySample> out;
  for (int k = 0; k <= 10; ++k) out.push_back(sample_at(profile, 0.1 * k * profile.duration()));
  return out;
}

TEST(TrajectorySample, SizedSamplesStartAtZeroAndResize) {
  const TrajectorySample s(4);
  EXPECT_EQ(s.size(), 4);
  EXPECT_TRUE(s.position.isZero() && s.velocity.isZero() && s.acceleration.isZero() &&
              s.jerk.isZero());
  TrajectorySample empty;
  EXPECT_EQ(empty.size(), 0);
  const SyncedTrapezoid trap(kSampleStart, kSampleGoal, 1.0, 2.0);
  trap.at(0.3, empty);  // an unsized sample is sized by the profile
  EXPECT_EQ(empty.size(), 3);
  EXPECT_EQ(empty.jerk.size(), 3);
}

TEST(TrajectorySample, NAxisProfilesWriteTheirOwnSamples) {
  const SyncedTrapezoid trap(kSampleStart, kSampleGoal, 1.0, 2.0);
  const QuinticTrajectory quintic(
      {kSampleStart, Eigen::VectorXd::Constant(3, 0.2), Eigen::VectorXd::Zero(3)},
      {kSampleGoal, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3)}, 1.1);
  Eigen::VectorXd q(3), qd(3), qdd(3), qddd(3);
  for (const TrajectorySample& s : samples_of(trap)) EXPECT_EQ(s.size(), 3);
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.13 * k;
    const TrajectorySample a = sample_at(trap, t);
    trap.at(t, q, qd, qdd);
    EXPECT_EQ(a.position, q);
    EXPECT_EQ(a.velocity, qd);
    EXPECT_EQ(a.acceleration, qdd);
    EXPECT_TRUE(a.jerk.isZero());  // the acceleration steps
    const TrajectorySample b = sample_at(quintic, t);
    quintic.at(t, q, qd, qdd, qddd);
    EXPECT_EQ(b.position, q);
    EXPECT_EQ(b.velocity, qd);
    EXPECT_EQ(b.acceleration, qdd);
    EXPECT_EQ(b.jerk, qddd);
  }
}

TEST(TrajectorySample, TheGeneratorSamplesEachDofAndStopsItsJerkAtTheEnd) {
  const std::vector<JerkLimits> limits(2, {1.0, 2.0, 10.0});
  JerkLimitedGenerator otg(limits);
  const std::vector<KinematicState> start{{0.0, 0.3, 0.0}, {1.0, 0.0, 0.5}};
  const std::vector<KinematicState> target{{0.8, 0.0, 0.0}, {0.2, 0.0, 0.0}};
  ASSERT_EQ(otg.calculate(start, target).status, OtgStatus::working);
  std::vector<JerkSample> own(2);
  TrajectorySample s;
  for (int k = 0; k <= 20; ++k) {
    const double t = 0.05 * k * otg.duration();
    otg.at(t, own);
    otg.at(t, s);
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(s.position[i], own[static_cast<std::size_t>(i)].p);
      EXPECT_EQ(s.velocity[i], own[static_cast<std::size_t>(i)].v);
      EXPECT_EQ(s.acceleration[i], own[static_cast<std::size_t>(i)].a);
      EXPECT_EQ(s.jerk[i], own[static_cast<std::size_t>(i)].j);
    }
  }
  otg.at(otg.duration() + 0.5, s);
  EXPECT_TRUE(s.jerk.isZero());
  EXPECT_NEAR(s.position[0], 0.8, 1e-9);
  EXPECT_NEAR(s.velocity[1], 0.0, 1e-9);
}

TEST(TrajectorySample, OneCoordinateProfilesWriteTheirOwnSamples) {
  const TrapezoidProfile trap = trap_profile(0.4);
  const Quintic quintic({0.0, 0.5, 0.0}, {1.0, 0.0, 0.0}, 1.5);
  const SmoothRamp ramp(SmoothRamp::Kind::smootherstep, 0.8);
  JerkProfile jerk;
  jerk.reset({0.0, 0.0, 0.0});
  jerk.append(2.0, 0.3);
  jerk.append(-2.0, 0.3);
  TrajectorySample s;
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.07 * k;
    trap.at(t, s);
    ASSERT_EQ(s.size(), 1);
    EXPECT_EQ(s.position[0], trap.at(t).position);
    EXPECT_EQ(s.velocity[0], trap.at(t).velocity);
    EXPECT_EQ(s.acceleration[0], trap.at(t).acceleration);
    EXPECT_EQ(s.jerk[0], 0.0);
    quintic.at(t, s);
    EXPECT_EQ(s.position[0], quintic.at(t).p);
    EXPECT_EQ(s.jerk[0], quintic.at(t).j);
    ramp.at(t, s);
    EXPECT_EQ(s.position[0], ramp.at(t).s);
    EXPECT_EQ(s.acceleration[0], ramp.at(t).dds);
    EXPECT_EQ(s.jerk[0], ramp.at(t).ddds);
    jerk.at(t, s);
    EXPECT_EQ(s.velocity[0], jerk.at(t).v);
    EXPECT_EQ(s.jerk[0], jerk.at(t).j);
  }
}

TEST(TrajectorySample, PoseProfilesShareOneSample) {
  Pose X1;
  X1.p << 0.3, -0.2, 0.4;
  const Se3Interpolation se3(Pose::identity(), Vector6d::Zero(), Vector6d::Zero(), X1, 0.9);
  const CartesianTrapezoid line(Pose::identity(), X1);
  const PoseSample a = se3.at(0.45), b = line.at(0.5 * line.duration());
  EXPECT_GT(a.V_WE.head<3>().norm(), 0.0);
  EXPECT_GT(b.V_WE.head<3>().norm(), 0.0);
  EXPECT_TRUE(se3.at(se3.duration()).X_WE.p.isApprox(X1.p, 1e-12));
  EXPECT_TRUE(line.at(line.duration()).X_WE.p.isApprox(X1.p, 1e-12));
}

TEST(TrajectorySample, SamplingASizedSampleAllocatesNothing) {
  const SyncedTrapezoid trap(kSampleStart, kSampleGoal, 1.0, 2.0);
  const QuinticTrajectory quintic(
      {kSampleStart, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3)},
      {kSampleGoal, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3)}, 1.1);
  const SmoothRampTrajectory ramp(SmoothRamp::Kind::smoothstep, kSampleStart, kSampleGoal, 0.7);
  JointMoveRequest request;
  request.start = kSampleStart;
  request.target = kSampleGoal;
  request.max_velocity = Eigen::VectorXd::Constant(3, 1.0);
  request.max_acceleration = Eigen::VectorXd::Constant(3, 2.0);
  request.max_jerk = Eigen::VectorXd::Constant(3, 20.0);
  const JointMove move(ProfileKind::jerk_limited, request);
  const Quintic one({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 1.0);
  TrajectorySample s(3), scalar(1);
  double sink = 0.0;
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 50; ++k) {
    const double t = 0.03 * k;
    trap.at(t, s);
    sink += s.velocity.sum();
    quintic.at(t, s);
    sink += s.jerk.sum();
    ramp.at(t, s);
    sink += s.acceleration.sum();
    move.at(t, s);
    sink += s.position.sum();
    one.at(t, scalar);
    sink += scalar.position[0];
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace mjarm
