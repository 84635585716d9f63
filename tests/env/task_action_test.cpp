// A task's own action (EnvTask::action_spec / map_action): any bounded array, mapped each step
// onto the environment's action space, checked and clipped like a space's own.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "env/env_test_support.hpp"
#include "mjarm/env/environment.hpp"

namespace mjarm {
namespace {

// one knob in [-1, 1] that turns the first joint: τ = (5·knob, 0) in the joint_torques space;
// a knob past `broken_above` maps to NaN (a broken mapping)
class KnobTask final : public EnvTask {
 public:
  explicit KnobTask(bool bounded = true) : hooks_(nullptr, -1), bounded_(bounded) {}
  std::unique_ptr<EnvTask> clone() const override { return std::make_unique<KnobTask>(*this); }
  std::string_view name() const noexcept override { return "knob"; }
  std::string_view description() const noexcept override { return "turns the first joint"; }
  const Robot& robot() const noexcept override { return hooks_.robot(); }
  const Chain& chain() const noexcept override { return hooks_.chain(); }
  void initialize_episode(Simulation& sim, EpisodeRandom& random) override {
    hooks_.initialize_episode(sim, random);
  }
  double reward(const StepContext&) const noexcept override { return 0.0; }

  std::optional<ArraySpec> action_spec() const override {
    const double inf = std::numeric_limits<double>::infinity();
    return bounded_ ? ArraySpec::bounded("knob", Eigen::VectorXd::Constant(1, -1.0),
                                         Eigen::VectorXd::Constant(1, 1.0))
                    : ArraySpec::bounded("knob", Eigen::VectorXd::Constant(1, -inf),
                                         Eigen::VectorXd::Constant(1, inf));
  }
  void map_action(const StepContext&, std::span<const double> action,
                  std::span<double> space_action) noexcept override {
    mapped = action[0];
    space_action[0] = broken ? std::nan("") : 5.0 * action[0];
    space_action[1] = 0.0;
  }

  double mapped = 0.0;  // the knob map_action saw
  bool broken = false;

 private:
  test::HookTask hooks_;
  bool bounded_;
};

EnvironmentOptions torque_options() {
  EnvironmentOptions o;
  o.action_space = ActionSpace::joint_torques;
  o.time_limit = 1.0;
  return o;
}

double first_joint_after(Environment& env, double knob, int steps) {
  env.reset(7);
  const double knob_action[] = {knob};
  for (int k = 0; k < steps; ++k) env.step(knob_action);
  return env.simulation().data().qpos[0];
}

TEST(TaskAction, TheTasksActionIsWhatAgentsGiveAndItsMappingDrivesTheArm) {
  auto task = std::make_unique<KnobTask>();
  KnobTask& knob = *task;
  Environment env(std::move(task), torque_options());
  ASSERT_EQ(env.action_spec().name, "knob");
  ASSERT_EQ(env.action_spec().size(), 1);
  EXPECT_GT(first_joint_after(env, 1.0, 10), 0.01) << "a positive knob turns j1 forward";
  EXPECT_LT(first_joint_after(env, -1.0, 10), -0.01) << "and a negative one backward";
  EXPECT_DOUBLE_EQ(first_joint_after(env, 0.0, 10), 0.0);
  // clipped into the task's bounds before the mapping, and counted
  env.reset(7);
  const double too_far[] = {3.0};
  env.step(too_far);
  EXPECT_DOUBLE_EQ(knob.mapped, 1.0);
  EXPECT_EQ(env.episode_clips().values, 1);
  // a broken mapping commands nothing rather than a NaN torque
  knob.broken = true;
  EXPECT_DOUBLE_EQ(first_joint_after(env, 1.0, 5), 0.0);
  EXPECT_TRUE(std::isfinite(env.simulation().data().qpos[1]));
}

TEST(TaskAction, BadActionsNameTheTasksActionAndAnUnboundedOneIsRefused) {
  Environment env(std::make_unique<KnobTask>(), torque_options());
  env.reset(1);
  const double two[] = {0.0, 0.0};
  test::expect_error_containing([&] { env.step(two); },
                                {"the task's action 'knob'", "needs 1 values, got 2"});
  const double nan[] = {std::nan("")};
  test::expect_error_containing([&] { env.step(nan); }, {"action[0]", "the task's action"});
  test::expect_error_containing(
      [] { Environment unbounded(std::make_unique<KnobTask>(false), torque_options()); },
      {"the task's action 'knob' needs finite bounds"});
}

}  // namespace
}  // namespace mjarm
