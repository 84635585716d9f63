#pragma once
/// @file
/// The TRAC-IK benchmark protocol for pose IK solvers.
///
/// For each of N samples: draw a joint configuration uniformly inside the limits (unlimited
/// hinges in [−π, π], unlimited slides in [−1, 1] m), compute its pose X_WT by forward
/// kinematics, and ask the solver for that pose starting from the middle of the joint ranges
/// (`IkSeedMode::mid_range`) or from a second, independent uniform configuration
/// (`IkSeedMode::random`). A sample succeeds when the returned q is finite, within the joint
/// limits, and its target-frame error (pose_tolerance.hpp) is within 1e-5 on each of x, y, z (m)
/// and roll, pitch, yaw (rad) — checked here by our own forward kinematics, not by trusting the
/// solver's status. Every solve is timed with std::chrono::steady_clock; failed solves run to
/// their timeout and count in the time statistics like any other. Times are wall-clock by
/// default; `IkBenchmarkClock::thread_cpu` measures the solver's work on a shared machine.

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>

#include "mjarm/ik/global_ik.hpp"
#include "mjarm/ik/pose_tolerance.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// Where each benchmark solve starts.
enum class IkSeedMode {
  mid_range,  ///< the middle of every joint range (Chain::center())
  random      ///< a uniform random configuration inside the limits, independent of the target
};

constexpr auto declared_names(const IkSeedMode*) {
  using M = IkSeedMode;
  return std::array{EnumName{M::mid_range, "mid_range", "the middle of every joint range"},
                    EnumName{M::random, "random", "a uniform random configuration"}};
}

/// Which clock times the solves and enforces the budget.
enum class IkBenchmarkClock {
  /// std::chrono::steady_clock, the solver's own timeout is the budget: the protocol as
  /// published, and what a real-time caller sees — including any time the process is not
  /// running (a busy or shared machine).
  wall,
  /// CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID): a solve succeeds only if it
  /// also used at most `timeout` of CPU time, and a slower one is charged exactly `timeout`.
  /// The built-in global solver gets a wall timeout of 20 × `timeout` so that descheduling
  /// does not cut it short; its iterates do not depend on time, so this reproduces the wall
  /// protocol of an idle core on a shared machine. Custom solvers need a roomy timeout too.
  thread_cpu
};

constexpr auto declared_names(const IkBenchmarkClock*) {
  using C = IkBenchmarkClock;
  return std::array{EnumName{C::wall, "wall", "the steady clock"},
                    EnumName{C::thread_cpu, "thread_cpu", "the calling thread's CPU time"}};
}

/// A solver under test: a name for the report and a function (X_WT, q_seed) → IkResult.
struct IkBenchmarkSolver {
  std::string name;  ///< e.g. "global_ik(alternate, speed)"
  std::function<IkResult(const Pose& X_WT, const Eigen::VectorXd& q_seed)> solve;
};

/// Protocol parameters.
struct IkBenchmarkOptions {
  int samples = 10000;                           ///< N (≥ 1)
  std::uint64_t seed = 0;                        ///< seeds the sample (and random-seed) generator
  IkSeedMode seed_mode = IkSeedMode::mid_range;  ///< where solves start
  /// Solver budget; used by the overload that builds the global solver (and recorded in the
  /// result). A custom solver enforces its own timeout.
  std::chrono::duration<double> timeout = std::chrono::milliseconds(5);
  IkBenchmarkClock clock = IkBenchmarkClock::wall;  ///< how solves are timed
  /// Restarts the built-in global solver may make per solve (≥ 0; GlobalIkOptions::max_restarts).
  /// The protocol's default is unbounded: the budget decides. With a cap and a budget far beyond
  /// it, the outcome of every sample is the same on any machine (the iterates do not depend on
  /// time): what the tests use.
  int max_restarts = std::numeric_limits<int>::max();
  PoseTolerance tolerance;  ///< success test (TRAC-IK: 1e-5 on each component)
  /// Called after every sample with (samples done, N); may be empty.
  std::function<void(int done, int total)> progress;
  /// Asked before every sample whether to stop (e.g. `interrupt_requested` after Ctrl-C); may
  /// be empty. A stop ends the run with the figures of the samples done
  /// (`IkBenchmarkResult::interrupted`).
  std::function<bool()> stop;
};

