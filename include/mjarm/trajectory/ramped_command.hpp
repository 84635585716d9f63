#pragma once
/// @file
/// `RampedCommand`: a scalar command (a gripper's opening: 0 open … 1 closed) that goes to each
/// new target along a smoothstep (or smootherstep) ramp from where it is, so that a jump of the
/// target — a slider dragged, a task closing the gripper — opens or closes the gripper smoothly.

#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {

/// The command c(t) ∈ [lower, upper]. When the target changes to c_T, a ramp starts from the
/// current value c₀: c(t) = c₀ + (c_T − c₀)·s((t − t₀)/T) with s the ramp of `kind` and
/// T = full_travel_time·|c_T − c₀|/(upper − lower), so every move has the same peak rate,
/// s′_max·(upper − lower)/full_travel_time (1.5 or 1.875 times the mean rate of a full travel).
/// A target changed mid-ramp starts a new ramp from the current value, at rest: the rate
/// steps to 0 there (the value stays continuous). Allocation-free.
class RampedCommand {
 public:
  /// @param full_travel_time the duration of a ramp over the whole range [s] (> 0)
  /// @param lower, upper the range (finite, lower < upper); targets are clamped into it
  /// @param kind smoothstep (C¹) or smootherstep (C², the minimum-jerk scaling)
  /// @throws Error naming the value when the time is not positive and finite or the range is
  ///         not finite and increasing.
  explicit RampedCommand(double full_travel_time, double lower = 0.0, double upper = 1.0,
                         SmoothRamp::Kind kind = SmoothRamp::Kind::smoothstep);

  /// Puts the command at @p value (clamped into the range; NaN: lower), at rest, with the
  /// target there.
  void reset(double value) noexcept;

  /// Takes @p target (clamped into the range; NaN is ignored and the last target kept), starting
  /// a ramp when it differs from the last one, and advances the command by @p dt [s] (a
  /// non-positive or non-finite dt advances nothing). Returns the command.
  double update(double target, double dt) noexcept;

  /// The command now.
  double value() const noexcept { return value_; }
  /// Its rate of change [1/s] (the unit of the command per second).
  double rate() const noexcept { return rate_; }
  /// The target it moves to.
  double target() const noexcept { return target_; }
  /// True when the command is at its target, at rest.
  bool settled() const noexcept { return elapsed_ >= duration_; }
  /// The duration of the current ramp [s] (0 when none).
  double ramp_duration() const noexcept { return duration_; }

 private:
  double full_travel_time_;
  double lower_;
  double upper_;
  SmoothRamp::Kind kind_;
  double value_ = 0.0;
  double rate_ = 0.0;
  double target_ = 0.0;
  double from_ = 0.0;      // value at the start of the ramp
  double duration_ = 0.0;  // of the ramp [s]
  double elapsed_ = 0.0;   // since its start [s]
};

}  // namespace mjarm
