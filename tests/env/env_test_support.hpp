#pragma once
// Shared pieces of the environment tests: the reach task built once (its scene compiles in
// ~0.1 s) and cloned per test, random actions, and HookTask — a small task on a two-joint arm
// with a free box that records its hooks, provides `object_pose` and can terminate on demand.

#include <gtest/gtest.h>

#include <initializer_list>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "mjarm/env/env_task.hpp"
#include "mjarm/env/reach_task.hpp"
#include "support/error_message.hpp"

namespace mjarm::test {

/// Expects @p f to throw an mjarm::Error whose message holds every one of @p parts.
template <class F>
void expect_error_containing(F&& f, std::initializer_list<const char*> parts) {
  const std::string message = error_of(f);
  for (const char* part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

/// A clone of one reach task built once per test process.
inline std::unique_ptr<EnvTask> reach_task() {
  static const ReachTask prototype;
  return prototype.clone();
}

/// @p rows actions uniform within @p spec's bounds (finite bounds assumed).
inline std::vector<double> uniform_actions(const ArraySpec& spec, std::size_t rows,
                                           std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::size_t width = static_cast<std::size_t>(spec.size());
  std::vector<double> actions(rows * width);
  for (std::size_t k = 0; k < actions.size(); ++k) {
    const Eigen::Index j = static_cast<Eigen::Index>(k % width);
    actions[k] = EpisodeRandom::uniform(rng, spec.minimum[j], spec.maximum[j]);
  }
  return actions;
}

inline constexpr const char* kHookArm = R"(
<mujoco model="hook_arm">
  <compiler autolimits="true"/>
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="base" pos="0 0 0.5">
      <joint name="j1" axis="0 0 1" range="-3 3" damping="0.2"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="1"/>
      <body name="l2" pos="0.3 0 0">
        <joint name="j2" axis="0 1 0" range="-2 2" damping="0.2"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="0.5"/>
        <site name="tip" pos="0.3 0 0"/>
      </body>
    </body>
    <body name="box" pos="0.5 0.5 0.05">
      <freejoint name="box_free"/>
      <geom name="box_geom" type="box" size="0.05 0.05 0.05" mass="0.2"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="m1" joint="j1" ctrllimited="true" ctrlrange="-20 20"/>
    <motor name="m2" joint="j2" ctrllimited="true" ctrlrange="-20 20"/>
  </actuator>
  <sensor>
    <jointpos name="j1_pos" joint="j1"/>
    <touch name="never" site="tip"/>
  </sensor>
</mujoco>)";

/// A task that writes down its hooks ("init", "before", "after", "observe", "reward",
/// "terminated"), provides `object_pose` (the box's free joint) and terminates at step
/// `terminate_at` (never when −1). Its log allocates: not for allocation tests.
class HookTask final : public EnvTask {
 public:
  explicit HookTask(std::shared_ptr<std::vector<std::string>> log = nullptr, int terminate_at = -1)
      : robot_(Robot::from_string(kHookArm)),
        chain_(robot_, "tip"),
        log_(std::move(log)),
        terminate_at_(terminate_at) {}

  std::unique_ptr<EnvTask> clone() const override { return std::make_unique<HookTask>(*this); }
  std::string_view name() const noexcept override { return "hooks"; }
  std::string_view description() const noexcept override { return "records its hooks"; }
  const Robot& robot() const noexcept override { return robot_; }
  const Chain& chain() const noexcept override { return chain_; }
  std::vector<ArraySpec> observation_specs() const override {
    return {ArraySpec::vector("object_pose", 7)};
  }
  std::vector<int> object_geoms() const override { return {robot_.geom("box_geom")}; }

  void initialize_episode(Simulation& sim, EpisodeRandom& random) override {
    note("init");
    sim.reset();
    drawn = EpisodeRandom::uniform(random.task, 0.0, 1.0);
  }
  void before_step(const StepContext&, std::span<const double> action) noexcept override {
    note("before");
    last_action.assign(action.begin(), action.end());
  }
  void after_step(const StepContext&) noexcept override { note("after"); }
  void observe(int, const StepContext& context, std::span<double> out) const noexcept override {
    note("observe");
    const double* q = context.data().qpos + robot_.model().jnt_qposadr[robot_.joint("box_free")];
    for (int k = 0; k < 7; ++k) out[static_cast<std::size_t>(k)] = q[k];
  }
  double reward(const StepContext& context) const noexcept override {
    note("reward");
    return static_cast<double>(context.step);
  }
  bool terminated(const StepContext& context) const noexcept override {
    note("terminated");
    return terminate_at_ >= 0 && context.step >= terminate_at_;
  }

  double drawn = 0.0;               ///< the task generator's first draw of the episode
  std::vector<double> last_action;  ///< the action before_step saw

 private:
  void note(const char* hook) const noexcept {
    if (log_) log_->push_back(hook);
  }
  Robot robot_;
  Chain chain_;
  std::shared_ptr<std::vector<std::string>> log_;
  int terminate_at_;
};

}  // namespace mjarm::test
