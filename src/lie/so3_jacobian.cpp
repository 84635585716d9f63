#include "mjarm/lie/so3_jacobian.hpp"

#include "mjarm/lie/coefficients.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm::so3 {

Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& w) noexcept {
  const lie::SeriesCoefficients k = lie::series_coefficients(w.norm());
  const Eigen::Matrix3d W = hat(w);
  return Eigen::Matrix3d::Identity() + k.a * W + k.b * (W * W);
}

Eigen::Matrix3d right_jacobian(const Eigen::Vector3d& w) noexcept { return left_jacobian(-w); }

Eigen::Matrix3d left_jacobian_inverse(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  lie::require_inverse_domain(theta, "so3::left_jacobian_inverse");
  const lie::InverseCoefficients k = lie::inverse_coefficients(theta);
  const Eigen::Matrix3d W = hat(w);
  return Eigen::Matrix3d::Identity() - 0.5 * W + k.e * (W * W);
}

Eigen::Matrix3d right_jacobian_inverse(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  lie::require_inverse_domain(theta, "so3::right_jacobian_inverse");
  return left_jacobian_inverse(-w);
}

Eigen::Matrix3d left_jacobian_derivative(const Eigen::Vector3d& w,
                                         const Eigen::Vector3d& w_dot) noexcept {
  // Jl = I + a W + b W²  ⇒  J̇l = ȧ W + a Ẇ + ḃ W² + b (Ẇ W + W Ẇ), with ḟ = (f'/θ)(ω·ω̇)
  const lie::SeriesCoefficients k = lie::series_coefficients(w.norm());
  const double s = w.dot(w_dot);
  const Eigen::Matrix3d W = hat(w);
  const Eigen::Matrix3d W_dot = hat(w_dot);
  return (s * k.a_rate) * W + k.a * W_dot + (s * k.b_rate) * (W * W) +
         k.b * (W_dot * W + W * W_dot);
}

Eigen::Matrix3d right_jacobian_derivative(const Eigen::Vector3d& w,
                                          const Eigen::Vector3d& w_dot) noexcept {
  // Jr(ω(t)) = Jl(−ω(t))
  return left_jacobian_derivative(-w, -w_dot);
}

Eigen::Matrix3d left_jacobian_inverse_derivative(const Eigen::Vector3d& w,
                                                 const Eigen::Vector3d& w_dot) {
  // Jl⁻¹ = I − ½W + e W²  ⇒  d/dt = −½Ẇ + ė W² + e (Ẇ W + W Ẇ)
  const double theta = w.norm();
  lie::require_inverse_domain(theta, "so3::left_jacobian_inverse_derivative");
  const lie::InverseCoefficients k = lie::inverse_coefficients(theta);
  const double s = w.dot(w_dot);
  const Eigen::Matrix3d W = hat(w);
  const Eigen::Matrix3d W_dot = hat(w_dot);
  return -0.5 * W_dot + (s * k.e_rate) * (W * W) + k.e * (W_dot * W + W * W_dot);
}

Eigen::Matrix3d right_jacobian_inverse_derivative(const Eigen::Vector3d& w,
                                                  const Eigen::Vector3d& w_dot) {
  lie::require_inverse_domain(w.norm(), "so3::right_jacobian_inverse_derivative");
  return left_jacobian_inverse_derivative(-w, -w_dot);
}

}  // namespace mjarm::so3
