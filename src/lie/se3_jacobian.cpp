#include "mjarm/lie/se3_jacobian.hpp"

#include "mjarm/lie/coefficients.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm::se3 {
namespace {

// Q from precomputed coefficients; P = ω̂, V = v̂
Eigen::Matrix3d q_from(const lie::SeriesCoefficients& k, const Eigen::Matrix3d& P,
                       const Eigen::Matrix3d& V) noexcept {
  const Eigen::Matrix3d PV = P * V;
  const Eigen::Matrix3d PVP = PV * P;
  const Eigen::Matrix3d PP = P * P;
  return 0.5 * V + k.b * (PV + V * P + PVP) + k.c * (PP * V + V * PP - 3.0 * PVP) +
         k.d * (PVP * P + P * PVP);
}

// Q̇ by the product rule on every term, with ḟ = (f'(θ)/θ)(ω·ω̇) for the coefficients
Eigen::Matrix3d q_dot_from(const lie::SeriesCoefficients& k, double w_dot_w,
                           const Eigen::Matrix3d& P, const Eigen::Matrix3d& V,
                           const Eigen::Matrix3d& P_dot, const Eigen::Matrix3d& V_dot) noexcept {
  const Eigen::Matrix3d PV = P * V;
  const Eigen::Matrix3d VP = V * P;
  const Eigen::Matrix3d PP = P * P;
  const Eigen::Matrix3d PVP = PV * P;
  const Eigen::Matrix3d d_PV = P_dot * V + P * V_dot;
  const Eigen::Matrix3d d_VP = V_dot * P + V * P_dot;
  const Eigen::Matrix3d d_PP = P_dot * P + P * P_dot;
  const Eigen::Matrix3d d_PVP = d_PV * P + PV * P_dot;
  // the three structure matrices and their derivatives
  const Eigen::Matrix3d M1 = PV + VP + PVP;
  const Eigen::Matrix3d M2 = PP * V + V * PP - 3.0 * PVP;
  const Eigen::Matrix3d M3 = PVP * P + P * PVP;
  const Eigen::Matrix3d d_M1 = d_PV + d_VP + d_PVP;
  const Eigen::Matrix3d d_M2 = d_PP * V + PP * V_dot + V_dot * PP + V * d_PP - 3.0 * d_PVP;
  const Eigen::Matrix3d d_M3 = d_PVP * P + PVP * P_dot + P_dot * PVP + P * d_PVP;
  return 0.5 * V_dot + (w_dot_w * k.b_rate) * M1 + (w_dot_w * k.c_rate) * M2 +
         (w_dot_w * k.d_rate) * M3 + k.b * d_M1 + k.c * d_M2 + k.d * d_M3;
}

// Jl⁻¹(ω) = I − ½P + e P² for P = ω̂
Eigen::Matrix3d so3_inverse(const lie::InverseCoefficients& ki, const Eigen::Matrix3d& P) noexcept {
  return Eigen::Matrix3d::Identity() - 0.5 * P + ki.e * (P * P);
}

Matrix6d block_upper(const Eigen::Matrix3d& diagonal, const Eigen::Matrix3d& upper) noexcept {
  Matrix6d m;
  m.topLeftCorner<3, 3>() = diagonal;
  m.topRightCorner<3, 3>() = upper;
  m.bottomLeftCorner<3, 3>().setZero();
  m.bottomRightCorner<3, 3>() = diagonal;
  return m;
}

}  // namespace

Eigen::Matrix3d q_block(const Eigen::Vector3d& v, const Eigen::Vector3d& w) noexcept {
  return q_from(lie::series_coefficients(w.norm()), so3::hat(w), so3::hat(v));
}

Eigen::Matrix3d q_block_derivative(const Eigen::Vector3d& v, const Eigen::Vector3d& w,
                                   const Eigen::Vector3d& v_dot,
                                   const Eigen::Vector3d& w_dot) noexcept {
  return q_dot_from(lie::series_coefficients(w.norm()), w.dot(w_dot), so3::hat(w), so3::hat(v),
                    so3::hat(w_dot), so3::hat(v_dot));
}

Matrix6d left_jacobian(const Vector6d& xi) noexcept {
  const Eigen::Vector3d w = xi.tail<3>();
  const lie::SeriesCoefficients k = lie::series_coefficients(w.norm());
  const Eigen::Matrix3d P = so3::hat(w);
  const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + k.a * P + k.b * (P * P);
  return block_upper(J, q_from(k, P, so3::hat(xi.head<3>())));
}

