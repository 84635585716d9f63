#pragma once
/// @file
/// The control benchmark: time per controller step and allocations per step of every torque
/// controller, each in closed loop with MuJoCo, and the real-time factor of operational-space
/// control plus `mj_step` beside that of `mj_step` alone.
///
/// Protocol. Around the `home` keyframe (qpos0 when the model has none), the reference is a
/// periodic joint motion q_d(t) = q_home + a·sin(2πft + 0.7·i) on every chain
/// joint i (a = `amplitude`, clipped so q_d stays 0.05 rad inside the limits) and its image in
/// task space (X_WD = FK(q_d), V_WD = J·q̇_d, A_WD = J·q̈_d + J̇·q̇_d): joint controllers and
/// task controllers track the same motion. One period (a whole number of physics steps) is
/// tabulated before any timing. Each controller then runs `steps` control ticks in closed loop,
/// one tick per physics step, starting on the reference (q = q_d(0), q̇ = q̇_d(0)), as a split
/// step:
///
///     mj_step1 → [clock] compute [clock] → ctrl = τ ÷ gear → mj_step2
///
/// after `warmup` untimed ticks. Each compute is timed with std::chrono::steady_clock (the
/// ~20–40 ns of the two clock reads are included), and the allocation hook, when given, is read
/// around each compute. Then the momentum observer: the same loop driven by a default
/// `OperationalSpaceController` (untimed), timing `ChainDynamics::update` + `MomentumObserver::
/// update` with OSC's torque (the "observer" row). Then the real-time factor: the operational-space
/// loop again without per-tick clocks (wall time of the whole loop, one thread), and `mj_step`
/// alone replaying the torques that run recorded (same physics, no controller), in the same process
/// right after. Real-time factor = simulated time / wall time.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// Settings of `run_control_benchmark`.
struct ControlBenchmarkOptions {
  int steps = 20000;  ///< timed ticks per controller, and physics steps of the RTF runs (≥ 1)
  int warmup = 200;   ///< untimed ticks before each timed run (≥ 0)
  double amplitude = 0.2;  ///< joint amplitude a of the reference [rad or m] (≥ 0)
  double frequency = 0.5;  ///< f [Hz] (> 0), rounded so that a period is a whole number of steps
  /// Allocation counter of the process (e.g. a replaced malloc's call count); read before and
  /// after every timed compute. Empty: allocations are not counted (reported as −1).
  std::function<std::uint64_t()> allocation_count;
  /// Called after each phase with (phases done, phases total); may be empty.
  std::function<void(int done, int total)> progress;
  /// Asked every thousand ticks whether to stop (e.g. `interrupt_requested` after Ctrl-C); may be
  /// empty. A stop ends the run `ControlBenchmarkStatus::interrupted`.
  std::function<bool()> stop;
};

constexpr auto declared_fields(const ControlBenchmarkOptions*) {
  using S = ControlBenchmarkOptions;
  return declare<S>(
      "control benchmark",
      field("steps", &S::steps, "", Range::positive(), "timed ticks per controller"),
      field("warmup", &S::warmup, "", Range::non_negative(), "untimed ticks before each run"),
      field("amplitude", &S::amplitude, "rad or m", Range::non_negative(),
            "joint amplitude of the reference"),
      field("frequency", &S::frequency, "Hz", Range::positive(), "of the reference"));
}

/// How a benchmark run ended.
enum class ControlBenchmarkStatus {
  ok,           ///< every phase ran; the figures stand
  faulted,      ///< MuJoCo flagged a bad state (bad qpos, qvel, qacc or ctrl, singular inertia)
                ///< and reset the simulation: the figures would be meaningless and are not given
  interrupted,  ///< the stop request said so; the figures are incomplete
};

constexpr auto declared_names(const ControlBenchmarkStatus*) {
  using S = ControlBenchmarkStatus;
  return std::array{EnumName{S::ok, "ok", "every phase ran"},
                    EnumName{S::faulted, "faulted", "MuJoCo flagged a bad state"},
                    EnumName{S::interrupted, "interrupted", "stopped on request"}};
}

