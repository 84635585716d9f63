#include "mjarm/control/control_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/control/acceleration_control.hpp"
#include "mjarm/control/cartesian_impedance.hpp"
#include "mjarm/control/computed_torque.hpp"
#include "mjarm/control/gravity_compensation.hpp"
#include "mjarm/control/hqp_ac.hpp"
#include "mjarm/control/joint_pd.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/control/se3_impedance.hpp"
#include "mjarm/control/task_pd.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/momentum_observer.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/frame_state.hpp"

namespace mjarm {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// One period of the reference motion, tabulated before any timing.
class ReferenceTable {
 public:
  ReferenceTable(const Chain& chain, const Eigen::VectorXd& qpos_home, double amplitude,
                 double frequency, int period) {
    const int n = chain.size();
    const Eigen::VectorXd q_home = chain.gather(qpos_home.data());
    ChainKinematics kin(chain);
    kin.set_fixed_qpos(qpos_home);
    Matrix6Xd J(6, n);
    const double w = 2.0 * std::numbers::pi * frequency;
    const double dt = 1.0 / (frequency * period);
    ticks_.resize(static_cast<std::size_t>(period));
    for (int k = 0; k < period; ++k) {
      Reference& r = ticks_[static_cast<std::size_t>(k)];
      r.joint.q.resize(n);
      r.joint.qd.resize(n);
      r.joint.qdd.resize(n);
      for (int i = 0; i < n; ++i) {
        // keep the motion 0.05 inside the limits
        const double room =
            std::min(q_home[i] - chain.lower()[i], chain.upper()[i] - q_home[i]) - 0.05;
        const double a = std::clamp(room, 0.0, amplitude);
        const double phase = w * k * dt + 0.7 * i;
        r.joint.q[i] = q_home[i] + a * std::sin(phase);
        r.joint.qd[i] = a * w * std::cos(phase);
        r.joint.qdd[i] = -a * w * w * std::sin(phase);
      }
      r.task.X_WE = kin.update(r.joint.q);
      kin.jacobian(J);
      r.task.V_WE = J * r.joint.qd;
      r.task.A_WE = J * r.joint.qdd + kin.bias_acceleration(r.joint.qd);
    }
  }

  int period() const noexcept { return static_cast<int>(ticks_.size()); }

  /// Copies tick @p k (mod the period) into @p ref (sizes already right: no allocation).
  void load(int k, Reference& ref) const noexcept {
    const Reference& r = ticks_[static_cast<std::size_t>(k % period())];
    ref.joint.q = r.joint.q;
    ref.joint.qd = r.joint.qd;
    ref.joint.qdd = r.joint.qdd;
    ref.task = r.task;
  }

 private:
  std::vector<Reference> ticks_;
};

/// The motor of each chain joint: ctrl = τ ÷ gear (MuJoCo clips it to ctrlrange).
class Motors {
 public:
  explicit Motors(const Chain& chain) {
    const Robot& robot = chain.robot();
    const std::vector<ActuatorInfo> actuators = robot.actuators();
    for (int i = 0; i < chain.size(); ++i) {
      const auto id = chain.actuator(i);
      const std::string& joint = chain.joint_names()[static_cast<std::size_t>(i)];
      if (!id || actuators[static_cast<std::size_t>(*id)].kind != ActuatorKind::motor ||
          actuators[static_cast<std::size_t>(*id)].gear == 0.0) {
        throw Error("control benchmark: joint '" + joint + "' of model '" + robot.name() +
                    "' is not driven by a motor; the benchmark needs torque actuators (load the "
                    "'_torque' variant of a bundled robot, e.g. 'panda_torque')");
      }
      ids_.push_back(*id);
      gears_.push_back(actuators[static_cast<std::size_t>(*id)].gear);
    }
  }

  void apply(const double* tau, mjData& d) const noexcept {
    for (std::size_t i = 0; i < ids_.size(); ++i) d.ctrl[ids_[i]] = tau[i] / gears_[i];
  }

