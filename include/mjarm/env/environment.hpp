#pragma once
/// @file
/// `Environment`: a learning environment with dm_env's semantics on a `Simulation` — reset to a
/// FIRST time step, step with an action to MID or LAST, action and observation specs, the
/// control step made of whole physics steps, a task's hooks around the physics, domain
/// randomization drawn from the episode's random state. See docs/env.md.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/env/action_driver.hpp"
#include "mjarm/env/action_space.hpp"
#include "mjarm/env/array_spec.hpp"
#include "mjarm/env/env_task.hpp"
#include "mjarm/env/randomization.hpp"
#include "mjarm/env/time_step.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {

/// Settings of an `Environment`, checked by its constructor.
struct EnvironmentOptions {
  ActionSpace action_space = ActionSpace::ee_pose_deltas;
  ActionOptions action;  ///< bounds and gains of the action spaces
  /// Control step T [s]: one action per T. A whole multiple of the model's physics timestep
  /// (10 physics steps of 2 ms on the bundled models).
  double control_period = 0.02;
  /// Period of the low-level controller [s]: a whole divisor of T (the controller then runs
  /// T / controller_period times per step on the step's reference). 0: the task's
  /// (`EnvTask::controller_period`) when it names one, else the action space's own —
  /// the physics timestep for joint_positions and joint_deltas (the joint PD is a servo loop:
  /// held over a whole control step its damping would not be stable on the light wrist
  /// joints), T for the others (the torques and the operational-space controller's output are
  /// held over the step).
  double controller_period = 0.0;
  /// Episode length [s]: after ⌈time_limit / T⌉ steps the episode ends LAST with discount 1
  /// (a truncation). Positive, finite and at least T.
  double time_limit = 10.0;
  /// Observations by name (see `ObservationSet`); empty: the task's defaults.
  std::vector<std::string> observations;
  /// An action outside its bounds is clipped into them and counted; with this set it is
  /// refused (an Error naming the entry and its bounds) instead.
  bool refuse_out_of_bounds = false;
  RandomizationOptions randomization;  ///< domain randomization (none by default)
  /// Seed of the episode seeds that `reset()` without a seed draws (`reset(seed)` ignores it).
  std::uint64_t seed = 0;
  /// Divergence bound on |q̈| (`SimulationOptions::max_acceleration`) [rad/s² or m/s²].
  double max_acceleration = 1e6;
  /// Standard deviation of the Gaussian noise added to every observation value, in each value's
  /// own unit (0: none). The noisy observations' bounds become unbounded in the spec. Drawn from
  /// the episode's own noise stream (splitmix64 of the episode's seed, mixed): a seed gives the
  /// same noise, and the task's draws are the same with or without noise.
  double observation_noise = 0.0;
  /// Control steps between an action and the step that applies it (0: none): step k applies
  /// the action given at step k − latency; the first `action_latency` steps of an episode apply
  /// its first action. The task's hooks see the action applied.
  int action_latency = 0;
};

/// `observations` is checked against the task's, the periods against the timestep by hand.
constexpr auto declared_fields(const EnvironmentOptions*) {
  using S = EnvironmentOptions;
  return declare<S>(
      "environment", field("action_space", &S::action_space, "what one action commands"),
      field("action", &S::action, "bounds and gains of the action spaces"),
      field("control_period", &S::control_period, "s", Range::positive(),
            "control step T, a whole multiple of the physics timestep"),
      field("controller_period", &S::controller_period, "s", Range::non_negative(),
            "low-level controller period, a whole divisor of T; 0: the action space's own"),
      field("time_limit", &S::time_limit, "s", Range::positive(),
            "episode length: LAST with discount 1 after ceil(time_limit / T) steps"),
      field("refuse_out_of_bounds", &S::refuse_out_of_bounds,
            "refuse instead of clipping an action outside its bounds"),
      field("randomization", &S::randomization, "domain randomization"),
      field("seed", &S::seed, "seed of the episode seeds reset() without a seed draws"),
      field("max_acceleration", &S::max_acceleration, "rad/s² or m/s²",
            Range::positive().or_infinity(), "divergence bound on |q̈|"),
      field("observation_noise", &S::observation_noise, "", Range::non_negative(),
            "standard deviation of the Gaussian noise on every observation value (own units)"),
      field("action_latency", &S::action_latency, "steps", Range::closed(0, 1000),
            "control steps between an action and the step that applies it"));
}

