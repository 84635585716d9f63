#include "mjarm/env/environment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "mjarm/env/action_driver.hpp"
#include "mjarm/env/observation_set.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

std::string value_text(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::unique_ptr<EnvTask> checked_task(std::unique_ptr<EnvTask> task) {
  if (!task) throw Error("environment: no task given");
  return task;
}

}  // namespace

struct Environment::Impl {
  EnvironmentOptions options;
  std::unique_ptr<EnvTask> task;
  std::unique_ptr<ActionDriver> driver;  // declared before the simulation that calls its controller
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<ObservationSet> observations;
  std::unique_ptr<DomainRandomizer> randomizer;
  std::unique_ptr<ChainKinematics> kinematics;
  Matrix6Xd J;
  Eigen::VectorXd q, qd;
  std::vector<double> observation;
  std::vector<double> action;  // the clipped action of the current step
  std::optional<ArraySpec> task_action;  // the task's own action, mapped onto the space's
  std::vector<double> space_action;      // the action space's values of the current step
  std::vector<double> delayed;           // action_latency: ring of the last latency + 1 actions
  int delayed_next = 0;                  // the slot the next action goes to
  int delayed_count = 0;                 // actions given in this episode, up to latency + 1
  Random noise;                          // the episode's observation noise
  std::optional<ObservationSpec> noisy_spec;  // the observations' spec, unbounded by the noise
  EpisodeRandom random;
  Random seeds;  // episode seeds for reset() without one
  StepContext context;
  TimeStep time_step;
  ObservationSpec empty_spec;
  int ticks_per_step = 1;
  int physics_per_step = 1;
  int step_limit = 1;
  double episode_start = 0.0;
  bool started = false;
  bool ended = false;
  bool closed = false;
  ClipCounts episode_clips, total_clips;

  Impl(std::unique_ptr<EnvTask> t, const EnvironmentOptions& o);
  void update_context() noexcept;
  TimeStep make_time_step(StepType type, EpisodeEnd end, double reward) noexcept;
};

Environment::Impl::Impl(std::unique_ptr<EnvTask> t, const EnvironmentOptions& o)
    : options(o), task(checked_task(std::move(t))), seeds(o.seed) {
  check_fields(o);
  const Robot& robot = task->robot();
  const Chain& chain = task->chain();
  const double h = robot.model().opt.timestep;
  // the control step: whole physics steps, whole controller periods
  // 0: the joint PD runs every physics step (a servo loop), the other spaces once per step
  const bool servo =
      o.action_space == ActionSpace::joint_positions || o.action_space == ActionSpace::joint_deltas;
  const double controller_period = o.controller_period != 0.0         ? o.controller_period
                                   : task->controller_period() != 0.0 ? task->controller_period()
                                   : servo                            ? h
                                                                      : o.control_period;
  physics_per_step =
      whole_multiple(o.control_period, h, "environment: control_period", "the physics timestep");
  whole_multiple(controller_period, h, "environment: controller_period", "the physics timestep");
  ticks_per_step = whole_multiple(o.control_period, controller_period,
                                  "environment: control_period", "the controller period");
  if (!(std::isfinite(o.time_limit) && o.time_limit >= o.control_period))
    throw Error("environment: time_limit must be finite and at least the control period " +
                value_text(o.control_period) + " s, got " + value_text(o.time_limit) + " s");
  step_limit = static_cast<int>(std::ceil(o.time_limit / o.control_period - 1e-9));

  // the simulation (its own model copy when randomized), the action driver, the observations
  SimulationOptions sim_options;
  sim_options.mode = SimulationMode::torque;
  sim_options.control_period = controller_period;
  sim_options.max_acceleration = o.max_acceleration;
  sim_options.own_model = o.randomization.any();
  driver = std::make_unique<ActionDriver>(o.action_space, chain, o.action, o.control_period,
                                          task->gripper_action());
  sim = std::make_unique<Simulation>(robot, sim_options);
  sim->add_controller(driver->controller());
  if (Controller* own = task->auxiliary_controller()) sim->add_controller(*own);
  if (o.randomization.any())
    randomizer =
        std::make_unique<DomainRandomizer>(robot.model(), o.randomization, task->object_geoms());
  observations = std::make_unique<ObservationSet>(
      *task, *sim, o.observations.empty() ? task->default_observations() : o.observations);

  kinematics = std::make_unique<ChainKinematics>(chain);
  const int n = chain.size();
  J = Matrix6Xd::Zero(6, n);
  q.setZero(n);
  qd.setZero(n);
  observation.assign(static_cast<std::size_t>(observations->spec().size()), 0.0);
  task_action = task->action_spec();
  if (task_action) {
    task_action->check();
    if (!task_action->bounded())
      throw Error("environment: the task's action '" + task_action->name +
                  "' needs finite bounds on every element (" + task_action->describe() + ")");
  }
  space_action.assign(static_cast<std::size_t>(driver->spec().size()), 0.0);
  action.assign(static_cast<std::size_t>(task_action ? task_action->size() : driver->spec().size()),
                0.0);
  delayed.assign(action.size() * static_cast<std::size_t>(o.action_latency + 1), 0.0);
  if (o.observation_noise > 0.0) {
    std::vector<ArraySpec> arrays = observations->spec().arrays();
    for (ArraySpec& a : arrays) {
      a.minimum.setConstant(-std::numeric_limits<double>::infinity());
      a.maximum.setConstant(std::numeric_limits<double>::infinity());
    }
    noisy_spec.emplace(std::move(arrays));
  }
  context.sim = sim.get();
  time_step.observation = Observation(&empty_spec, {});
}