Matrix6d right_jacobian(const Vector6d& xi) noexcept { return left_jacobian(-xi); }

Matrix6d left_jacobian_inverse(const Vector6d& xi) {
  const Eigen::Vector3d w = xi.tail<3>();
  const double theta = w.norm();
  lie::require_inverse_domain(theta, "se3::left_jacobian_inverse");
  const Eigen::Matrix3d P = so3::hat(w);
  const Eigen::Matrix3d A = so3_inverse(lie::inverse_coefficients(theta), P);
  const Eigen::Matrix3d Q = q_from(lie::series_coefficients(theta), P, so3::hat(xi.head<3>()));
  return block_upper(A, -A * Q * A);
}

Matrix6d right_jacobian_inverse(const Vector6d& xi) {
  lie::require_inverse_domain(xi.tail<3>().norm(), "se3::right_jacobian_inverse");
  return left_jacobian_inverse(-xi);
}

Matrix6d left_jacobian_derivative(const Vector6d& xi, const Vector6d& xi_dot) noexcept {
  const Eigen::Vector3d w = xi.tail<3>();
  const Eigen::Vector3d w_dot = xi_dot.tail<3>();
  const lie::SeriesCoefficients k = lie::series_coefficients(w.norm());
  const double s = w.dot(w_dot);
  const Eigen::Matrix3d P = so3::hat(w);
  const Eigen::Matrix3d P_dot = so3::hat(w_dot);
  // SO(3) block: d/dt (I + a P + b P²)
  const Eigen::Matrix3d J_dot =
      (s * k.a_rate) * P + k.a * P_dot + (s * k.b_rate) * (P * P) + k.b * (P_dot * P + P * P_dot);
  return block_upper(
      J_dot, q_dot_from(k, s, P, so3::hat(xi.head<3>()), P_dot, so3::hat(xi_dot.head<3>())));
}

Matrix6d right_jacobian_derivative(const Vector6d& xi, const Vector6d& xi_dot) noexcept {
  // Jr(ξ(t)) = Jl(−ξ(t))
  return left_jacobian_derivative(-xi, -xi_dot);
}

Matrix6d left_jacobian_inverse_derivative(const Vector6d& xi, const Vector6d& xi_dot) {
  const Eigen::Vector3d w = xi.tail<3>();
  const Eigen::Vector3d w_dot = xi_dot.tail<3>();
  const double theta = w.norm();
  lie::require_inverse_domain(theta, "se3::left_jacobian_inverse_derivative");
  const lie::SeriesCoefficients k = lie::series_coefficients(theta);
  const lie::InverseCoefficients ki = lie::inverse_coefficients(theta);
  const double s = w.dot(w_dot);
  const Eigen::Matrix3d P = so3::hat(w);
  const Eigen::Matrix3d P_dot = so3::hat(w_dot);
  const Eigen::Matrix3d V = so3::hat(xi.head<3>());
  // Jl⁻¹ = [A, B; 0, A] with A = Jl⁻¹(ω) = I − ½P + e P², B = −A Q A
  //   ⇒ Ȧ = −½Ṗ + ė P² + e (Ṗ P + P Ṗ), Ḃ = −(Ȧ Q A + A Q̇ A + A Q Ȧ)
  const Eigen::Matrix3d A = so3_inverse(ki, P);
  const Eigen::Matrix3d A_dot =
      -0.5 * P_dot + (s * ki.e_rate) * (P * P) + ki.e * (P_dot * P + P * P_dot);
  const Eigen::Matrix3d Q = q_from(k, P, V);
  const Eigen::Matrix3d Q_dot = q_dot_from(k, s, P, V, P_dot, so3::hat(xi_dot.head<3>()));
  return block_upper(A_dot, -(A_dot * Q * A + A * Q_dot * A + A * Q * A_dot));
}

Matrix6d right_jacobian_inverse_derivative(const Vector6d& xi, const Vector6d& xi_dot) {
  lie::require_inverse_domain(xi.tail<3>().norm(), "se3::right_jacobian_inverse_derivative");
  return left_jacobian_inverse_derivative(-xi, -xi_dot);
}

}  // namespace mjarm::se3
