#pragma once
/// @file
/// Trapezoidal velocity profiles: `TrapezoidProfile` (one distance, the classic
/// `trap_profile` / `trap_frac` pair) and `SyncedTrapezoid` (several axes that start and finish
/// together).

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

/// A rest-to-rest move over a distance d ≥ 0 with constant acceleration a up to a cruise speed,
/// a cruise, and a constant deceleration (docs/trajectory.md). With d_acc = v_max²/(2·a_max):
///
/// - trapezoid when 2·d_acc ≤ d: t_acc = v_max/a_max, t_cruise = (d − 2·d_acc)/v_max,
///   peak speed v_max;
/// - triangle when 2·d_acc > d: t_acc = √(d/a_max), t_cruise = 0, peak speed a_max·t_acc;
///
/// and the duration T = 2·t_acc + t_cruise. Units are whatever d is in (u): limits in u/s, u/s².
/// Jerk is zero inside each phase and unbounded (a step of acceleration) at the switches.
class TrapezoidProfile {
 public:
  /// Position, velocity, acceleration and fraction done at one instant.
  struct Sample {
    double position = 0.0;      ///< distance covered [u], 0 … d
    double velocity = 0.0;      ///< [u/s], ≥ 0
    double acceleration = 0.0;  ///< [u/s²]: +a, 0 or −a
    double fraction = 0.0;      ///< position/d ∈ [0, 1] (1 from t = 0 on when d = 0)
  };

  /// The default speed limit of the classic teaching code [m/s].
  static constexpr double kDefaultMaxVelocity = 0.18;
  /// The default acceleration limit of the classic teaching code [m/s²].
  static constexpr double kDefaultMaxAcceleration = 0.9;

  /// The profile of a move over @p distance [u] under @p max_velocity [u/s] and
  /// @p max_acceleration [u/s²]. A zero distance gives a valid zero-duration profile.
  /// @throws Error when the distance is negative or not finite, or a limit is not positive and
  ///         finite (the value is named).
  explicit TrapezoidProfile(double distance, double max_velocity = kDefaultMaxVelocity,
                            double max_acceleration = kDefaultMaxAcceleration);

  /// The distance d [u].
  double distance() const noexcept { return distance_; }
  /// The duration T [s].
  double duration() const noexcept { return duration_; }
  /// The duration of the acceleration phase (= that of the deceleration phase) [s].
  double acceleration_time() const noexcept { return accel_time_; }
  /// The duration of the cruise phase [s] (0 for a triangle).
  double cruise_time() const noexcept { return cruise_time_; }
  /// The highest speed reached [u/s] (v_max for a trapezoid, less for a triangle).
  double peak_velocity() const noexcept { return peak_velocity_; }
  /// The acceleration of the ramps [u/s²] (a_max).
  double acceleration() const noexcept { return acceleration_; }
  /// True when v_max is never reached (2·d_acc > d): the profile is a triangle.
  bool triangular() const noexcept { return triangular_; }

  /// The state at time @p t [s]; t is clamped to [0, T] (NaN gives the start; at t ≥ T the
  /// end, so a zero-duration profile is done at t = 0).
  Sample at(double t) const noexcept;
  /// One coordinate (a `TrajectoryProfile` of dofs() = 1).
  int dofs() const noexcept { return 1; }
  /// `at(t)` as a `TrajectorySample` of one coordinate (jerk 0: the acceleration steps).
  void at(double t, TrajectorySample& sample) const;

  /// The fraction of the distance covered at time @p t [s], in [0, 1] (clamped as `at`).
  double fraction(double t) const noexcept { return at(t).fraction; }

 private:
  double distance_;
  double accel_time_ = 0.0;
  double cruise_time_ = 0.0;
  double duration_ = 0.0;
  double peak_velocity_ = 0.0;
  double acceleration_;
  bool triangular_ = false;
};

/// The classic `trap_profile(dist, v_max, a_max)`: the profile (its duration is
/// `duration()`), with the defaults v_max = 0.18 m/s and a_max = 0.9 m/s².
/// @throws Error as the `TrapezoidProfile` constructor.
TrapezoidProfile trap_profile(double distance,
                              double max_velocity = TrapezoidProfile::kDefaultMaxVelocity,
                              double max_acceleration = TrapezoidProfile::kDefaultMaxAcceleration);

/// The classic `trap_frac(t)`: the fraction of @p profile done at time @p t [s], in [0, 1].
double trap_frac(const TrapezoidProfile& profile, double t) noexcept;

/// Trapezoidal moves of n axes from a start to a goal that start together and finish together:
/// each axis gets its own trapezoid under its own limits, the slowest sets the duration T, and
/// every faster axis i (own duration T_i) is stretched in time by λ_i = T_i/T — which is the
/// trapezoid of the same distance under the scaled limits λ_i·v_max and λ_i²·a_max, the same
/// shape (a triangle stays a triangle) finishing exactly at T.
class SyncedTrapezoid {
 public:
  /// Moves from @p start to @p goal (n values each, any units u per axis) under per-axis
  /// @p max_velocity [u/s] and @p max_acceleration [u/s²] (n values each).
  /// @throws Error when the sizes differ, n is 0, a position is not finite, or a limit is not
  ///         positive and finite (the axis is named).
  SyncedTrapezoid(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                  const Eigen::VectorXd& max_velocity, const Eigen::VectorXd& max_acceleration);

  /// The same limits on every axis.
  /// @throws Error as above.
  SyncedTrapezoid(const Eigen::VectorXd& start, const Eigen::VectorXd& goal, double max_velocity,
                  double max_acceleration);

  /// The number of axes n.
  std::size_t size() const noexcept { return axes_.size(); }
  /// The number of axes n (as a `TrajectoryProfile`).
  Eigen::Index dofs() const noexcept { return static_cast<Eigen::Index>(axes_.size()); }
  /// The common duration T [s] (0 when start equals goal).
  double duration() const noexcept { return duration_; }
  /// The index of the axis that needs the longest time (it moves at its own limits).
  std::size_t limiting_axis() const noexcept { return limiting_axis_; }
  /// Axis @p i's unstretched profile (under its own limits, over |goal_i − start_i|).
  const TrapezoidProfile& axis(std::size_t i) const { return axes_.at(i); }
  /// λ_i = T_i/T ∈ [0, 1]: axis @p i's limits are scaled by λ_i (velocity) and λ_i²
  /// (acceleration).
  double time_scale(std::size_t i) const { return scale_.at(i); }

  /// Position [u], velocity [u/s] and acceleration [u/s²] of every axis at time @p t [s]
  /// (clamped to [0, T]); allocates nothing.
  /// @throws Error when an output does not have n entries.
  void at(double t, Eigen::Ref<Eigen::VectorXd> position, Eigen::Ref<Eigen::VectorXd> velocity,
          Eigen::Ref<Eigen::VectorXd> acceleration) const;
  /// The same into @p sample (resized to n when it is not), jerk 0 (the acceleration steps).
  void at(double t, TrajectorySample& sample) const;

  /// The fraction of the limiting axis's move done at @p t [s], in [0, 1] (other axes may be
  /// a little ahead or behind when their profiles have a different shape: triangle/trapezoid).
  double fraction(double t) const noexcept;

 private:
  Eigen::VectorXd start_;
  Eigen::VectorXd direction_;  // +1, −1 (0 for an axis that does not move)
  std::vector<TrapezoidProfile> axes_;
  std::vector<double> scale_;
  double duration_ = 0.0;
  std::size_t limiting_axis_ = 0;
};

}  // namespace mjarm