void Environment::Impl::update_context() noexcept {
  // the end effector from the current qpos and qvel (mjData's derived values lag a physics step)
  const Chain& chain = task->chain();
  const mjData& d = sim->data();
  for (int i = 0; i < chain.size(); ++i) {
    q[i] = d.qpos[chain.qpos_address(i)];
    qd[i] = d.qvel[chain.dof_address(i)];
  }
  // the end-effector spaces' QP starts the next step from this q: its kinematics do the work
  ChainKinematics* shared = driver->measured_kinematics();
  ChainKinematics& k = shared != nullptr ? *shared : *kinematics;
  context.X_WE = k.update(q);
  k.jacobian(J);
  context.V_WE.noalias() = J * qd;
  context.time = d.time - episode_start;
}

TimeStep Environment::Impl::make_time_step(StepType type, EpisodeEnd end, double reward) noexcept {
  observations->fill(context, *task, observation);
  if (options.observation_noise > 0.0) {
    for (double& v : observation) v += normal(noise, 0.0, options.observation_noise);
  }
  TimeStep ts;
  ts.step_type = type;
  ts.end = end;
  if (type != StepType::first) {
    ts.reward = reward;
    ts.discount = end == EpisodeEnd::terminated || end == EpisodeEnd::diverged ? 0.0 : 1.0;
  }
  ts.observation = Observation(noisy_spec ? &*noisy_spec : &observations->spec(), observation);
  time_step = ts;
  return ts;
}

Environment::Environment(std::unique_ptr<EnvTask> task, const EnvironmentOptions& options)
    : impl_(std::make_unique<Impl>(std::move(task), options)) {}

Environment::Environment(std::string_view task, const EnvironmentOptions& options)
    : Environment(make_env_task(task), options) {}

Environment::~Environment() = default;

TimeStep Environment::reset() { return reset(impl_->seeds()); }

void Environment::close() noexcept { impl_->closed = true; }

bool Environment::closed() const noexcept { return impl_->closed; }

namespace {

[[noreturn]] void refuse_closed(const EnvTask& task, const char* call) {
  throw Error("environment '" + std::string(task.name()) + "': " + call +
              " after close(); a closed environment stays closed: make a new one");
}

}  // namespace

TimeStep Environment::reset(std::uint64_t seed) {
  Impl& e = *impl_;
  if (e.closed) refuse_closed(*e.task, "reset()");
  e.started = false;
  e.random.reseed(seed);
  // the noise's own stream: the task's and the randomization's draws are the same without it
  e.noise.seed(splitmix64(seed ^ 0x6f62736e6f697365ull));
  e.delayed_next = 0;
  e.delayed_count = 0;
  if (e.randomizer)
    e.randomizer->apply(*e.sim->editable_model(), e.sim->data(), e.random.randomization);
  e.task->initialize_episode(*e.sim, e.random);
  e.driver->reset(e.sim->data());
  e.episode_start = e.sim->time();
  e.context.step = 0;
  e.update_context();
  e.episode_clips = ClipCounts{};
  e.started = true;
  e.ended = false;
  return e.make_time_step(StepType::first, EpisodeEnd::running, 0.0);
}

