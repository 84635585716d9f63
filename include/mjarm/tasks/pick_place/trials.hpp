#pragma once
/// @file
/// Randomized pick-and-place trials run in parallel, and the figures of a batch: success rate,
/// failure reasons, placement error, cycle time, grasp force, weld jump.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "mjarm/tasks/pick_place/pick_place.hpp"

namespace mjarm {

/// How to run a batch.
struct PickPlaceBatchOptions {
  /// Every trial's options; trial k runs with seed = base.seed + k (so any trial can be
  /// replayed alone with that seed). base.record and base.video are ignored (see `record`).
  PickPlaceOptions base;
  int trials = 10;  ///< ≥ 1
  int threads = 0;  ///< worker threads, ≥ 0; 0 = one per core (`std::thread::hardware_concurrency`)
  /// When set, trial k records into record / "seed_<seed>" (a full `Recorder` folder each).
  std::filesystem::path record;
  /// Called after each finished trial with the number done so far, from the worker that finished
  /// it, one call at a time (the batch holds a lock around it).
  std::function<void(int)> on_progress;
};

/// Mean and largest of a figure over some trials (NaN when none).
struct PickPlaceStat {
  int count = 0;
  double mean = PickPlaceTrace::kNaN;
  double max = PickPlaceTrace::kNaN;
  /// Adds @p value (NaN is skipped).
  void add(double value) noexcept;
};

/// The figures of a batch. Trials cut short by Ctrl-C are not counted.
struct PickPlaceSummary {
  int trials = 0;  ///< trials that ran to their end (successes and failures)
  int successes = 0;
  int interrupted = 0;  ///< trials cut short (not in `trials`)
  /// Failures per reason, indexed by `PickPlaceFailure` (index 0, none, stays 0).
  std::array<int, 12> failures{};
  PickPlaceStat placement_error;  ///< [m], successful trials
  PickPlaceStat cycle_time;       ///< [s], successful trials
  PickPlaceStat grasp_force;      ///< transport mean per trial [N], successful trials
  PickPlaceStat weld_jump;        ///< [m], trials whose weld was switched on
  PickPlaceStat weld_settle;      ///< [m], trials whose weld was switched on
  PickPlaceStat max_slip;         ///< [m], trials that closed on the object
  /// Success rate in [0, 1] (NaN without trials).
  double success_rate() const noexcept;
};

/// Summarizes reports (in any order).
PickPlaceSummary summarize(const std::vector<PickPlaceReport>& reports);

/// What a batch did.
struct PickPlaceBatch {
  std::vector<PickPlaceReport> reports;  ///< finished trials, in seed order
  PickPlaceSummary summary;
  bool interrupted = false;  ///< Ctrl-C stopped the batch (see mjarm/interrupt.hpp)
};

/// Runs `trials` trials on `threads` workers. A trial that fails — also by diverging — is a
/// report with its reason; the batch goes on. Ctrl-C (an `InterruptGuard` alive) stops every
/// worker at its next control tick; the trials finished so far are returned.
/// @throws Error for bad counts, or the first error a trial raised before it ran (an unknown
///         robot, an unreachable object: every trial would raise it), after the workers stopped.
PickPlaceBatch run_pick_place_trials(const PickPlaceBatchOptions& options);

}  // namespace mjarm
