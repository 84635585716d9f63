#pragma once
/// @file
/// `EnvTask`: what an environment asks of a task (dm_control's `Task`): the model and arm, the
/// episode's start, the hooks around the physics, the task's own observations, the reward and
/// the termination. And `EpisodeRandom`, the random state of one episode.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/env/array_spec.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/random.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {

/// The random state of one episode: two `Random` generators seeded from the episode's seed —
/// the task's with the seed itself, the domain randomization's with splitmix64(seed) — so that
/// a task draws the same start and goal for a seed whether or not the model is randomized. Draw
/// with random.hpp's functions: the same numbers on every platform.
struct EpisodeRandom {
  std::uint64_t seed = 0;
  Random task;
  Random randomization;

  explicit EpisodeRandom(std::uint64_t seed = 0) { reseed(seed); }
  /// Seeds both generators from @p seed (allocation-free).
  void reseed(std::uint64_t seed) noexcept;
  /// `mjarm::uniform(rng, lo, hi)` (random.hpp), under its former name.
  static double uniform(Random& rng, double lo, double hi) noexcept {
    return mjarm::uniform(rng, lo, hi);
  }
};

/// What the task's hooks see of the environment after the physics of a step (or after the
/// episode's start): the simulation and the end-effector state computed from the current qpos
/// and qvel by `ChainKinematics` (MuJoCo's own derived quantities in `mjData` lag one physics
/// step, see `Simulation`).
struct StepContext {
  const Simulation* sim = nullptr;
  Pose X_WE;                         ///< pose of the chain's frame E in W
  Vector6d V_WE = Vector6d::Zero();  ///< its twist [v; ω], world axes
  int step = 0;                      ///< control steps since the episode's start
  double time = 0.0;                 ///< simulated time since the episode's start [s]

  const Simulation& simulation() const noexcept { return *sim; }
  const mjData& data() const noexcept { return sim->data(); }
};

/// A task of an environment. The environment owns it, calls its hooks in this order and never
/// concurrently:
///
///     reset:  initialize_episode → observation
///     step:   [map_action →] before_step → physics → after_step → observation → reward →
///             terminated
///
/// Hooks after construction must not allocate (the environment's step allocates nothing) and
/// must not throw; `initialize_episode` may do both.
class EnvTask {
 public:
  virtual ~EnvTask() = default;

  /// An independent copy (its own episode state) sharing the immutable model: for the
  /// environments of a vectorized batch.
  virtual std::unique_ptr<EnvTask> clone() const = 0;

  /// Short name ("reach").
  virtual std::string_view name() const noexcept = 0;
  /// One line on what the task asks, for listings.
  virtual std::string_view description() const noexcept = 0;
  /// The model the environment simulates (torque motors on the chain's joints).
  virtual const Robot& robot() const noexcept = 0;
  /// The arm actions drive; its frame is the end effector.
  virtual const Chain& chain() const noexcept = 0;

  /// The task's own observations (e.g. "target", "object_pose"): name, shape, bounds.
  virtual std::vector<ArraySpec> observation_specs() const { return {}; }
  /// Observation names used when the environment is given none.
  virtual std::vector<std::string> default_observations() const;
  /// Geoms whose size the domain randomization may scale (the task's objects); none by default.
  virtual std::vector<int> object_geoms() const { return {}; }
  /// True when the task has a gripper the agent commands: the action then ends with one more
  /// entry in [0, 1] (0 open, 1 closed), passed to the controllers as `Reference::gripper`.
  virtual bool gripper_action() const noexcept { return false; }
  /// A controller of the task's own for the joints the chain does not hold (e.g. the fingers),
  /// added to the environment's simulation after the action's controller: it runs at the same
  /// period on the same reference (the gripper command in `Reference::gripper`). Null by
  /// default. The task owns it; each clone has its own.
  virtual Controller* auxiliary_controller() noexcept { return nullptr; }
  /// The controller period the task needs [s] (a whole divisor of the control step), used when
  /// `EnvironmentOptions::controller_period` is 0; 0 (the default): the action space's own.
  virtual double controller_period() const noexcept { return 0.0; }

  /// The task's own action, when it has one: any bounded array, which `map_action` turns into
  /// the values of the environment's action space at each step (so the environment's controllers
  /// carry it out). nullopt (the default): agents act in that action space directly.
  virtual std::optional<ArraySpec> action_spec() const { return std::nullopt; }
  /// With a task action (`action_spec`): writes the action space's values for the checked and
  /// clipped task action @p action into @p space_action (its size; clipped into the space's
  /// bounds afterwards). Called before `before_step`. The default writes zeros.
  virtual void map_action(const StepContext& context, std::span<const double> action,
                          std::span<double> space_action) noexcept;

  /// Starts an episode: puts the simulation in its start state (reset, set_state) and draws
  /// the episode's goal from @p random.task. The model is already randomized.
  virtual void initialize_episode(Simulation& sim, EpisodeRandom& random) = 0;
  /// Before the physics, with the clipped action.
  virtual void before_step(const StepContext& context, std::span<const double> action) noexcept;
  /// After the physics.
  virtual void after_step(const StepContext& context) noexcept;
  /// Writes task observation @p index (of `observation_specs()`) into @p out (its size).
  virtual void observe(int index, const StepContext& context, std::span<double> out) const noexcept;
  /// The reward of the step that led to @p context.
  virtual double reward(const StepContext& context) const noexcept = 0;
  /// True when the episode ends here by the task's own rule (discount 0).
  virtual bool terminated(const StepContext& context) const noexcept;
};

}  // namespace mjarm
