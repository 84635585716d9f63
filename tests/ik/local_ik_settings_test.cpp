#include "mjarm/ik/local_ik_settings.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "ik/local_ik_support.hpp"
#include "mjarm/ik/multi_target_ik.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

// The tuning of each solver: the numbers docs/ik.md's figures were measured with.
TEST(LocalIkSettings, EachSolverKeepsItsTuning) {
  const PositionIkOptions position;
  EXPECT_EQ(position.damping, 0.02);
  EXPECT_EQ(position.step, 0.6);
  EXPECT_EQ(position.limits.centre_gain, 0.05);
  EXPECT_EQ(position.limits.repulsion_gain, 0.2);
  EXPECT_EQ(position.limits.repulsion_zone, 0.15);
  EXPECT_EQ(position.max_iterations, 300);
  EXPECT_EQ(position.stall_iterations, 60);
  EXPECT_EQ(position.tolerance, 1e-4);

  const PoseIkOptions pose;
  EXPECT_EQ(pose.damping, 1e-3);
  EXPECT_EQ(pose.step, 1.0);
  EXPECT_EQ(pose.limits.centre_gain, 0.0);
  EXPECT_EQ(pose.limits.repulsion_gain, 0.0);
  EXPECT_EQ(pose.max_iterations, 200);
  EXPECT_EQ(pose.stall_iterations, 30);
  EXPECT_EQ(pose.error_damping, 0.5);
  EXPECT_EQ(pose.orientation_weight, 0.5);

  const MultiTargetIkOptions multi;
  EXPECT_EQ(multi.damping, 1e-3);
  EXPECT_EQ(multi.max_iterations, 300);
  EXPECT_EQ(multi.stall_iterations, 30);
  EXPECT_EQ(multi.mode, MultiTargetMode::prioritized);

  // the rest is shared
  const LocalIkSettings* shared[] = {&position, &pose, &multi};
  for (const LocalIkSettings* s : shared) {
    EXPECT_EQ(s->max_backtracks, 4);
    EXPECT_EQ(s->null_space_damping, 1e-5);
    EXPECT_EQ(s->max_step, 0.5);
    EXPECT_EQ(s->secondary_ratio, 1.0);
    EXPECT_EQ(s->posture.gain, 0.0);
    EXPECT_EQ(s->stall_progress, 1e-4);
    EXPECT_TRUE(s->collision.empty());
    EXPECT_FALSE(s->on_iteration);
  }
}

/// A bad value of one shared field and the message every solver gives for it, after
/// "<solver>: ".
struct BadSetting {
  std::function<void(LocalIkSettings&)> spoil;
  std::string message;
};

std::vector<BadSetting> bad_settings() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {
      {[](LocalIkSettings& s) { s.damping = 0.0; }, "damping must be positive and finite, got 0"},
      {[](LocalIkSettings& s) { s.step = 1.5; }, "step must be in (0, 1], got 1.5"},
      {[](LocalIkSettings& s) { s.max_backtracks = -1; }, "max_backtracks must be ≥ 0, got -1"},
      {[nan](LocalIkSettings& s) { s.null_space_damping = nan; },
       "null_space_damping must be finite and ≥ 0, got nan"},
      {[](LocalIkSettings& s) { s.max_step = -0.1; },
       "max_step must be positive and finite [rad or m], got -0.1"},
      {[](LocalIkSettings& s) { s.secondary_ratio = -1.0; },
       "secondary_ratio must be finite and ≥ 0, got -1"},
      {[](LocalIkSettings& s) { s.limits.centre_gain = -0.5; },
       "limits.centre_gain must be finite and ≥ 0, got -0.5"},
      {[](LocalIkSettings& s) { s.limits.repulsion_zone = 0.7; },
       "limits.repulsion_zone must be in [0, 0.5], got 0.7"},
      {[nan](LocalIkSettings& s) { s.posture.q_pref = Eigen::Vector3d(0.1, nan, 0.2); },
       "posture.q_pref[1] must be finite [rad or m], got nan"},
      {[](LocalIkSettings& s) { s.posture.gain = 2.0; }, "posture.gain must be in [0, 1], got 2"},
      {[](LocalIkSettings& s) { s.max_iterations = 0; }, "max_iterations must be ≥ 1, got 0"},
      {[](LocalIkSettings& s) { s.stall_iterations = 0; }, "stall_iterations must be ≥ 1, got 0"},
      {[](LocalIkSettings& s) { s.stall_progress = 1.0; },
       "stall_progress must be in [0, 1), got 1"},
      {[](LocalIkSettings& s) { s.collision.margin = -0.01; },
       "collision.margin must be finite and ≥ 0 [m], got -0.01"},
      {[](LocalIkSettings& s) { s.collision.max_halvings = -2; },
       "collision.max_halvings must be ≥ 0, got -2"},
  };
}

