#pragma once
/// @file
/// `PickMonitor`: turns the trace of a tool tip approaching a target into the figures of a pick
/// — time to enter the tolerance, overshoot, steady-state error and the hold result.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string_view>

#include "mjarm/fields.hpp"

namespace mjarm {

/// When a pick counts as done.
struct PickCriteria {
  double tolerance = 1e-3;  ///< the tip is "at" the target when ‖p_WE − p_WT‖ ≤ this [m] (> 0)
  double hold_time = 0.2;   ///< ... and must stay there this long without leaving [s] (> 0)
  /// The steady state is the last this-long stretch of the completed hold [s], in (0, hold_time]:
  /// by then the approach transient that carried the tip into the tolerance has died out.
  double steady_window = 0.1;
};

constexpr auto declared_fields(const PickCriteria*) {
  using S = PickCriteria;
  return declare<S>(
      "pick criteria",
      field("tolerance", &S::tolerance, "m", Range::positive(),
            "the tip is at the target within this"),
      field("hold_time", &S::hold_time, "s", Range::positive(), "and must stay there this long"),
      field("steady_window", &S::steady_window, "s", Range::positive(),
            "the last stretch of the hold judged as the steady state (≤ hold_time)"));
}

/// Checks each criterion against its range and the steady window against the hold time.
/// @param owner who uses the criteria, for the message ("shelf pick")
/// @throws Error "shelf pick: criteria.hold_time must be positive and finite [s], got 0"
void check(const PickCriteria& criteria, std::string_view owner);

/// What one `PickMonitor::observe` saw.
enum class PickEvent {
  none,     ///< nothing changed
  entered,  ///< the tip entered the tolerance: a hold begins
  left,     ///< the tip left the tolerance: the hold is broken (it restarts at the next entry)
  held      ///< the tip stayed inside for the hold time: the pick is done
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const PickEvent*) {
  using E = PickEvent;
  return std::array{EnumName{E::none, "none"}, EnumName{E::entered, "entered"},
                    EnumName{E::left, "left"}, EnumName{E::held, "held"}};
}

/// The figures of one pick. Times are relative to the start of the motion [s]; NaN when the
/// event did not happen.
struct PickMetrics {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  bool held = false;  ///< the tip stayed within tolerance for the hold time
  /// First time the error was ≤ tolerance [s].
  double first_entry_time = kNaN;
  /// Time to enter the tolerance: the start of the stay that completed the hold [s] (equals
  /// first_entry_time when the tip never left after entering). NaN when not held.
  double time_to_tolerance = kNaN;
  /// Time the hold completed (time_to_tolerance + hold_time, on the sample grid) [s].
  double hold_end_time = kNaN;
  /// Largest distance past the target along the approach direction u = (p_WT − p_start)/‖·‖,
  /// max((p_WE − p_WT)·u, 0), over the samples from the first entry to the end of the hold (or
  /// of the trace) [m]. When the start is on the target (no direction), the largest error over
  /// the same samples. 0 when the tip never entered.
  double overshoot = 0.0;
  /// Mean and largest error ‖p_WE − p_WT‖ over the samples of the whole completed hold (entry
  /// sample to completion sample, both included) [m]; NaN when not held. The mean includes the
  /// end of the approach (the tip enters at up to the tolerance and converges from there); the
  /// largest is ≤ tolerance by construction.
  double hold_mean = kNaN;
  double hold_max = kNaN;
  /// Steady-state error: mean and largest ‖p_WE − p_WT‖ over the samples of the last
  /// `steady_window` of the completed hold (t ≥ completion − steady_window) [m]; NaN when not held.
  double steady_state_mean = kNaN;
  double steady_state_max = kNaN;
  /// Largest orientation error passed to `observe` over the whole completed hold [rad]; NaN when
  /// not held.
  double orientation_error_max = kNaN;
  /// How many times the tip left the tolerance after entering.
  int exits = 0;
  /// Error at the last sample observed [m].
  double final_error = kNaN;
  /// Samples observed.
  std::int64_t samples = 0;
};

constexpr auto declared_fields(const PickMetrics*) {
  using S = PickMetrics;
  return declare<S>(
      "pick metrics",
      field("time_to_tolerance", &S::time_to_tolerance, "s",
            "start of the stay that completed the hold; NaN (null) when not held"),
      field("first_entry_time", &S::first_entry_time, "s", "first error ≤ tolerance"),
      field("overshoot", &S::overshoot, "m",
            "largest distance past the target, along the approach"),
      field("steady_state_mean", &S::steady_state_mean, "m",
            "mean error over the hold's last steady window"),
      field("steady_state_max", &S::steady_state_max, "m",
            "largest error over the hold's last steady window"),
      field("hold_mean", &S::hold_mean, "m", "mean error over the completed hold"),
      field("hold_max", &S::hold_max, "m", "largest error over the completed hold"),
      field("orientation_error_max", &S::orientation_error_max, "rad",
            "largest orientation error over the completed hold"),
      field("hold_end_time", &S::hold_end_time, "s", "the hold completed"),
      field("exits", &S::exits, "", "times the tip left the tolerance after entering"),
      field("final_error", &S::final_error, "m", "error at the last sample"),
      field("held", &S::held, "the tip stayed within tolerance for the hold time"),
      field("samples", &S::samples, "", "samples observed"));
}

/// Watches the tip of a tool approach a target point, one sample per control tick, and keeps
/// the figures of `PickMetrics`. Once the hold is complete further samples are ignored.
/// Allocation-free; never throws after construction.
class PickMonitor {
 public:
  /// @param p_start tip position at the start of the motion (world, m)
  /// @param p_target the pick point (world, m)
  /// @throws Error when a point is not finite or the criteria are not positive and finite.
  PickMonitor(const Eigen::Vector3d& p_start, const Eigen::Vector3d& p_target,
              const PickCriteria& criteria = {});

  /// One sample: the tip at @p p_WE at time @p t [s] (non-decreasing from call to call), with an
  /// orientation error @p orientation_error [rad] (0 for position-only tasks).
  PickEvent observe(double t, const Eigen::Vector3d& p_WE, double orientation_error = 0.0) noexcept;

  /// The figures so far.
  const PickMetrics& metrics() const noexcept { return metrics_; }
  /// True while the tip is within tolerance (a hold is running or complete).
  bool inside() const noexcept { return inside_; }
  /// True once the hold is complete.
  bool held() const noexcept { return metrics_.held; }
  /// Unit approach direction u (zero when the start is on the target).
  const Eigen::Vector3d& approach_direction() const noexcept { return direction_; }
  const Eigen::Vector3d& target() const noexcept { return target_; }
  const PickCriteria& criteria() const noexcept { return criteria_; }

 private:
  Eigen::Vector3d target_;
  Eigen::Vector3d direction_;
  PickCriteria criteria_;
  PickMetrics metrics_;
  bool inside_ = false;
  double entry_time_ = 0.0;  // start of the current stay inside
  // running sums of the current stay, and of its part inside the steady window
  double stay_sum_ = 0.0;
  double stay_max_ = 0.0;
  double steady_sum_ = 0.0;
  double steady_max_ = 0.0;
  std::int64_t steady_samples_ = 0;
  double stay_orientation_max_ = 0.0;
  std::int64_t stay_samples_ = 0;
};

}  // namespace mjarm
