#pragma once
/// @file
/// Scalar coefficient functions of the rotation angle θ that appear in the closed forms of
/// SO(3)/SE(3) exp, dexp (left/right Jacobians), their inverses and their time derivatives.
///
/// Every coefficient is an even, smooth function of θ. Below `kSeriesThreshold` they are
/// evaluated from their Taylor series in θ² (the closed forms cancel catastrophically there);
/// above it from the closed forms. The "rate" members are f'(θ)/θ, which is smooth at θ = 0 and
/// gives the time derivative as ḟ = (f'(θ)/θ)·(ω·ω̇) without dividing by θ.

namespace mjarm::lie {

/// Angle (rad) below which the coefficients come from Taylor series instead of closed forms.
inline constexpr double kSeriesThreshold = 1.0;

/// 2π (rad): dexp⁻¹ is singular at ‖ω‖ = 2π, so inverse Jacobians accept ‖ω‖ < 2π only.
inline constexpr double kTwoPi = 6.283185307179586476925286766559;

/// Coefficients of exp and of the left Jacobian of SO(3) and SE(3), and their rates.
struct SeriesCoefficients {
  double sinc = 1.0;    ///< sin θ / θ (Rodrigues), dimensionless
  double a = 0.5;       ///< (1 − cos θ)/θ² (Rodrigues, Jacobian)
  double b = 0.0;       ///< (θ − sin θ)/θ³ (Jacobian, Q block)
  double c = 0.0;       ///< (θ² + 2 cos θ − 2)/(2θ⁴) (Q block)
  double d = 0.0;       ///< (2θ − 3 sin θ + θ cos θ)/(2θ⁵) (Q block)
  double a_rate = 0.0;  ///< a'(θ)/θ
  double b_rate = 0.0;  ///< b'(θ)/θ
  double c_rate = 0.0;  ///< c'(θ)/θ
  double d_rate = 0.0;  ///< d'(θ)/θ
};

/// Coefficient of the inverse left Jacobian of SO(3), Jl⁻¹ = I − ½ω̂ + e ω̂², and its rate.
struct InverseCoefficients {
  double e = 1.0 / 12.0;  ///< 1/θ² − cot(θ/2)/(2θ)
  double e_rate = 0.0;    ///< e'(θ)/θ
};

/// All exp/Jacobian coefficients at rotation angle `theta` (rad, θ ≥ 0). One sin/cos call.
SeriesCoefficients series_coefficients(double theta) noexcept;

/// The inverse-Jacobian coefficient at `theta` (rad). Precondition: 0 ≤ θ < 2π (the result is
/// meaningless otherwise; callers check with require_inverse_domain first).
InverseCoefficients inverse_coefficients(double theta) noexcept;

/// Checks that a rotation angle lies in the domain of dexp⁻¹.
/// @param theta    rotation angle ‖ω‖ (rad)
/// @param function name of the calling function, put in the message
/// @throws mjarm::Error if θ ≥ 2π or θ is not finite (dexp⁻¹ is singular at 2π).
void require_inverse_domain(double theta, const char* function);

}  // namespace mjarm::lie
