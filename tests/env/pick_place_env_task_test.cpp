// PickPlaceEnvTask: the tasks room's pick and place as an environment — the draws of
// draw_pick_place_trial for a seed, the gripper entry of the action, a scripted pick and place
// that ends placed, the failures (the robot on the table), truncation, determinism on one and
// two threads, no allocation per step, bad input.

#include "mjarm/env/pick_place_env_task.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "env/env_test_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/env/vector_environment.hpp"

namespace mjarm {
namespace {

const PickPlaceEnvTask& pick_place(const Environment& env) {
  return static_cast<const PickPlaceEnvTask&>(env.task());
}

/// One pick-and-place task built per test process (its scene compiles in a fraction of a
/// second), cloned per environment.
std::unique_ptr<EnvTask> pick_place_task() {
  static const PickPlaceEnvTask prototype;
  return prototype.clone();
}

/// A scripted pick and place on the environment's actions: above the cube, down, close, lift,
/// across, down, open — each stage a proportional step (0.3 × the pose error, translation
/// clipped to 4 mm per step) towards its tool pose, the next once within 2 mm.
class ScriptedPickPlace {
 public:
  explicit ScriptedPickPlace(const Environment& env)
      : env_(env),
        R_(grasp_rotation(env.context().X_WE.R, grasp_yaw(pick_place(env).trial().object))),
        object_(pick_place(env).object_pose().p),
        target_(pick_place(env).target()) {}

  std::vector<double> action() const {
    Vector6d e = 0.3 * task_error(env_.context().X_WE, Pose{R_, stop()});
    for (int k = 0; k < 3; ++k) e[k] = std::clamp(e[k], -0.004, 0.004);
    std::vector<double> a(e.data(), e.data() + 6);
    a.push_back(stage_ >= 2 && stage_ <= 5 ? 1.0 : 0.0);  // closed from the grasp to the place
    return a;
  }
  /// After the step: moves on when the stage is done (the grasp: after 30 steps, 0.6 s).
  void advance() {
    ++count_;
    const bool at = (env_.context().X_WE.p - stop()).norm() < 0.002 && count_ > 5;
    if ((stage_ == 2 && count_ >= 30) || (stage_ != 2 && stage_ < 6 && at)) {
      ++stage_;
      count_ = 0;
    }
  }
  int stage() const noexcept { return stage_; }

 private:
  /// The tool position of the stage: above the cube, at it (grasp: the same), lifted, above
  /// the target, down (release: the same).
  Eigen::Vector3d stop() const {
    const double heights[] = {0.05, 0.01, 0.01, 0.12, 0.12, 0.012, 0.012};
    return (stage_ <= 3 ? object_ : target_) + Eigen::Vector3d(0.0, 0.0, heights[stage_]);
  }

