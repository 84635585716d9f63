#pragma once
/// @file
/// `JerkBlock`: what step 1 of the jerk-limited generator learns about one degree of freedom —
/// its time-optimal profile, every other extremal profile, and the intervals of durations in
/// which it has no profile at all ("blocked intervals", Berscheid & Kröger 2021), which the
/// synchronization must skip.

#include <array>

#include "mjarm/trajectory/otg/profile.hpp"

namespace mjarm {

/// An open interval of durations (lower, upper) [s].
struct JerkInterval {
  double lower = 0.0;  ///< start [s]
  double upper = 0.0;  ///< end [s]
};

/// The minimum duration of one DoF, its profile, and the durations it cannot take.
struct JerkBlock {
  /// Most blocked intervals recorded.
  static constexpr int kMaxBlocked = 4;
  /// Most distinct profile durations recorded.
  static constexpr int kMaxDurations = 12;

  KinematicState start;  ///< the state every profile of the block starts from
  double t_min = 0.0;    ///< the minimum duration [s]
  /// Blocked intervals, ascending: no profile has a duration inside one.
  std::array<JerkInterval, kMaxBlocked> blocked{};
  int blocked_count = 0;  ///< how many of `blocked` are set
  /// The distinct durations of every valid extremal profile found, ascending; t_min first.
  std::array<double, kMaxDurations> durations{};
  /// The phases of each entry of `durations` (the interval ends are reached exactly by them).
  std::array<JerkPhases, kMaxDurations> profiles{};
  int duration_count = 0;  ///< how many of `durations` are set

  /// The time-optimal profile (of t_min) from `start`.
  JerkProfile fastest() const noexcept;
  /// Adds a profile of @p duration to `durations` (ascending; a duration within 1e-9 relative
  /// of one already there is not added again; when full, the longest is dropped).
  void record(double duration, const JerkPhases& phases) noexcept;
  /// The profile whose duration is within round-off (1e-10 relative) of @p duration, or nullptr.
  const JerkPhases* profile_of(double duration) const noexcept;
  /// Rebuilds the blocked intervals from `durations` by their parity: with 2k + 1 distinct
  /// extremal durations d₀ < d₁ < … the feasible durations are [d₀, d₁] ∪ [d₂, d₃] ∪ … ∪
  /// [d₂ₖ, ∞), so (d₁, d₂), (d₃, d₄) … are blocked.
  void set_blocked_from_durations() noexcept;
  /// True when @p t is below t_min or inside a blocked interval.
  bool is_blocked(double t) const noexcept;
};

}  // namespace mjarm
