#pragma once
/// @file
/// `JerkWaypointTrajectory`: a jerk-limited trajectory through a path's waypoints that passes
/// the interior ones in motion (as Ruckig Pro's intermediate waypoints do), from a
/// TimeOptimalPath: each waypoint gets the velocity the time-optimal parameterization has there
/// (q′(s_k)·ṡ(s_k), zero acceleration), and each segment between waypoints is the jerk-limited
/// generator's synchronized time-optimal motion (otg/generator.hpp) between those states. A
/// segment the generator cannot join (the next waypoint's velocity out of reach within the
/// segment) is retried with that velocity halved, up to a stop there; then, left to right, an
/// interior waypoint whose two segments are shorter through a stop gets the stop. Every segment
/// is the generator's checked result: within v, a and j at the analytic extrema of every phase.
///
/// The segments do not follow the spline between waypoints (each joint runs its own profile,
/// synchronized in time): the waypoints are passed exactly, the path between them is the
/// generator's.

#include <Eigen/Core>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

/// How the waypoint velocities are chosen.
struct JerkWaypointOptions {
  /// The share of the time-optimal path's speed at each waypoint (1: all of it; 0: stop at
  /// every waypoint).
  double velocity_share = 1.0;
  /// Halvings of a waypoint's velocity tried before stopping there.
  int retries = 6;
};

constexpr auto declared_fields(const JerkWaypointOptions*) {
  using S = JerkWaypointOptions;
  return declare<S>("jerk waypoints",
                    field("velocity_share", &S::velocity_share, "", Range::closed(0.0, 1.0),
                          "share of the time-optimal speed at each waypoint"),
                    field("retries", &S::retries, "", Range::closed(0.0, 60.0),
                          "halvings of a waypoint's velocity before a stop there"));
}

/// Jerk-limited segments through a TimeOptimalPath's waypoints (see the file). A
/// `TrajectoryProfile`; sampling allocates nothing.
class JerkWaypointTrajectory {
 public:
  /// Through the waypoints of @p topp's path under its velocity and acceleration limits and
  /// @p max_jerk [u/s³] (n entries).
  /// @throws Error when @p topp is not solved, a jerk limit is not positive and finite (named),
  ///         an option is out of range, or a segment fails even with a stop at its end.
  JerkWaypointTrajectory(const TimeOptimalPath& topp, const Eigen::VectorXd& max_jerk,
                         const JerkWaypointOptions& options = {});

  Eigen::Index dofs() const noexcept { return static_cast<Eigen::Index>(segments_.front().dofs()); }
  /// The total duration [s].
  double duration() const noexcept { return starts_.back(); }
  /// The number of segments (waypoints − 1).
  int segments() const noexcept { return static_cast<int>(segments_.size()); }
  /// Segment @p k: the generator holding its motion.
  const JerkLimitedGenerator& segment(int k) const {
    return segments_.at(static_cast<std::size_t>(k));
  }
  /// The start time of segment @p k (k = segments() gives the duration) [s].
  double segment_start(int k) const { return starts_.at(static_cast<std::size_t>(k)); }
  /// The velocity at each waypoint (first and last zero) [u/s].
  const std::vector<Eigen::VectorXd>& waypoint_velocities() const noexcept { return velocities_; }
  /// Waypoint velocities that were halved to make their segment feasible.
  int reduced_waypoints() const noexcept { return reduced_; }
  /// Interior waypoints given a stop because their two segments were shorter with one.
  int stopped_waypoints() const noexcept { return stopped_; }

  /// q, q̇, q̈ and q⃛ at @p t [s] (clamped to [0, T]) into @p sample (resized to n when it is
  /// not; no allocation once it is).
  void at(double t, TrajectorySample& sample) const;

 private:
  std::vector<JerkLimitedGenerator> segments_;
  std::vector<double> starts_;
  std::vector<Eigen::VectorXd> velocities_;
  int reduced_ = 0;
  int stopped_ = 0;
};

}  // namespace mjarm
