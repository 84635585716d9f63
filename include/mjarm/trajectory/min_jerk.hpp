#pragma once
/// @file
/// `MinJerkProfile`: the rest-to-rest minimum-jerk (quintic) time scaling s(t) ∈ [0, 1].

namespace mjarm {

/// The time scaling of a rest-to-rest point-to-point motion that minimizes the integral of the
/// squared jerk (Flash & Hogan 1985): with τ = t/T ∈ [0, 1],
///
///     s(τ) = 10τ³ − 15τ⁴ + 6τ⁵,   ṡ = 30τ²(1 − τ)²/T,   s̈ = 60τ(1 − τ)(1 − 2τ)/T²
///
/// s, ṡ and s̈ are zero at both ends except s(T) = 1, so a path x(t) = x₀ + (x₁ − x₀)·s(t) starts
/// and stops at rest with zero acceleration. Peaks: ṡ_max = 1.875/T at τ = ½,
/// |s̈|_max = (10/√3)/T² ≈ 5.7735/T² at τ = ½ ∓ √3/6.
class MinJerkProfile {
 public:
  /// s(t) and its first two time derivatives.
  struct Sample {
    double s = 0.0;    ///< progress [1], 0 at t ≤ 0, 1 at t ≥ T
    double ds = 0.0;   ///< ṡ [1/s]
    double dds = 0.0;  ///< s̈ [1/s²]
  };

  /// ṡ_max·T: peak speed of a unit move times its duration.
  static constexpr double kPeakVelocity = 1.875;
  /// |s̈|_max·T² = 10/√3: peak acceleration of a unit move times its duration squared.
  static constexpr double kPeakAcceleration = 5.773502691896258;

  /// A profile lasting @p duration [s].
  /// @throws Error when @p duration is not positive and finite.
  explicit MinJerkProfile(double duration);

  /// The duration T [s].
  double duration() const noexcept { return duration_; }

  /// s, ṡ, s̈ at time @p t [s] (t is clamped to [0, T]; NaN gives the start).
  Sample at(double t) const noexcept;

  /// The shortest duration [s] for a move of @p distance (in any unit u) whose peak speed stays
  /// ≤ @p max_velocity [u/s] and whose peak acceleration stays ≤ @p max_acceleration [u/s²],
  /// and never shorter than @p min_duration [s].
  /// @throws Error when distance is negative or a bound is not positive and finite.
  static double duration_for(double distance, double max_velocity, double max_acceleration,
                             double min_duration);

 private:
  double duration_;
};

}  // namespace mjarm