TEST(LocalIkSettings, EverySolverRejectsABadSharedFieldInOneWording) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  std::vector<std::string> joints;
  for (int i = 1; i <= 7; ++i) joints.push_back("joint" + std::to_string(i));
  std::vector<FrameTarget> targets(1);
  targets[0].frame = "attachment_site";
  for (const BadSetting& bad : bad_settings()) {
    PositionIkOptions position;
    bad.spoil(position);
    EXPECT_EQ(test::error_of([&] { PositionIk ik(chain, position); }),
              "position IK: " + bad.message);
    PoseIkOptions pose;
    bad.spoil(pose);
    EXPECT_EQ(test::error_of([&] { PoseIk ik(chain, pose); }), "pose IK: " + bad.message);
    MultiTargetIkOptions multi;
    bad.spoil(multi);
    EXPECT_EQ(test::error_of([&] { MultiTargetIk ik(robot, joints, targets, multi); }),
              "multi-target IK: " + bad.message);
    LocalIkSettings settings;
    bad.spoil(settings);
    EXPECT_EQ(test::error_of([&] { check_fields(settings, "my IK"); }), "my IK: " + bad.message);
  }
}

TEST(LocalIkSettings, SolverFieldsUseTheSameWording) {
  PositionIkOptions position;
  position.tolerance = 0.0;
  EXPECT_EQ(test::error_of([&] { check(position); }),
            "position IK: tolerance must be positive and finite [m], got 0");
  PoseIkOptions pose;
  pose.orientation_weight = -1.0;
  EXPECT_EQ(test::error_of([&] { check(pose); }),
            "pose IK: orientation_weight must be positive and finite [1/rad], got -1");
  MultiTargetIkOptions multi;
  multi.error_damping = std::numeric_limits<double>::infinity();
  EXPECT_EQ(test::error_of([&] { check(multi); }),
            "multi-target IK: error_damping must be finite and ≥ 0, got inf");
  multi.error_damping = 0.5;
  multi.mode = static_cast<MultiTargetMode>(7);
  EXPECT_EQ(test::error_of([&] { check(multi); }),
            "multi-target IK: mode holds 7, which names no value");
  EXPECT_STREQ(to_string(MultiTargetMode::stacked), "stacked");
}

// The structs' own checks, outside a solver's options, keep their names.
TEST(LocalIkSettings, NestedStructsAloneNameThemselves) {
  const Chain chain(Robot::bundled("panda"), "attachment_site");
  EXPECT_EQ(test::error_of([] {
              check(LimitBias{-1.0, 0.0, 0.15});
            }),
            "limit bias: centre_gain must be finite and ≥ 0, got -1");
  EXPECT_EQ(test::error_of([&] {
              resolve_posture(chain, Posture{{}, -0.5});
            }),
            "posture: gain must be in [0, 1], got -0.5");
  EXPECT_EQ(test::error_of([&] {
              CollisionGuard(chain, CollisionSpec{{}, {}, 0.0, -1});
            }),
            "collision: max_halvings must be ≥ 0, got -1");
}

}  // namespace
}  // namespace mjarm
