#pragma once
/// @file
/// `JerkProfile`: one degree of freedom moved by piecewise-constant jerk (at most 16 phases: a
/// brake pre-trajectory of up to 3 phases and a jerk-limited profile of up to 13), with its state
/// at any time and the analytic extrema of velocity and acceleration over every phase.
/// `JerkPhases`: the seven phases of one profile structure without a start state, the compact
/// form in which the solvers pass profiles around. Also the per-DoF `JerkLimits` and the
/// `KinematicState` (p, v, a) the generator works on.

#include <array>

#include "mjarm/fields.hpp"

namespace mjarm {

struct TrajectorySample;  // trajectory/trajectory_sample.hpp

/// Symmetric limits of one degree of freedom: |v| ≤ velocity, |a| ≤ acceleration, |j| ≤ jerk,
/// in the DoF's unit u (m or rad): [u/s], [u/s²], [u/s³]. All must be positive and finite.
struct JerkLimits {
  double velocity = 1.0;      ///< v_max [u/s]
  double acceleration = 1.0;  ///< a_max [u/s²]
  double jerk = 1.0;          ///< j_max [u/s³]
};

constexpr auto declared_fields(const JerkLimits*) {
  using S = JerkLimits;
  return declare<S>("jerk limits",
                    field("velocity", &S::velocity, "u/s", Range::positive(), "v_max"),
                    field("acceleration", &S::acceleration, "u/s²", Range::positive(), "a_max"),
                    field("jerk", &S::jerk, "u/s³", Range::positive(), "j_max"));
}

/// Position, velocity and acceleration of one degree of freedom.
struct KinematicState {
  double p = 0.0;  ///< position [u]
  double v = 0.0;  ///< velocity [u/s]
  double a = 0.0;  ///< acceleration [u/s²]
};

/// The state of a profile at one instant, with the jerk that acts then.
struct JerkSample {
  double p = 0.0;  ///< position [u]
  double v = 0.0;  ///< velocity [u/s]
  double a = 0.0;  ///< acceleration [u/s²]
  double j = 0.0;  ///< jerk [u/s³]
};

/// Extreme velocity and acceleration over a profile, found analytically per phase (acceleration
/// is linear in a phase: extremes at its ends; velocity is quadratic: extremes at the ends or
/// where the acceleration crosses zero inside).
struct JerkExtrema {
  double v_min = 0.0;  ///< lowest velocity [u/s]
  double v_max = 0.0;  ///< highest velocity [u/s]
  double a_min = 0.0;  ///< lowest acceleration [u/s²]
  double a_max = 0.0;  ///< highest acceleration [u/s²]
};

/// A motion of one DoF under piecewise-constant jerk: phases i = 0 … size−1 of duration tᵢ ≥ 0
/// and jerk jᵢ from a start state. Fixed capacity, no allocation.
class JerkProfile {
 public:
  /// Most phases a profile holds: a brake (≤ 3) and a synchronized profile (≤ 13, the blend of
  /// two seven-phase profiles, otg/fixed_time.hpp).
  static constexpr int kMaxPhases = 16;

  /// An empty profile resting at the origin.
  JerkProfile() = default;

  /// Restarts the profile at @p start with no phases.
  void reset(const KinematicState& start) noexcept;
  /// Appends a phase of @p duration [s] (≥ 0) with constant @p jerk [u/s³]; returns false (and
  /// changes nothing) when the profile is full.
  bool append(double jerk, double duration) noexcept;
  /// Appends a cruise of @p duration [s]: zero jerk at zero acceleration. The acceleration at its
  /// start, zero up to round-off by construction of the caller, is set to exactly zero, so that a
  /// long cruise does not integrate that round-off into the position. False when full.
  bool append_cruise(double duration) noexcept;

  /// Drops the phases from index @p size on (nothing when the profile is not longer).
  void truncate(int size) noexcept {
    if (size >= 0 && size < size_) size_ = size;
  }

  /// Number of phases.
  int size() const noexcept { return size_; }
  /// Total duration [s].
  double duration() const noexcept { return start_time_[size_]; }
  /// Time at which phase @p i starts [s] (duration() for i = size()).
  double duration_until(int i) const noexcept { return start_time_[i]; }
  /// Jerk of phase @p i [u/s³].
  double jerk(int i) const noexcept { return jerk_[i]; }
  /// Duration of phase @p i [s].
  double phase_duration(int i) const noexcept { return start_time_[i + 1] - start_time_[i]; }
  /// The state at the start.
  KinematicState start() const noexcept { return state_[0]; }
  /// The state at the end of the last phase.
  KinematicState end() const noexcept { return state_[size_]; }

  /// The state at time @p t [s] from the start. Before 0 it is the start state; after the end
  /// the motion continues with the final acceleration and zero jerk (a constant-acceleration
  /// extrapolation, which is rest when the target acceleration and velocity are zero).
  JerkSample at(double t) const noexcept;
  /// One coordinate (a `TrajectoryProfile` of dofs() = 1).
  int dofs() const noexcept { return 1; }
  /// `at(t)` as a `TrajectorySample` of one coordinate (trajectory/trajectory_sample.hpp).
  void at(double t, TrajectorySample& sample) const;

  /// Extreme velocity and acceleration over phases @p first_phase … size−1 (analytic, see
  /// JerkExtrema); 0 covers [0, duration()].
  JerkExtrema extrema(int first_phase = 0) const noexcept;

  /// True when every phase keeps |v| ≤ limits.velocity·(1 + @p relative) and
  /// |a| ≤ limits.acceleration·(1 + @p relative), and every phase's |jerk| ≤ limits.jerk·(1 +
  /// @p relative), checked at the analytic extrema.
  bool within(const JerkLimits& limits, double relative) const noexcept;

 private:
  std::array<double, kMaxPhases> jerk_{};
  std::array<double, kMaxPhases + 1> start_time_{};
  std::array<KinematicState, kMaxPhases + 1> state_{};
  int size_ = 0;
};

/// The phases of a seven-phase profile (otg/min_time.hpp) without a start state: phase
/// i lasts duration[i] ≥ 0 [s] with jerk jerk[i] [u/s³]; phases of zero duration are kept (a
/// profile structure has fixed slots). Slot kCruise, when it has a duration and zero jerk, is the
/// velocity plateau at zero acceleration (appended with JerkProfile::append_cruise()).
struct JerkPhases {
  static constexpr int kSize = 7;        ///< number of phase slots
  static constexpr int kCruise = 3;      ///< the slot of the velocity plateau
  std::array<double, kSize> jerk{};      ///< jerk of each phase [u/s³]
  std::array<double, kSize> duration{};  ///< duration of each phase [s]

  /// Sum of the durations [s].
  double total() const noexcept;
  /// The state reached from @p start at the end of the last phase.
  KinematicState end(const KinematicState& start) const noexcept;
  /// Appends the phases of nonzero duration to @p profile; false when it is full.
  bool append_to(JerkProfile& profile) const noexcept;
};

/// The state reached from @p s after @p t [s] of constant jerk @p j.
inline KinematicState integrate_jerk(const KinematicState& s, double j, double t) noexcept {
  return {s.p + t * (s.v + t * (0.5 * s.a + t * (j / 6.0))), s.v + t * (s.a + t * (0.5 * j)),
          s.a + t * j};
}

}  // namespace mjarm