/// Figures of one controller.
struct ControllerBenchmark {
  std::string name;               ///< Controller::name()
  int steps = 0;                  ///< timed ticks
  double median_us = 0.0;         ///< median time of one compute [µs]
  double p99_us = 0.0;            ///< 99th percentile (nearest rank) [µs]
  double mean_us = 0.0;           ///< mean [µs]
  double max_us = 0.0;            ///< slowest tick [µs]
  std::int64_t allocations = -1;  ///< heap allocations during the timed computes (−1: not counted)
  double allocations_per_step = -1.0;  ///< allocations / steps (−1: not counted)
  /// RMS distance between E's origin and the reference over the timed ticks [m]: a sanity check
  /// that the controller really was in the loop (gravity hold ignores the reference).
  double rms_position_error = 0.0;
};

constexpr auto declared_fields(const ControllerBenchmark*) {
  using S = ControllerBenchmark;
  return declare<S>(
      "controller benchmark", field("name", &S::name, "the controller's name"),
      field("steps", &S::steps, "", "timed ticks"),
      field("median_us", &S::median_us, "µs", "median time of one compute"),
      field("p99_us", &S::p99_us, "µs", "99th percentile (nearest rank)"),
      field("mean_us", &S::mean_us, "µs", "mean time of one compute"),
      field("max_us", &S::max_us, "µs", "slowest tick"),
      field("allocations", &S::allocations, "", "heap allocations while timed; -1: not counted"),
      field("allocations_per_step", &S::allocations_per_step, "",
            "allocations / steps; -1: not counted"),
      field("rms_position_error_m", &S::rms_position_error, "m",
            "RMS distance of E to the reference over the timed ticks"));
}

/// Figures of one benchmark run.
struct ControlBenchmarkResult {
  ControlBenchmarkStatus status = ControlBenchmarkStatus::ok;
  /// What went wrong when status is not ok, naming the phase ("MuJoCo warned 'bad qacc' 3 times
  /// (first at dof 6) while running 'osc' …"); empty when ok.
  std::string message;
  std::string robot;       ///< model name
  std::string frame;       ///< chain frame
  int joints = 0;          ///< chain size n
  double timestep = 0.0;   ///< physics timestep [s]
  double frequency = 0.0;  ///< reference frequency actually used [Hz]
  int steps = 0;           ///< ticks per controller
  /// One entry per controller, in order, then one named "observer" (see the protocol).
  std::vector<ControllerBenchmark> controllers;
  double osc_real_time_factor = 0.0;      ///< OSC compute + mj_step1/2, one thread
  double passive_real_time_factor = 0.0;  ///< mj_step alone (replayed torques)
  double osc_step_us = 0.0;               ///< mean wall time per closed-loop step [µs]
  double passive_step_us = 0.0;           ///< mean wall time per mj_step [µs]
  /// Allocations during the whole closed-loop OSC run (controller and physics); −1: not counted.
  std::int64_t loop_allocations = -1;
};

/// The controllers the benchmark times on @p chain, in report order: joint-pd (with gravity
/// compensation), gravity (hold), ct, task-pd, accel, osc, se3, cic, hqp-ac, each with its
/// default options (cic and hqp-ac without a force source).
/// @throws Error from the controllers' constructors.
std::vector<std::unique_ptr<Controller>> default_benchmark_controllers(const Chain& chain);

/// Runs the protocol for @p controllers (torque controllers on the same chain as @p chain; the
/// real-time runs use a default `OperationalSpaceController`).
/// @throws Error when steps < 1, warmup < 0, amplitude < 0 or frequency ≤ 0 (or not finite), when
/// a controller is not a torque controller or has another chain size, when a chain joint is
/// not driven by a motor (torque actuators: load the `_torque` variant of a bundled robot), or
/// when the frame hangs from a joint the chain does not move (a free or ball joint: the base
/// would fall or swing, warned about by MuJoCo or not, and the figures would measure that).
/// A bad state reported by MuJoCo is not thrown: the run stops at the end of that phase with
/// `ControlBenchmarkStatus::faulted` (MuJoCo's warning counters are read after every phase).
ControlBenchmarkResult run_control_benchmark(const Chain& chain,
                                             std::vector<std::unique_ptr<Controller>>& controllers,
                                             const ControlBenchmarkOptions& options = {});

/// Same, with `default_benchmark_controllers(chain)`.
ControlBenchmarkResult run_control_benchmark(const Chain& chain,
                                             const ControlBenchmarkOptions& options = {});

}  // namespace mjarm