 private:
  std::vector<int> ids_;
  std::vector<double> gears_;
};

/// The controllers drive the chain's joints only: a free or ball joint (or a joint left out of
/// the chain) between the world and the frame lets the base fall or swing, with or without a
/// MuJoCo warning, and the figures would measure that motion.
void check_fixed_base(const Chain& chain) {
  const std::vector<int> unmoved = chain.unmoved_path_joints();
  if (unmoved.empty()) return;
  const mjModel& m = chain.robot().model();
  const int j = unmoved.front();
  const char* name = mj_id2name(&m, mjOBJ_JOINT, j);
  throw Error("control benchmark: the frame '" + chain.frame().name + "' of model '" +
              chain.robot().name() + "' hangs from " +
              to_string(static_cast<JointType>(m.jnt_type[j])) + " joint '" +
              (name != nullptr ? std::string(name) : "#" + std::to_string(j)) +
              "', which no controller drives: the base would fall or swing and the figures would "
              "measure that; the benchmark needs an arm on a fixed base (every joint between the "
              "world and the frame in the chain)");
}

// MuJoCo's warnings after which it has reset the data: the run's figures mean nothing
constexpr int kFatalWarnings[] = {mjWARN_INERTIA, mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC,
                                  mjWARN_BADCTRL};

const char* fatal_warning_text(int warning) noexcept {
  switch (warning) {
    case mjWARN_INERTIA:
      return "singular inertia matrix";
    case mjWARN_BADQPOS:
      return "bad qpos";
    case mjWARN_BADQVEL:
      return "bad qvel";
    case mjWARN_BADQACC:
      return "bad qacc";
    default:
      return "bad ctrl";
  }
}

/// Sets @p result faulted when MuJoCo raised a fatal warning during phase @p phase (the counters
/// start at zero with every `reset_start`). Returns true then.
bool check_warnings(const mjData& d, const std::string& phase, ControlBenchmarkResult& result) {
  for (const int w : kFatalWarnings) {
    const int times = d.warning[w].number;
    if (times == 0) continue;
    result.status = ControlBenchmarkStatus::faulted;
    result.message = "MuJoCo warned '" + std::string(fatal_warning_text(w)) + "' " +
                     std::to_string(times) + (times == 1 ? " time" : " times") + " (dof or index " +
                     std::to_string(d.warning[w].lastinfo) + ") while running '" + phase +
                     "' and reset the simulation, so the timings and errors are meaningless; "
                     "the model's dynamics (e.g. links too light for the motors' torques) "
                     "cannot follow this benchmark";
    return true;
  }
  return false;
}

/// True (and @p result interrupted) when the stop request says so; asked every 1000 ticks.
bool stop_requested(const ControlBenchmarkOptions& options, int tick,
                    ControlBenchmarkResult& result) {
  if (!options.stop || tick % 1000 != 0 || !options.stop()) return false;
  result.status = ControlBenchmarkStatus::interrupted;
  result.message = "interrupted";
  return true;
}

/// Restarts @p d on the reference's first tick (chain joints at q_d(0) moving at q̇_d(0), the
/// rest at home), with fresh kinematics and dynamics: every run starts on the reference.
void reset_start(const Chain& chain, const Reference& first, const Eigen::VectorXd& qpos_home,
                 mjData& d) {
  const mjModel& m = chain.robot().model();
  mj_resetData(&m, &d);
  mju_copy(d.qpos, qpos_home.data(), m.nq);
  chain.scatter(first.joint.q, d.qpos);
  for (int i = 0; i < chain.size(); ++i) d.qvel[chain.dof_address(i)] = first.joint.qd[i];
  mj_forward(&m, &d);
}

}  // namespace