  const Environment& env_;
  Eigen::Matrix3d R_;
  Eigen::Vector3d object_, target_;
  int stage_ = 0;
  int count_ = 0;
};

TEST(PickPlaceEnvTask, TheSeedDrawsTheTasksRoomsTrialAndTheActionEndsWithTheGripper) {
  Environment env(pick_place_task());
  const ArraySpec& spec = env.action_spec();
  ASSERT_EQ(spec.size(), 7);  // the tool's six, then the gripper
  EXPECT_EQ(spec.minimum[6], 0.0);
  EXPECT_EQ(spec.maximum[6], 1.0);
  for (std::uint64_t seed : {1, 9}) {
    PickPlaceOptions draw;
    draw.robot = "panda_hand";
    draw.seed = seed;
    draw.object_half_size = 0.015;
    const PickPlaceTrial trial = draw_pick_place_trial(draw);
    const TimeStep ts = env.reset(seed);
    const std::span<const double> object = ts.observation["object_pose"];
    EXPECT_EQ(object[0], trial.object.position[0]);
    EXPECT_EQ(object[1], trial.object.position[1]);
    EXPECT_NEAR(2.0 * std::atan2(object[6], object[3]), trial.object.yaw, 1e-12);
    const std::span<const double> target = ts.observation["target"];
    EXPECT_EQ(target[0], trial.target[0]);
    EXPECT_EQ(target[1], trial.target[1]);
    EXPECT_DOUBLE_EQ(target[2], pick_place(env).scene().table_height + 0.015);
    const std::span<const double> grasp = ts.observation["grasp"];
    EXPECT_GT(grasp[0], 0.0);  // the fingers open
    EXPECT_EQ(grasp[1] + grasp[2], 0.0);
  }
}

TEST(PickPlaceEnvTask, AScriptedPickAndPlacePlacesTheCubeAndTerminates) {
  Environment env(pick_place_task());
  const PickPlaceEnvTask& task = pick_place(env);
  TimeStep ts = env.reset(1);
  ScriptedPickPlace policy(env);
  bool squeezed = false;
  while (!ts.last()) {
    ts = env.step(policy.action());
    policy.advance();
    const Eigen::Vector3d o = task.object_pose().p;
    EXPECT_DOUBLE_EQ(*ts.reward, -((env.context().X_WE.p - o).norm() + (o - task.target()).norm()));
    // lifted between the fingers, with both touching and the set squeeze
    if (policy.stage() == 4 && ts.observation["grasp"][1] == 1.0 &&
        ts.observation["grasp"][2] == 1.0)
      squeezed = squeezed || std::abs(task.grasp()->force - 8.0) < 2.0;
  }
  EXPECT_TRUE(squeezed);
  EXPECT_EQ(task.outcome(), PickPlaceEnvOutcome::placed);
  EXPECT_EQ(ts.end, EpisodeEnd::terminated);
  EXPECT_EQ(*ts.discount, 0.0);
  const Eigen::Vector3d o = task.object_pose().p;
  EXPECT_LE(std::hypot(o.x() - task.target().x(), o.y() - task.target().y()),
            task.options().criteria.placement_tolerance);
  EXPECT_EQ(policy.stage(), 6);
}

TEST(PickPlaceEnvTask, TheToolOnTheTableFailsTheEpisode) {
  Environment env(pick_place_task());
  const PickPlaceEnvTask& task = pick_place(env);
  TimeStep ts = env.reset(2);
  const std::vector<double> down{0.0, 0.0, -0.01, 0.0, 0.0, 0.0, 0.0};
  while (!ts.last()) ts = env.step(down);
  EXPECT_EQ(task.outcome(), PickPlaceEnvOutcome::table_contact);
  EXPECT_EQ(ts.end, EpisodeEnd::terminated);
  EXPECT_EQ(*ts.discount, 0.0);
  const Eigen::Vector3d o = task.object_pose().p;
  EXPECT_DOUBLE_EQ(*ts.reward, -((env.context().X_WE.p - o).norm() + (o - task.target()).norm()) -
                                   task.options().failure_penalty);
}

TEST(PickPlaceEnvTask, AZeroPolicyIsTruncatedWithTheCubeWhereItWas) {
  EnvironmentOptions o;
  o.time_limit = 0.2;
  Environment env(pick_place_task(), o);
  TimeStep ts = env.reset(3);
  const std::vector<double> zero(7, 0.0);
  const std::vector<double> start(ts.observation["object_pose"].begin(),
                                  ts.observation["object_pose"].end());
  while (!ts.last()) ts = env.step(zero);
  EXPECT_EQ(ts.end, EpisodeEnd::truncated);
  EXPECT_EQ(*ts.discount, 1.0);
  EXPECT_EQ(pick_place(env).outcome(), PickPlaceEnvOutcome::running);
  const std::span<const double> end = ts.observation["object_pose"];
  // resting on the table: it settles into the soft contact by about 0.1 mm, no more
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(end[k], start[k], 0.5e-3);
}

TEST(PickPlaceEnvTask, TheSameSeedGivesTheSameBatchOnOneAndTwoThreads) {
  EnvironmentOptions o;
  o.seed = 5;
  VectorEnvironment one(pick_place_task(), o, 2, 1);
  VectorEnvironment two(pick_place_task(), o, 2, 2);
  const std::vector<double> actions = test::uniform_actions(one.action_spec(), 2 * 15, 8);
  one.reset();
  two.reset();
  for (int k = 0; k < 15; ++k) {
    const std::span<const double> row = std::span<const double>(actions).subspan(14 * k, 14);
    one.step(row);
    two.step(row);
  }
  ASSERT_EQ(one.observations().size(), two.observations().size());
  EXPECT_EQ(std::memcmp(one.observations().data(), two.observations().data(),
                        one.observations().size_bytes()),
            0);
  EXPECT_EQ(std::memcmp(one.rewards().data(), two.rewards().data(), one.rewards().size_bytes()), 0);
}

TEST(PickPlaceEnvTask, StepAllocatesNothing) {
  Environment env(pick_place_task());
  const std::vector<double> actions = test::uniform_actions(env.action_spec(), 20, 4);
  env.reset(1);
  env.step(std::span<const double>(actions).subspan(0, 7));
  const std::uint64_t before = test::malloc_calls();
  for (std::size_t k = 1; k < 20; ++k) env.step(std::span<const double>(actions).subspan(7 * k, 7));
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(PickPlaceEnvTask, BadInputIsAnError) {
  PickPlaceEnvOptions o;
  o.robot = "ur5";
  test::expect_error_containing([&] { PickPlaceEnvTask t(o); },
                                {"unknown robot 'ur5'", "panda_hand"});
  o = PickPlaceEnvOptions{};
  o.object_half_size = -0.01;
  test::expect_error_containing([&] { PickPlaceEnvTask t(o); }, {"object_half_size"});
  o = PickPlaceEnvOptions{};
  o.grasp_force = 0.0;
  test::expect_error_containing([&] { PickPlaceEnvTask t(o); }, {"grasp_force"});
  o = PickPlaceEnvOptions{};
  o.ranges.yaw = {1.0, -1.0};
  test::expect_error_containing([&] { PickPlaceEnvTask t(o); }, {"yaw"});
  // the gripper entry is checked like the others: a NaN is an error, a value out of [0, 1] is
  // clipped and counted
  Environment env(pick_place_task());
  env.reset(1);
  std::vector<double> a(7, 0.0);
  a[6] = std::nan("");
  test::expect_error_containing([&] { env.step(a); }, {"action[6]", "finite"});
  a[6] = 2.0;
  env.step(a);
  EXPECT_EQ(env.action_driver().reference().gripper, 1.0);
  EXPECT_EQ(env.episode_clips().values, 1);
  test::expect_error_containing([&] { env.step(std::vector<double>(6, 0.0)); },
                                {"needs 7 values, got 6"});
}

}  // namespace
}  // namespace mjarm
