// DockingEnvTask: the tasks room's docking as an environment — the start of plan_docking, the
// believed socket drawn from the seed, a scripted insertion that seats the peg and terminates,
// the failures (too much force), truncation, determinism, bad options.

#include "mjarm/env/docking_env_task.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "env/env_test_support.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/env/environment.hpp"

namespace mjarm {
namespace {

const DockingEnvTask& docking(const Environment& env) {
  return static_cast<const DockingEnvTask&>(env.task());
}

/// One docking task with the default options built per test process (its scene, and the IK of
/// its start, take a while under the sanitizers), cloned per environment.
std::unique_ptr<EnvTask> docking_task() {
  static const DockingEnvTask prototype;
  return prototype.clone();
}

/// One with the believed socket on the true one.
std::unique_ptr<EnvTask> aligned_docking_task() {
  static const DockingEnvTask prototype = [] {
    DockingEnvOptions options;
    options.offset_range = {0.0, 0.0, 0.0};
    return DockingEnvTask(options);
  }();
  return prototype.clone();
}

/// A proportional policy on the pose error to the believed seat, its translation clipped to
/// @p max_step per step [m] (the environment's own bound is 20 mm: far too fast for a 0.5 mm
/// clearance).
std::vector<double> insert_action(const Environment& env, double max_step) {
  Vector6d e = 0.3 * task_error(env.context().X_WE, docking(env).believed_seated());
  for (int k = 0; k < 3; ++k) e[k] = std::clamp(e[k], -max_step, max_step);
  return {e.data(), e.data() + 6};
}

TEST(DockingEnvTask, StartsAboveTheSocketAsTheDockingRunAndDrawsTheBelievedSocket) {
  Environment env(docking_task());
  const DockingEnvTask& task = docking(env);
  const DockingPlan plan = plan_docking(task.scene(), DockingOffset{}, task.options().motion);
  for (std::uint64_t seed : {1, 2}) {
    const TimeStep ts = env.reset(seed);
    const std::span<const double> q = ts.observation["joint_positions"];
    for (int i = 0; i < 7; ++i)
      EXPECT_LE(std::abs(q[i] - plan.q_start[i]), task.options().start_perturbation + 1e-12);
    // the believed socket: within the offset range of the true one, shown as `target`
    EXPECT_LE(std::abs(task.offset().dx), task.options().offset_range.dx);
    EXPECT_LE(std::abs(task.offset().dy), task.options().offset_range.dy);
    const Vector6d off = task_error(task.seated(), task.believed_seated());
    EXPECT_NEAR(off.head<2>().norm(), std::hypot(task.offset().dx, task.offset().dy), 1e-12);
    const std::span<const double> target = ts.observation["target"];
    for (int k = 0; k < 3; ++k) EXPECT_EQ(target[k], task.believed_seated().p[k]);
    // the tip starts start_height above the top face (the perturbation moves it by millimetres)
    EXPECT_NEAR(task.insertion()[0], -task.options().motion.start_height, 0.01);
    EXPECT_EQ(task.outcome(), DockingEnvOutcome::running);
  }
  const double dx = task.offset().dx;
  env.reset(1);
  const double dx1 = task.offset().dx;
  env.reset(2);
  EXPECT_EQ(task.offset().dx, dx);  // the seed decides it
  EXPECT_NE(dx1, dx);
}

TEST(DockingEnvTask, AScriptedInsertionSeatsThePegAndTerminates) {
  const DockingEnvOptions options;
  Environment env(aligned_docking_task());  // the believed socket is the true one
  const DockingEnvTask& task = docking(env);
  TimeStep ts = env.reset(3);
  while (!ts.last()) {
    ts = env.step(insert_action(env, 0.002));
    const double tilt = task.insertion()[2];
    EXPECT_DOUBLE_EQ(*ts.reward, -((env.context().X_WE.p - task.seated().p).norm() + 0.05 * tilt));
  }
  EXPECT_EQ(ts.end, EpisodeEnd::terminated);
  EXPECT_EQ(*ts.discount, 0.0);
  EXPECT_EQ(task.outcome(), DockingEnvOutcome::seated);
  const DockingCriteria& c = options.criteria;
  const double full_depth = options.scene.geometry.chamfer + options.scene.geometry.bore_depth;
  EXPECT_GE(task.insertion()[0], full_depth - c.depth_tolerance);
  EXPECT_LE(task.insertion()[1], c.max_lateral);
  EXPECT_LE(task.insertion()[2], c.max_tilt);
  EXPECT_GT(task.sample().contacts, 0);  // resting on the bottom
  EXPECT_LT(env.steps(), 200);           // 60 mm above + 50 mm deep at 2 mm per step, then the hold
}

TEST(DockingEnvTask, RammingThePegInFailsOnTheForce) {
  const DockingEnvOptions options;
  Environment env(aligned_docking_task());
  const DockingEnvTask& task = docking(env);
  TimeStep ts = env.reset(1);
  double peak = 0.0;
  while (!ts.last()) {
    ts = env.step(insert_action(env, 1.0));  // the environment clips to 20 mm per step
    peak = std::max(peak, task.sample().F_peg.head<3>().norm());
  }
  EXPECT_EQ(task.outcome(), DockingEnvOutcome::excess_force);
  EXPECT_GT(peak, options.criteria.max_force);
  EXPECT_EQ(ts.end, EpisodeEnd::terminated);
  EXPECT_EQ(*ts.discount, 0.0);
  const double dense =
      -((env.context().X_WE.p - task.seated().p).norm() + 0.05 * task.insertion()[2]);
  EXPECT_DOUBLE_EQ(*ts.reward, dense - options.failure_penalty);
  EXPECT_EQ(ts.observation.spec().find("wrench"), -1);  // not a default observation
}

TEST(DockingEnvTask, HoveringIsTruncatedAtTheTimeLimitAndTheWrenchIsObservable) {
  EnvironmentOptions o;
  o.time_limit = 0.2;
  o.observations = {"ee_pose", "wrench", "insertion", "sensor:iiwa/peg/ft_force"};
  Environment env(docking_task(), o);
  TimeStep ts = env.reset(4);
  const std::vector<double> zero(6, 0.0);
  while (!ts.last()) ts = env.step(zero);
  EXPECT_EQ(ts.end, EpisodeEnd::truncated);
  EXPECT_EQ(*ts.discount, 1.0);
  EXPECT_EQ(env.steps(), 10);
  EXPECT_EQ(docking(env).outcome(), DockingEnvOutcome::running);
  for (double f : ts.observation["wrench"]) EXPECT_EQ(f, 0.0);  // no contact up there
  // the sensor carries the peg's weight
  const std::span<const double> ft = ts.observation["sensor:iiwa/peg/ft_force"];
  EXPECT_NEAR(std::hypot(ft[0], ft[1], ft[2]), docking(env).scene().peg_mass * 9.81, 0.1);
}

TEST(DockingEnvTask, TheSameSeedAndActionsGiveTheSameStepsBitForBit) {
  auto trace = [](Environment& env) {
    std::vector<double> out;
    TimeStep ts = env.reset(11);
    const std::vector<double> actions = test::uniform_actions(env.action_spec(), 30, 5);
    for (int k = 0; k < 30 && !ts.last(); ++k) {
      ts = env.step(std::span<const double>(actions).subspan(6 * k, 6));
      out.insert(out.end(), ts.observation.values().begin(), ts.observation.values().end());
      out.push_back(*ts.reward);
    }
    return out;
  };
  Environment a(docking_task());
  Environment b(docking_task());
  b.reset(99);  // an earlier episode changes nothing
  const std::vector<double> ta = trace(a), tb = trace(b);
  ASSERT_EQ(ta.size(), tb.size());
  EXPECT_EQ(std::memcmp(ta.data(), tb.data(), ta.size() * sizeof(double)), 0);
}

TEST(DockingEnvTask, BadOptionsAreErrors) {
  DockingEnvOptions o;
  o.scene.ft_sensor = false;
  test::expect_error_containing([&] { DockingEnvTask t(o); }, {"force/torque sensor"});
  o = DockingEnvOptions{};
  o.start_perturbation = -0.1;
  test::expect_error_containing([&] { DockingEnvTask t(o); }, {"start_perturbation"});
  o = DockingEnvOptions{};
  o.offset_range.dx = 0.2;
  test::expect_error_containing([&] { DockingEnvTask t(o); }, {"offset_range"});
  o = DockingEnvOptions{};
  o.criteria.max_force = 0.0;
  test::expect_error_containing([&] { DockingEnvTask t(o); }, {"max_force"});
  o = DockingEnvOptions{};
  o.seated_time = std::nan("");
  test::expect_error_containing([&] { DockingEnvTask t(o); }, {"seated_time"});
  // an observation the docking does not provide
  EnvironmentOptions e;
  e.observations = {"object_pose"};
  test::expect_error_containing([&] { Environment env(docking_task(), e); },
                                {"'object_pose' is switched off", "docking"});
}

}  // namespace
}  // namespace mjarm
