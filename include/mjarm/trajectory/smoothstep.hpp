#pragma once
/// @file
/// smoothstep and smootherstep: polynomial ramps from 0 to 1 on x ∈ [0, 1], clipped outside,
/// with their derivatives (for gripper opening and closing and other blends).

namespace mjarm {

struct TrajectorySample;  // trajectory_sample.hpp

/// A ramp value and its first three derivatives with respect to its argument x.
struct RampSample {
  double s = 0.0;     ///< value ∈ [0, 1]
  double ds = 0.0;    ///< ds/dx
  double dds = 0.0;   ///< d²s/dx²
  double ddds = 0.0;  ///< d³s/dx³
};

/// smoothstep s(x) = x²(3 − 2x) (C¹: s′ = 6x(1 − x) is zero at both ends; s″ = 6 − 12x steps
/// from 0 to ±6 there). x < 0 gives 0, x > 1 gives 1, derivatives 0 outside [0, 1]; NaN gives 0.
/// Peak slope 1.5 at x = ½, peak |s″| = 6 at the ends.
RampSample smoothstep(double x) noexcept;

/// smootherstep s(x) = 6x⁵ − 15x⁴ + 10x³ (C²: s′ = 30x²(1 − x)² and s″ = 60x(1 − x)(1 − 2x)
/// are zero at both ends; s‴ = 60(6x² − 6x + 1) steps from 0 to 60 there). Clipped as
/// `smoothstep`. It is the rest-to-rest minimum-jerk time scaling (the rest-to-rest `Quintic`).
/// Peak slope 1.875 at x = ½, peak |s″| = 10/√3 at x = ½ ∓ √3/6.
RampSample smootherstep(double x) noexcept;

/// A ramp of duration T run in time: s(t) = ramp(t/T) with ṡ = s′/T, s̈ = s″/T², s⃛ = s‴/T³.
class SmoothRamp {
 public:
  /// Which polynomial.
  enum class Kind {
    smoothstep,   ///< x²(3 − 2x), C¹
    smootherstep  ///< 6x⁵ − 15x⁴ + 10x³, C²
  };

  /// A ramp of @p kind lasting @p duration [s].
  /// @throws Error when @p duration is not positive and finite.
  SmoothRamp(Kind kind, double duration);

  /// The shortest duration [s] for a move of @p distance (u) whose peak speed stays ≤
  /// @p max_velocity [u/s] and peak acceleration ≤ @p max_acceleration [u/s²]; 0 for a zero
  /// distance.
  /// @throws Error when the distance is negative or not finite, or a limit is not positive and
  ///         finite.
  static double duration_for(Kind kind, double distance, double max_velocity,
                             double max_acceleration);

  /// Peak slope max s′ of @p kind (1.5 or 1.875).
  static double peak_slope(Kind kind) noexcept;
  /// Peak |s″| of @p kind (6 or 10/√3).
  static double peak_curvature(Kind kind) noexcept;
  /// Peak |s‴| of @p kind (12 throughout for smoothstep; 60 at the ends for smootherstep).
  static double peak_jerk(Kind kind) noexcept;

  /// The kind.
  Kind kind() const noexcept { return kind_; }
  /// The duration T [s].
  double duration() const noexcept { return duration_; }
  /// s(t) with its time derivatives ṡ [1/s], s̈ [1/s²], s⃛ [1/s³]; clamped outside [0, T].
  RampSample at(double t) const noexcept;
  /// One coordinate (a `TrajectoryProfile` of dofs() = 1).
  int dofs() const noexcept { return 1; }
  /// `at(t)` as a `TrajectorySample` of one coordinate, s (trajectory_sample.hpp).
  void at(double t, TrajectorySample& sample) const;

 private:
  Kind kind_;
  double duration_;
};

}  // namespace mjarm
