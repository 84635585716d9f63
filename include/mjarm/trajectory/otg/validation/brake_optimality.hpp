#pragma once
/// @file
/// The validation of the generator's brake (`mjarm bench otg-brake`, and the test suite with a
/// reduced count): seeded random n-DoF cases whose every DoF starts beyond its limits or cannot
/// avoid overshooting them. Per DoF, the duration of its brake and its time-optimal profile
/// together is compared with the best feasible one, for the standard brake (append_brake) and
/// for the generator's (append_optimal_brake):
/// - on every DoF, the best over a scan of its brake family (otg/brake.hpp) — members uniform in
///   the end acceleration and in the settled velocity, each followed by step 1;
/// - on the first `structure_cases` DoFs, the independent exhaustive structure search
///   (otg/validation/structure_search.hpp), which searches the brake's end with the motion after
///   it and shares no code with the generator.
/// Every n-DoF result is also checked: limits at the analytic extrema after the brakes, each
/// brake in the brake's order and into the startable states, the end on target, one duration.

#include <cstdint>
#include <functional>
#include <string>

#include "mjarm/fields.hpp"

namespace mjarm {

/// What to run.
struct BrakeOptimalityOptions {
  int cases = 10000;          ///< random n-DoF cases (every DoF beyond its limits)
  int dofs = 7;               ///< DoFs per case
  std::uint64_t seed = 0;     ///< seed of the case generator
  /// Brake-family members scanned per DoF (half uniform in the end acceleration, half in the
  /// settled velocity).
  int family_members = 1000;
  int structure_cases = 0;    ///< DoFs also given to the structure search (the first ones)
  int structure_seeds = 16;   ///< starting points per structure of that search
  /// Called now and then with (DoFs done, DoFs) (optional).
  std::function<void(int, int)> progress;
  /// Asked every case whether to stop (optional); the figures are then those of the cases done.
  std::function<bool()> stop;
};

constexpr auto declared_fields(const BrakeOptimalityOptions*) {
  using S = BrakeOptimalityOptions;
  return declare<S>(
      "brake optimality", field("cases", &S::cases, "", Range::at_least(1), "random n-DoF cases"),
      field("dofs", &S::dofs, "", Range::at_least(1), "DoFs per case"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of the case generator"),
      field("family_members", &S::family_members, "", Range::at_least(2),
            "brake-family members scanned per DoF"),
      field("structure_cases", &S::structure_cases, "", Range::non_negative(),
            "DoFs also given to the structure search"),
      field("structure_seeds", &S::structure_seeds, "", Range::at_least(1),
            "starting points per structure of the structure search"));
}

/// Durations of one brake against the best feasible ones.
struct BrakeDurationFigures {
  int longer = 0;            ///< DoFs longer than the best by more than 1e-9 relative
  double worst_ratio = 1.0;  ///< the largest duration / best
  int shorter = 0;           ///< DoFs shorter than the best by more than 1e-9 relative
};

/// What was measured.
struct BrakeOptimalityResult {
  bool interrupted = false;         ///< the stop request ended the batch early
  int cases = 0;                    ///< n-DoF cases run
  int dofs = 0;                     ///< DoFs per case
  int braking_dofs = 0;             ///< DoFs (all started beyond their limits)
  int with_choice = 0;              ///< of those, DoFs whose brake family has more than one member
  BrakeDurationFigures standard;    ///< append_brake + step 1, against the family scan
  BrakeDurationFigures optimal;     ///< the generator's brake + step 1, against the family scan
  int failures = 0;                 ///< n-DoF calculations that did not succeed
  int check_failures = 0;           ///< successful results failing a check (see the file)
  double worst_limit_excess = 0.0;  ///< after the brakes, relative, ≥ 0
  double worst_target_error = 0.0;  ///< max |end − target| over p, v, a
  double worst_sync_error = 0.0;    ///< max |DoF duration − synchronized duration| [s]
  int structure_cases = 0;          ///< DoFs given to the structure search
  int structure_not_found = 0;      ///< of those, ones where it found no motion
  BrakeDurationFigures structure_standard;  ///< the standard brake against the search
  BrakeDurationFigures structure_optimal;   ///< the generator's brake against the search
  double structure_mean_ms = 0.0;           ///< mean search time per DoF [ms] (wall clock)
  std::string first_failure;                ///< the first failure or mismatch (empty: none)
  /// The first DoF whose duration differs from the structure search's (empty: none).
  std::string first_structure_mismatch;
};

/// Runs the protocol (see the file).
/// @throws Error when an option is outside its declared range.
BrakeOptimalityResult run_brake_optimality(const BrakeOptimalityOptions& options);

}  // namespace mjarm