std::vector<std::unique_ptr<Controller>> default_benchmark_controllers(const Chain& chain) {
  std::vector<std::unique_ptr<Controller>> controllers;
  controllers.push_back(std::make_unique<JointPdController>(chain));
  controllers.push_back(std::make_unique<GravityHoldController>(chain));
  controllers.push_back(std::make_unique<ComputedTorqueController>(chain));
  controllers.push_back(std::make_unique<TaskPdController>(chain));
  controllers.push_back(std::make_unique<AccelerationController>(chain));
  controllers.push_back(std::make_unique<OperationalSpaceController>(chain));
  controllers.push_back(std::make_unique<Se3ImpedanceController>(chain));
  controllers.push_back(std::make_unique<CartesianImpedanceController>(chain));
  controllers.push_back(std::make_unique<HqpAcController>(chain));
  return controllers;
}

ControlBenchmarkResult run_control_benchmark(const Chain& chain,
                                             const ControlBenchmarkOptions& options) {
  auto controllers = default_benchmark_controllers(chain);
  return run_control_benchmark(chain, controllers, options);
}

ControlBenchmarkResult run_control_benchmark(const Chain& chain,
                                             std::vector<std::unique_ptr<Controller>>& controllers,
                                             const ControlBenchmarkOptions& options) {
  check_fields(options);
  const Robot& robot = chain.robot();
  const mjModel& m = robot.model();
  const int n = chain.size();
  for (const auto& c : controllers) {
    if (c->command_kind() != CommandKind::torque || c->chain().size() != n) {
      throw Error("control benchmark: controller '" + std::string(c->name()) +
                  "' must be a torque controller of " + std::to_string(n) + " joints");
    }
  }
  check_fixed_base(chain);
  const Motors motors(chain);
  OperationalSpaceController osc(chain);

  // the home state and one period of the reference
  Eigen::VectorXd qpos_home = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
  const auto keys = robot.keyframe_names();
  if (std::find(keys.begin(), keys.end(), "home") != keys.end()) {
    const auto key = robot.keyframe_qpos("home");
    qpos_home = Eigen::Map<const Eigen::VectorXd>(key.data(), m.nq);
  }
  const double dt = m.opt.timestep;
  const int period = std::max(1, static_cast<int>(std::lround(1.0 / (options.frequency * dt))));
  const ReferenceTable table(chain, qpos_home, options.amplitude, 1.0 / (period * dt), period);

  ControlBenchmarkResult result;
  result.robot = robot.name();
  result.frame = chain.frame().name;
  result.joints = n;
  result.timestep = dt;
  result.frequency = 1.0 / (period * dt);
  result.steps = options.steps;

  DataPtr data = robot.make_data();
  mjData& d = *data;
  Reference ref;
  ref.joint.q.setZero(n);
  ref.joint.qd.setZero(n);
  ref.joint.qdd.setZero(n);
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(n)};
  std::vector<double> times(static_cast<std::size_t>(options.steps));
  const auto& count = options.allocation_count;
  const int phases = static_cast<int>(controllers.size()) + 3;
  int phase = 0;

  // one closed-loop phase from the reference's first state: each tick `untimed` (may be empty)
  // then `timed` run after mj_step1, the latter timed, then the command goes to the motors
  auto run_phase = [&](const std::string& name, auto&& untimed, auto&& timed) -> bool {
    table.load(0, ref);
    reset_start(chain, ref, qpos_home, d);
    std::uint64_t allocations = 0;
    double error2 = 0.0;
    for (int k = 0; k < options.warmup + options.steps; ++k) {
      if (stop_requested(options, k, result)) return false;
      table.load(k, ref);
      mj_step1(&m, &d);
      untimed();
      const std::uint64_t a0 = count ? count() : 0;
      const Clock::time_point t0 = Clock::now();
      timed();
      const Clock::time_point t1 = Clock::now();
      const std::uint64_t a1 = count ? count() : 0;
      if (k >= options.warmup) {
        times[static_cast<std::size_t>(k - options.warmup)] = 1e6 * seconds_between(t0, t1);
        allocations += a1 - a0;
        error2 += (frame_pose(m, d, chain.frame()).p - ref.task.X_WE.p).squaredNorm();
      }
      motors.apply(command.value.data(), d);
      mj_step2(&m, &d);
    }
    if (check_warnings(d, name, result)) return false;
    ControllerBenchmark b;
    b.name = name;
    b.steps = options.steps;
    b.mean_us = 0.0;
    for (double t : times) b.mean_us += t;
    b.mean_us /= options.steps;
    std::sort(times.begin(), times.end());
    b.median_us = nearest_rank(times, 0.5);
    b.p99_us = nearest_rank(times, 0.99);
    b.max_us = times.back();
    if (count) {
      b.allocations = static_cast<std::int64_t>(allocations);
      b.allocations_per_step = static_cast<double>(allocations) / options.steps;
    }
    b.rms_position_error = std::sqrt(error2 / options.steps);
    result.controllers.push_back(std::move(b));
    if (options.progress) options.progress(++phase, phases);
    return true;
  };

  // every controller in closed loop, each compute timed
  for (auto& controller : controllers) {
    controller->reset();
    Controller& c = *controller;
    if (!run_phase(
            std::string(c.name()), [] {}, [&] { c.compute(d, ref, command); })) {
      return result;
    }
  }

  // the momentum observer (ChainDynamics::update + MomentumObserver::update) riding along an
  // OSC loop: the OSC compute is not timed, the observer's update with OSC's torque is
  {
    ChainDynamics dynamics(chain);
    MomentumObserver observer(chain);
    osc.reset();
    if (!run_phase(
            "observer", [&] { osc.compute(d, ref, command); },
            [&] {
              dynamics.update(d);
              observer.update(d, dynamics, command.value, dt);
            })) {
      return result;
    }
  }

  // real-time factor of closed-loop OSC + physics, no per-tick clocks
  std::vector<double> torques(static_cast<std::size_t>(options.steps) *
                              static_cast<std::size_t>(n));
  table.load(0, ref);
  reset_start(chain, ref, qpos_home, d);
  osc.reset();
  const std::uint64_t loop_a0 = count ? count() : 0;
  const Clock::time_point osc_start = Clock::now();
  for (int k = 0; k < options.steps; ++k) {
    if (stop_requested(options, k, result)) return result;
    table.load(k, ref);
    mj_step1(&m, &d);
    osc.compute(d, ref, command);
    motors.apply(command.value.data(), d);
    std::copy(command.value.data(), command.value.data() + n,
              torques.data() + static_cast<std::size_t>(k) * n);
    mj_step2(&m, &d);
  }
  const double osc_seconds = seconds_between(osc_start, Clock::now());
  if (count) result.loop_allocations = static_cast<std::int64_t>(count() - loop_a0);
  if (check_warnings(d, "osc + mj_step", result)) return result;
  if (options.progress) options.progress(++phase, phases);

  // the same physics alone: mj_step replaying the recorded torques
  table.load(0, ref);
  reset_start(chain, ref, qpos_home, d);
  const Clock::time_point passive_start = Clock::now();
  for (int k = 0; k < options.steps; ++k) {
    if (stop_requested(options, k, result)) return result;
    motors.apply(torques.data() + static_cast<std::size_t>(k) * n, d);
    mj_step(&m, &d);
  }
  const double passive_seconds = seconds_between(passive_start, Clock::now());
  if (check_warnings(d, "mj_step only", result)) return result;
  if (options.progress) options.progress(++phase, phases);

  const double simulated = options.steps * dt;
  result.osc_real_time_factor = simulated / osc_seconds;
  result.passive_real_time_factor = simulated / passive_seconds;
  result.osc_step_us = 1e6 * osc_seconds / options.steps;
  result.passive_step_us = 1e6 * passive_seconds / options.steps;
  return result;
}

}  // namespace mjarm
