#pragma once
/// @file
/// The validation protocol of the time-optimal path parameterization (`mjarm bench topp`, and
/// the tests with a reduced count): seeded random n-DoF paths through 5–8 waypoints, each timed
/// by TimeOptimalPath and checked —
///  - the limits at the grid points (velocity, and both one-sided accelerations) and at the
///    analytic extrema between them: on each piece of a step (split at the spline's knots) q̈_j
///    is a quadratic in s (q′ quadratic, q″ linear, ṡ² linear), so its extremes are at the ends
///    or its vertex, and q̇_j's at the ends or where q̈_j = 0 (d(q′_j²ṡ²)/ds = 2q′_j·q̈_j);
///  - the duration against the independent grid reference (path/validation/topp_reference.hpp)
///    on the same grid;
///  - sampling allocates nothing (when an allocation counter is given);
///  - the jerk-limited variant through the same waypoints (JerkWaypointTrajectory, j = 10·a per
///    joint): every segment's profiles within v, a and j at their analytic extrema, its duration
///    against the time-optimal path's and against stopping at every waypoint —
/// and the calculation time per path measured.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

struct ToppCase;
class TimeOptimalPath;

/// What to run.
struct ToppValidationOptions {
  int paths = 10000;            ///< random paths
  int dofs = 7;                 ///< joints per path
  std::uint64_t seed = 0;       ///< seed of the path generator
  int grid_intervals = 100;     ///< N of every parameterization (and of the reference)
  int reference_paths = 10000;  ///< the first paths also solved by the reference
  /// Start the reference's Newton steps from TOPP-RA's profile (fewer steps; the minimum does
  /// not depend on the start) instead of its own feasible point.
  bool reference_from_topp = true;
  int refinement_paths = 100;     ///< the first paths also timed on a grid 4× finer
  int jerk_paths = 10000;         ///< the first paths also run through JerkWaypointTrajectory
  bool thread_cpu_clock = false;  ///< time on the thread's CPU clock, not the steady clock
  /// Heap allocations of the process so far (optional; counted around each path's sampling).
  std::function<std::uint64_t()> allocation_count;
  std::function<void(int, int)> progress;  ///< (paths done, paths), now and then (optional)
  std::function<bool()> stop;              ///< asked every 100 paths whether to stop (optional)
  /// Called for every path with its index, case, parameterization and calculation time [µs]
  /// (optional: a peer comparison's record).
  std::function<void(int, const ToppCase&, const TimeOptimalPath&, double)> each_path;
};

constexpr auto declared_fields(const ToppValidationOptions*) {
  using S = ToppValidationOptions;
  return declare<S>(
      "TOPP validation", field("paths", &S::paths, "", Range::at_least(1), "random paths"),
      field("dofs", &S::dofs, "", Range::at_least(1), "joints per path"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of the path generator"),
      field("grid_intervals", &S::grid_intervals, "", Range::closed(2.0, 1e6),
            "grid steps N of every parameterization"),
      field("reference_paths", &S::reference_paths, "", Range::non_negative(),
            "the first paths also solved by the reference QP"),
      field("reference_from_topp", &S::reference_from_topp,
            "start the reference's Newton steps from TOPP-RA's profile"),
      field("refinement_paths", &S::refinement_paths, "", Range::non_negative(),
            "the first paths also timed on a grid 4× finer"),
      field("jerk_paths", &S::jerk_paths, "", Range::non_negative(),
            "the first paths also run through the jerk-limited waypoint variant"),
      field("thread_cpu_clock", &S::thread_cpu_clock,
            "time on the calling thread's CPU clock instead of the steady wall clock"));
}

/// What was measured.
struct ToppValidationResult {
  bool interrupted = false;  ///< the stop request ended the batch early
  int paths = 0;             ///< paths parameterized
  int dofs = 0;
  int grid_intervals = 0;
  int failures = 0;  ///< parameterizations not solved (the problem is always feasible at rest)
  /// max over paths of the relative excess over the limits at the grid points (velocity, both
  /// one-sided accelerations; topp_grid_excess): max(|q̇|/v, |q̈|/a) − 1 (≤ 0 when within)
  double worst_grid_excess = -1.0;
  /// the same at the analytic extrema of every step, grid points included (the discretization's
  /// error between grid points)
  double worst_excess = -1.0;
  int reference_paths = 0;     ///< paths solved by the reference
  int reference_failures = 0;  ///< reference QPs not solved
  /// max over paths of (T − T_ref)/T_ref: how much longer the TOPP-RA duration is than the grid
  /// problem's minimum
  double worst_longer = 0.0;
  double mean_longer = 0.0;  ///< the mean of (T − T_ref)/T_ref
  /// paths where T − T_ref > 1e-6·T_ref: the greedy forward pass is not the grid's minimum
  int longer_paths = 0;
  /// max over paths of (T_ref − T)/T_ref: how much shorter (a definite error beyond rounding:
  /// the reference is the minimum over all feasible grid profiles)
  double worst_shorter = 0.0;
  int refinement_paths = 0;  ///< paths also timed on a 4× finer grid
  /// max over those of |T(N) − T(4N)|/T(4N): how far the grid's duration is from converged
  double worst_refinement_change = 0.0;
  int jerk_paths = 0;     ///< paths run through JerkWaypointTrajectory
  int jerk_failures = 0;  ///< of those, ones it threw on
  /// max over their segments and joints of max(|v|/v_max, |a|/a_max, |j|/j_max) − 1 at the
  /// analytic extrema of every phase (≤ 0 when within)
  double jerk_worst_excess = -1.0;
  int jerk_reduced_waypoints = 0;          ///< waypoint velocities halved to join a segment
  int jerk_stopped_waypoints = 0;          ///< interior waypoints given a stop (shorter segments)
  double jerk_mean_over_topp = 0.0;        ///< mean duration ratio T_jerk / T_topp
  double jerk_mean_over_stops = 0.0;       ///< mean T_jerk / T (stopping at every waypoint)
  double jerk_worst_over_stops = 0.0;      ///< max T_jerk / T (stopping at every waypoint)
  std::uint64_t sampling_allocations = 0;  ///< heap allocations while sampling (when counted)
  bool allocations_counted = false;
  double mean_us = 0.0;                ///< mean parameterization time [µs]
  double median_us = 0.0;              ///< median [µs]
  double p95_us = 0.0;                 ///< 95th percentile [µs]
  double max_us = 0.0;                 ///< slowest [µs]
  double reference_mean_ms = 0.0;      ///< mean reference time [ms] (wall clock)
  double reference_mean_newton = 0.0;  ///< mean Newton steps of the reference
  std::string first_failure;  ///< the first failure or worst-case description (empty: none)
};

/// One random case: waypoints and limits.
struct ToppCase {
  std::vector<Eigen::VectorXd> waypoints;
  Eigen::VectorXd max_velocity, max_acceleration;
};

/// Draws a case of @p dofs joints from @p rng: 5–8 waypoints, the first uniform in [−2, 2] per
/// joint, each next one a step uniform in [−1, 1] per joint from the last; limits log-uniform,
/// v in [0.5, 3], a in [1, 15] per joint.
ToppCase random_topp_case(Random& rng, int dofs);

/// Runs the protocol (see the file comment).
/// @throws Error when an option is outside its declared range.
ToppValidationResult run_topp_validation(const ToppValidationOptions& options);

}  // namespace mjarm