TimeStep Environment::step(std::span<const double> action) {
  Impl& e = *impl_;
  if (e.closed) refuse_closed(*e.task, "step()");
  if (!e.started) throw Error("environment: step() before reset(); call reset() first");
  if (e.ended)
    throw Error("environment: step() after the last step of the episode (" +
                std::string(to_string(e.time_step.end)) + "); call reset() to start another");
  const ArraySpec& spec = e.task_action ? *e.task_action : e.driver->spec();
  const std::string space = e.task_action ? "the task's action '" + e.task_action->name + "'"
                                          : std::string(to_string(e.options.action_space));
  const std::size_t size = static_cast<std::size_t>(spec.size());
  if (action.size() != size)
    throw Error("environment: the action (" + space + ") needs " + std::to_string(size) +
                " values, got " + std::to_string(action.size()));
  for (std::size_t i = 0; i < size; ++i) {
    if (!std::isfinite(action[i]))
      throw Error("environment: action[" + std::to_string(i) + "] is " + value_text(action[i]) +
                  " (" + space + " needs finite values)");
  }
  // clip into the bounds (or refuse), counting
  std::int64_t clipped = 0;
  for (std::size_t i = 0; i < size; ++i) {
    const double lo = spec.minimum[static_cast<Eigen::Index>(i)];
    const double hi = spec.maximum[static_cast<Eigen::Index>(i)];
    const double a = action[i];
    if (a < lo || a > hi) {
      if (e.options.refuse_out_of_bounds)
        throw Error("environment: action[" + std::to_string(i) + "] = " + value_text(a) +
                    " is outside its bounds [" + value_text(lo) + ", " + value_text(hi) + "] (" +
                    space + "; refuse_out_of_bounds is set)");
      ++clipped;
    }
    e.action[i] = std::clamp(a, lo, hi);
  }
  if (clipped > 0) {
    ++e.episode_clips.steps;
    ++e.total_clips.steps;
    e.episode_clips.values += clipped;
    e.total_clips.values += clipped;
  }

  // action_latency: the action of `latency` steps ago (the episode's first one until then)
  if (e.options.action_latency > 0) {
    const std::size_t n = e.action.size();
    const int slots = e.options.action_latency + 1;
    std::copy(e.action.begin(), e.action.end(),
              e.delayed.begin() + static_cast<std::ptrdiff_t>(n) * e.delayed_next);
    if (e.delayed_count == 0) {  // the first action fills the line
      for (int k = 1; k < slots; ++k)
        std::copy(e.action.begin(), e.action.end(),
                  e.delayed.begin() + static_cast<std::ptrdiff_t>(n) * k);
      // (slot 0 was just written; the ring is full of the first action)
    }
    e.delayed_count = std::min(e.delayed_count + 1, slots);
    e.delayed_next = (e.delayed_next + 1) % slots;
    // the oldest slot is the one written next
    const auto oldest = e.delayed.begin() + static_cast<std::ptrdiff_t>(n) * e.delayed_next;
    std::copy(oldest, oldest + static_cast<std::ptrdiff_t>(n), e.action.begin());
  }

  // the task, the reference, the physics
  std::span<const double> space_action = e.action;
  if (e.task_action) {
    // the task's action onto the action space's values, inside their bounds
    e.task->map_action(e.context, e.action, e.space_action);
    const ArraySpec& bounds = e.driver->spec();
    for (std::size_t i = 0; i < e.space_action.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      const double v = e.space_action[i];
      e.space_action[i] = std::isfinite(v) ? std::clamp(v, bounds.minimum[k], bounds.maximum[k])
                                           : 0.0;  // a broken mapping commands nothing
    }
    space_action = e.space_action;
  }
  e.task->before_step(e.context, e.action);
  const Reference& reference = e.driver->apply(space_action, e.sim->data());
  EpisodeEnd end = EpisodeEnd::running;
  for (int k = 0; k < e.ticks_per_step; ++k) {
    if (!e.sim->tick(reference).ok()) {
      end = EpisodeEnd::diverged;
      break;
    }
  }
  ++e.context.step;
  e.update_context();
  e.task->after_step(e.context);
  const double reward = e.task->reward(e.context);
  if (end == EpisodeEnd::running) {
    if (e.task->terminated(e.context)) {
      end = EpisodeEnd::terminated;
    } else if (e.context.step >= e.step_limit) {
      end = EpisodeEnd::truncated;
    }
  }
  e.ended = end != EpisodeEnd::running;
  return e.make_time_step(e.ended ? StepType::last : StepType::mid, end, reward);
}

const ArraySpec& Environment::action_spec() const noexcept {
  return impl_->task_action ? *impl_->task_action : impl_->driver->spec();
}
const ObservationSpec& Environment::observation_spec() const noexcept {
  return impl_->noisy_spec ? *impl_->noisy_spec : impl_->observations->spec();
}
const TimeStep& Environment::time_step() const noexcept { return impl_->time_step; }
const EnvironmentOptions& Environment::options() const noexcept { return impl_->options; }
const EnvTask& Environment::task() const noexcept { return *impl_->task; }
const Simulation& Environment::simulation() const noexcept { return *impl_->sim; }
const StepContext& Environment::context() const noexcept { return impl_->context; }
std::uint64_t Environment::episode_seed() const noexcept { return impl_->random.seed; }
int Environment::steps() const noexcept { return impl_->context.step; }
int Environment::step_limit() const noexcept { return impl_->step_limit; }
int Environment::physics_steps_per_step() const noexcept { return impl_->physics_per_step; }
const ClipCounts& Environment::episode_clips() const noexcept { return impl_->episode_clips; }
const ClipCounts& Environment::total_clips() const noexcept { return impl_->total_clips; }
const ActionDriver& Environment::action_driver() const noexcept { return *impl_->driver; }
const DomainRandomizer* Environment::randomizer() const noexcept { return impl_->randomizer.get(); }

}  // namespace mjarm