/// The plain fields of `IkBenchmarkOptions` (the timeout and the tolerance are checked by hand).
constexpr auto declared_fields(const IkBenchmarkOptions*) {
  using S = IkBenchmarkOptions;
  return declare<S>(
      "IK benchmark", field("samples", &S::samples, "", Range::at_least(1), "N"),
      field("seed", &S::seed, "", Range::non_negative(), "seeds the sample generator"),
      field("seed_mode", &S::seed_mode, "where solves start"),
      field("clock", &S::clock, "how solves are timed"),
      field("max_restarts", &S::max_restarts, "", Range::non_negative(),
            "restarts the built-in global solver may make per solve"));
}

/// Figures of one benchmark run.
struct IkBenchmarkResult {
  std::string solver;  ///< IkBenchmarkSolver::name
  std::string robot;   ///< model name
  std::string frame;   ///< chain frame name
  IkSeedMode seed_mode = IkSeedMode::mid_range;
  IkBenchmarkClock clock = IkBenchmarkClock::wall;
  double timeout_ms = 0.0;       ///< IkBenchmarkOptions::timeout [ms]
  bool interrupted = false;      ///< the stop request ended the run early
  int samples = 0;               ///< N, or the samples done when interrupted
  int successes = 0;             ///< samples meeting the success test
  double success_rate = 0.0;     ///< successes / N, in [0, 1]
  double mean_time_ms = 0.0;     ///< mean wall-clock time per solve [ms], failures included
  double median_time_ms = 0.0;   ///< median [ms]
  double p99_time_ms = 0.0;      ///< 99th percentile (nearest rank) [ms]
  double max_time_ms = 0.0;      ///< slowest solve [ms]
  double mean_iterations = 0.0;  ///< mean IkResult::iterations
  int solver_converged = 0;      ///< solves whose status was converged (cross-check of the test)
};

constexpr auto declared_fields(const IkBenchmarkResult*) {
  using S = IkBenchmarkResult;
  return declare<S>(
      "ik benchmark result", field("solver", &S::solver, "the solver's name"),
      field("seed_mode", &S::seed_mode, "where the solves start"),
      field("timeout_ms", &S::timeout_ms, "ms", "time budget per solve"),
      field("samples", &S::samples, "", "N, or the samples done when interrupted"),
      field("successes", &S::successes, "", "samples meeting the success test"),
      field("success_rate", &S::success_rate, "", "successes / N"),
      field("mean_time_ms", &S::mean_time_ms, "ms", "mean time per solve, failures included"),
      field("median_time_ms", &S::median_time_ms, "ms", "median time per solve"),
      field("p99_time_ms", &S::p99_time_ms, "ms", "99th percentile (nearest rank)"),
      field("max_time_ms", &S::max_time_ms, "ms", "slowest solve"),
      field("mean_iterations", &S::mean_iterations, "", "mean iterations per solve"),
      field("solver_converged", &S::solver_converged, "",
            "solves whose status was converged (cross-check of the test)"),
      field("robot", &S::robot, "the model's name"), field("frame", &S::frame, "the chain's frame"),
      field("clock", &S::clock, "what the times measure"),
      field("interrupted", &S::interrupted, "the stop request ended the run early"));
}

/// The default solver of the protocol: `GlobalIk` on @p chain with @p options, named
/// "global_ik(<methods>, <mode>)".
/// @throws Error for invalid options.
IkBenchmarkSolver global_ik_solver(const Chain& chain, const GlobalIkOptions& options = {});

/// Runs the protocol for @p solver on @p chain.
/// @throws Error when samples < 1 or the tolerance is invalid (a solver's own exceptions pass
/// through).
IkBenchmarkResult run_ik_benchmark(const Chain& chain, const IkBenchmarkSolver& solver,
                                   const IkBenchmarkOptions& options);

/// Runs the protocol for `GlobalIk` in speed mode with options.timeout (× 20 for the
/// thread_cpu clock, see IkBenchmarkClock), options.max_restarts, options.tolerance, and
/// options.seed as the solver's restart seed too.
IkBenchmarkResult run_ik_benchmark(const Chain& chain, const IkBenchmarkOptions& options);

}  // namespace mjarm