/// How often actions were clipped into their bounds.
struct ClipCounts {
  std::int64_t steps = 0;   ///< steps whose action had at least one value clipped
  std::int64_t values = 0;  ///< values clipped
};

/// A learning environment (dm_env / dm_control `control.Environment` semantics):
///
/// - `reset(seed)` → TimeStep{FIRST, reward none, discount none, observation};
/// - `step(action)` → MID; or LAST when the task terminates (discount 0), when the time limit
///   is reached (discount 1: a truncation), or when the physics diverges (discount 0,
///   `EpisodeEnd::diverged`; the state of the last good physics step is kept);
/// - `step` before the first `reset` or after LAST is an error: call `reset`;
/// - `close()` ends the environment for good (dm_env's `close`): a `reset` or `step` after it is
///   an error naming the task, never a new episode.
///
/// One step: the action is checked (size, NaN/inf: errors) and clipped into its bounds (or
/// refused), the task's `before_step` sees it, the `ActionDriver` turns it into a reference,
/// the simulation runs T / controller_period control ticks of controller_period / h physics
/// steps each, then `after_step`, the observation, the reward and the termination. Nothing is
/// allocated in `step` after construction; `reset` may allocate.
///
/// The model is simulated in torque mode (each chain joint needs a torque motor). With domain
/// randomization the simulation steps its own copy of the model, randomized at every reset.
/// The same seed and actions give the same time steps bit for bit.
class Environment {
 public:
  /// @throws Error for options out of range: a control period that is not a whole multiple of
  ///         the physics timestep (or of the controller period), a time limit shorter than it,
  ///         an unknown or unavailable observation (see `ObservationSet`), a chain joint
  ///         without a torque motor, randomization ranges out of [0, 1) or object-size
  ///         randomization on a task without objects.
  Environment(std::unique_ptr<EnvTask> task, const EnvironmentOptions& options = {});
  /// The task called @p task (`make_env_task`). @throws Error for an unknown task, and as above.
  explicit Environment(std::string_view task, const EnvironmentOptions& options = {});
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

  /// Starts an episode with seed @p seed: randomizes the model (when asked), lets the task set
  /// the start state and goal, and returns FIRST.
  /// @throws Error after `close()`.
  TimeStep reset(std::uint64_t seed);
  /// Starts an episode with the next seed of the environment's own seed sequence
  /// (`EnvironmentOptions::seed`).
  TimeStep reset();
  /// One control step with @p action (action_spec().size() values). Allocation-free.
  /// @throws Error before the first reset, after LAST, after `close()`, for a wrong size, a
  ///         NaN/inf value, or a value out of bounds when `refuse_out_of_bounds` is set.
  TimeStep step(std::span<const double> action);
  /// Closes the environment: every later `reset` and `step` throws `Error` (a closed environment
  /// stays closed; make a new one). Closing twice is allowed. The memory goes with the object;
  /// the accessors below keep answering.
  void close() noexcept;
  /// True after `close()`.
  bool closed() const noexcept;

  /// The action agents give: the task's own (`EnvTask::action_spec`) when it has one, else the
  /// action space's.
  const ArraySpec& action_spec() const noexcept;
  const ObservationSpec& observation_spec() const noexcept;
  /// The last time step returned (FIRST before any reset, with an empty observation).
  const TimeStep& time_step() const noexcept;

  const EnvironmentOptions& options() const noexcept;
  const EnvTask& task() const noexcept;
  const Simulation& simulation() const noexcept;
  /// The context the task's hooks saw last (end-effector state, step, time).
  const StepContext& context() const noexcept;
  /// The seed of the current episode.
  std::uint64_t episode_seed() const noexcept;
  /// Steps taken in the current episode.
  int steps() const noexcept;
  /// Steps after which an episode is truncated: ⌈time_limit / T⌉.
  int step_limit() const noexcept;
  /// Physics steps per control step (T / h).
  int physics_steps_per_step() const noexcept;
  /// Clipping of the current episode, and since construction.
  const ClipCounts& episode_clips() const noexcept;
  const ClipCounts& total_clips() const noexcept;
  /// What turns the actions into references (its last reference, the QP's last step).
  const ActionDriver& action_driver() const noexcept;
  /// The randomizer (its last draws), or null without randomization.
  const DomainRandomizer* randomizer() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjarm
