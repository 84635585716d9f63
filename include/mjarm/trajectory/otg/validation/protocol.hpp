#pragma once
/// @file
/// The validation protocol of the jerk-limited generator (`mjarm bench otg`, and the test suite
/// with a reduced count): seeded random n-DoF cases through JerkLimitedGenerator, every result
/// checked at the analytic extrema of every phase, calculation time and heap allocations per
/// calculation measured, and time optimality checked on a subset of one-DoF cases against two
/// independent methods: a grid search (otg/validation/grid_reference.hpp) and the exhaustive search
/// over the switching structures (otg/validation/structure_search.hpp).

#include <cstdint>
#include <functional>
#include <string>

#include "mjarm/fields.hpp"

namespace mjarm {

/// What to run.
struct OtgValidationOptions {
  int cases = 10000;         ///< random n-DoF cases (position and velocity interface each)
  int dofs = 7;              ///< DoFs per case
  std::uint64_t seed = 0;    ///< seed of the case generator
  double brake_share = 0.1;  ///< share of DoFs that start beyond their limits
  /// One-DoF cases checked against the grid reference (a QP per duration probed: slow).
  int reference_cases = 0;
  int reference_steps = 100;  ///< jerk steps of the reference grid
  /// Starting points per structure of the structure search run on every reference case (0: no
  /// structure search).
  int structure_seeds = 32;
  /// Time the calculations on the calling thread's CPU clock instead of the steady wall clock
  /// (on a shared machine, time the thread was not running is not counted).
  bool thread_cpu_clock = false;
  /// Heap allocations of the process so far (optional; counted around each calculation).
  std::function<std::uint64_t()> allocation_count;
  /// Called now and then with (cases done, cases), reference cases counted after the n-DoF
  /// cases: (cases + k, cases + reference_cases) (optional).
  std::function<void(int, int)> progress;
  /// Asked every thousand cases and before every reference case whether to stop (e.g.
  /// `interrupt_requested` after Ctrl-C; optional). A stop ends the batch with the figures of
  /// the cases done so far and `OtgValidationResult::interrupted` set.
  std::function<bool()> stop;
};

/// The plain fields of `OtgValidationOptions`.
constexpr auto declared_fields(const OtgValidationOptions*) {
  using S = OtgValidationOptions;
  return declare<S>(
      "OTG validation", field("cases", &S::cases, "", Range::at_least(1), "random n-DoF cases"),
      field("dofs", &S::dofs, "", Range::at_least(1), "DoFs per case"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of the case generator"),
      field("brake_share", &S::brake_share, "", Range::closed(0.0, 1.0),
            "share of DoFs that start beyond their limits"),
      field("reference_cases", &S::reference_cases, "", Range::non_negative(),
            "one-DoF cases checked against the grid reference"),
      field("reference_steps", &S::reference_steps, "", Range::at_least(1),
            "jerk steps of the reference grid"),
      field("structure_seeds", &S::structure_seeds, "", Range::non_negative(),
            "starting points per structure of the structure search; 0: none"),
      field("thread_cpu_clock", &S::thread_cpu_clock,
            "time on the calling thread's CPU clock instead of the steady wall clock"));
}

/// What was measured.
struct OtgValidationResult {
  bool interrupted = false;            ///< the stop request ended the batch early
  int cases = 0;                       ///< n-DoF cases run (each interface)
  int dofs = 0;                        ///< DoFs per case
  int braking_dofs = 0;                ///< DoFs that started beyond their limits
  int position_failures = 0;           ///< position calculations that did not succeed
  int velocity_failures = 0;           ///< velocity calculations that did not succeed
  int check_failures = 0;              ///< successful results that failed a check below
  double worst_limit_violation = 0.0;  ///< max over results of (|v|/v_max, |a|/a_max) − 1, ≥ 0
  double worst_target_error = 0.0;     ///< max |end − target| over p, v, a (position interface)
  double worst_velocity_target_error = 0.0;  ///< max |end − target| over v, a (velocity)
  double worst_sync_error = 0.0;             ///< max |DoF duration − synchronized duration| [s]
  std::string first_failure;                 ///< description of the first failure (empty when none)
  std::string first_velocity_failure;        ///< the first velocity-interface failure (empty: none)
  double mean_us = 0.0;                      ///< mean position calculation time [µs]
  double median_us = 0.0;                    ///< median [µs]
  double p99_us = 0.0;                       ///< 99th percentile [µs]
  double max_us = 0.0;                       ///< slowest [µs]
  double velocity_mean_us = 0.0;             ///< mean velocity calculation time [µs]
  std::uint64_t allocations = 0;     ///< heap allocations inside all calculations (when counted)
  bool allocations_counted = false;  ///< whether allocation_count was given
  int reference_cases = 0;           ///< one-DoF cases checked against the grid reference
  /// Reference cases where a grid motion shorter than the computed minimum exists: the minimum
  /// is beaten (a definite error, since a grid motion is a true motion).
  int optimality_beaten = 0;
  /// Reference cases where no grid motion exists within 3 % above the computed minimum (checked
  /// when the grid's velocity margin j·h²/8 is ≤ 1 % of v_max): the grid is too coarse for the
  /// profile's short phases, or the minimum is too short to be right.
  int reference_not_within = 0;
  /// n-DoF cases (the first reference_cases) whose limiting DoF was checked: no grid motion
  /// of that DoF (after its brake) just shorter than the synchronized duration exists.
  int sync_reference_cases = 0;
  int sync_mismatches = 0;              ///< of those, cases where one exists
  int blocked_checked = 0;              ///< blocked intervals probed by the reference
  int blocked_mismatches = 0;           ///< of those, midpoints where a grid motion exists
  /// One-DoF cases drawn until they have a blocked interval (reference_cases / 4 of them; such
  /// cases are about 1 % of random draws): each interval's midpoint is probed as above, and the
  /// durations 1 % of its width outside its ends must get a profile (fixed_time_profile).
  int blocked_cases = 0;
  int blocked_end_failures = 0;  ///< of their interval ends, ones without a profile just outside
  /// Of those ends, where the grid is fine enough (j·h²/8 ≤ 1 % of v_max), ones where neither
  /// the reference grid nor one three times finer has a motion just outside (grid resolution, or
  /// an end in the wrong place).
  int blocked_end_not_confirmed = 0;
  std::string first_reference_failure;  ///< the first reference mismatch (empty when none)

  /// Reference cases (both kinds above) also given to the structure search.
  int structure_cases = 0;
  /// Of those, cases whose search missed t_min or a blocked interval's end with
  /// structure_seeds and was run again with four times as many (the counts below are after it).
  int structure_retries = 0;
  /// Cases where the search found no motion at all although the generator did.
  int structure_not_found = 0;
  /// Cases where the search's shortest motion is shorter than t_min by more than 1e-9 relative:
  /// the minimum is beaten (a definite error, since every solution of the search is a motion).
  int structure_shorter = 0;
  /// Cases where the search's shortest motion is longer than t_min by more than 1e-9 relative
  /// (the search missed the minimum's structure, or t_min is not a motion).
  int structure_longer = 0;
  /// Cases where a motion the search found has a duration inside a blocked interval (by more than
  /// 1e-9 relative): the interval is not blocked (a definite error).
  int structure_inside_blocked = 0;
  int structure_blocked_ends = 0;  ///< blocked interval ends of those cases
  /// Of those ends, ones that are not the duration of an extremal motion the search found (within
  /// 1e-9 relative): the search missed it, or the end is in the wrong place.
  int structure_blocked_ends_missing = 0;
  double structure_mean_ms = 0.0;       ///< mean search time per case [ms] (wall clock)
  std::string first_structure_failure;  ///< the first structure-search mismatch (empty: none)
};

/// Runs the protocol (see the file comment).
/// @throws Error when cases < 1, dofs < 1, brake_share is outside [0, 1] or structure_seeds < 0.
OtgValidationResult run_otg_validation(const OtgValidationOptions& options);

}  // namespace mjarm
