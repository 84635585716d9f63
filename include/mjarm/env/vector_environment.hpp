#pragma once
/// @file
/// `VectorEnvironment`: N environments of one task stepped together on a thread pool, with
/// automatic resets and the results in contiguous batch arrays.

#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "mjarm/env/environment.hpp"
#include "mjarm/env/worker_pool.hpp"

namespace mjarm {

/// N independent `Environment`s of one task. Environment i runs its own clone of the task
/// (sharing the immutable model) with `EnvironmentOptions::seed` = splitmix64(seed + i), so its
/// episode seeds, and everything it computes, depend only on (seed, i) and on its actions: the
/// batch arrays are the same bit for bit whatever the number of threads.
///
/// Batch arrays, row i for environment i, written by `reset` and `step`:
/// - `step_types()` (N), `ends()` (N);
/// - `rewards()`, `discounts()` (N): NaN on FIRST rows (dm_env's "none");
/// - `observations()` (N × observation size, row-major, the spec's arrays back to back).
///
/// Automatic reset: a `step` on an environment whose last time step was LAST resets it
/// (`Environment::reset()`, the next seed of its sequence) and returns its FIRST time step; its
/// action row is checked but otherwise ignored. `step` allocates nothing when no task
/// allocates in its reset (none of the bundled ones does).
class VectorEnvironment {
 public:
  /// @param count environments N (1 to 4096)
  /// @param threads 1 to 256 (more than N leaves threads idle)
  /// @throws Error for counts out of range, and as `Environment`.
  VectorEnvironment(std::unique_ptr<EnvTask> task, const EnvironmentOptions& options, int count,
                    int threads);
  /// The task called @p task. @throws Error for an unknown task, and as above.
  VectorEnvironment(std::string_view task, const EnvironmentOptions& options, int count,
                    int threads);
  ~VectorEnvironment();
  VectorEnvironment(const VectorEnvironment&) = delete;
  VectorEnvironment& operator=(const VectorEnvironment&) = delete;

  /// Resets every environment (the next seed of each one's sequence): every row FIRST.
  /// @throws Error after `close()`.
  void reset();
  /// One step of every environment with @p actions (N × action size, row i for environment
  /// i); environments whose last step was LAST are reset instead.
  /// @throws Error before the first reset, for a wrong size, a NaN/inf value, or (with
  ///         `refuse_out_of_bounds`) a value out of bounds — naming the row and entry; nothing
  ///         is stepped then; after `close()`.
  void step(std::span<const double> actions);
  /// Closes every environment of the batch (`Environment::close`): every later `reset` and
  /// `step` throws `Error`. Closing twice is allowed.
  void close() noexcept;
  /// True after `close()`.
  bool closed() const noexcept { return closed_; }

  int size() const noexcept { return static_cast<int>(environments_.size()); }
  int threads() const noexcept { return pool_.threads(); }
  /// CPU time [s] each thread spent in the last `reset` or `step` (`WorkerPool::last_cpu_seconds`).
  const std::vector<double>& last_thread_cpu_seconds() const noexcept {
    return pool_.last_cpu_seconds();
  }
  /// CPU time [s] of each environment's part of the last `reset` or `step` (N; the thread CPU
  /// clock of the thread that ran it, read before and after: two clock reads per environment).
  std::span<const double> last_env_cpu_seconds() const noexcept { return env_cpu_; }
  const ArraySpec& action_spec() const noexcept { return environments_.front()->action_spec(); }
  const ObservationSpec& observation_spec() const noexcept {
    return environments_.front()->observation_spec();
  }

  std::span<const StepType> step_types() const noexcept { return step_types_; }
  std::span<const EpisodeEnd> ends() const noexcept { return ends_; }
  std::span<const double> rewards() const noexcept { return rewards_; }
  std::span<const double> discounts() const noexcept { return discounts_; }
  std::span<const double> observations() const noexcept { return observations_; }
  /// Row @p i of `observations()`.
  std::span<const double> observation(int i) const;
  /// Environment @p i (read-only: stepping goes through the batch).
  const Environment& environment(int i) const {
    return *environments_.at(static_cast<std::size_t>(i));
  }

 private:
  void record(int i, const TimeStep& ts) noexcept;

  std::vector<std::unique_ptr<Environment>> environments_;
  WorkerPool pool_;
  std::vector<StepType> step_types_;
  std::vector<EpisodeEnd> ends_;
  std::vector<double> rewards_, discounts_, observations_;
  std::vector<double> env_cpu_;      // per environment, of the last reset or step
  std::span<const double> actions_;  // the batch being stepped
  bool started_ = false;
  bool closed_ = false;
};

}  // namespace mjarm
