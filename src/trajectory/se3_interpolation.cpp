#include "mjarm/trajectory/se3_interpolation.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/lie/so3_jacobian.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

void require_interpolated_pose(const Pose& X, const char* which) {
  if (!X.R.allFinite() || !X.p.allFinite())
    throw Error(std::string("SE(3) interpolation: the ") + which + " pose must be finite");
  const double error = (X.R.transpose() * X.R - Eigen::Matrix3d::Identity()).norm();
  if (!(error <= 1e-6) || !(X.R.determinant() > 0.0))
    throw Error(std::string("SE(3) interpolation: the ") + which +
                " rotation must be orthonormal with det +1 (‖RᵀR − I‖ = " + number_text(error) +
                ")");
}

void require_interpolation_duration(double duration) {
  if (!(duration > 0.0) || !std::isfinite(duration))
    throw Error("SE(3) interpolation: duration must be positive and finite, got " +
                number_text(duration) + " s");
}

// the three quintics of a 3-vector from (x0, v0, a0) to (x1, 0, 0)
std::array<Quintic, 3> axis_quintics(const Eigen::Vector3d& x0, const Eigen::Vector3d& v0,
                                     const Eigen::Vector3d& a0, const Eigen::Vector3d& x1,
                                     double T) {
  return {Quintic({x0[0], v0[0], a0[0]}, {x1[0], 0.0, 0.0}, T),
          Quintic({x0[1], v0[1], a0[1]}, {x1[1], 0.0, 0.0}, T),
          Quintic({x0[2], v0[2], a0[2]}, {x1[2], 0.0, 0.0}, T)};
}

std::array<Quintic, 3> checked_position(const Pose& X_start, const Vector6d& V, const Vector6d& A,
                                        const Pose& X_goal, double T) {
  require_interpolated_pose(X_start, "start");
  require_interpolated_pose(X_goal, "goal");
  require_interpolation_duration(T);
  if (!V.allFinite() || !A.allFinite())
    throw Error("SE(3) interpolation: the start twist and twist rate must be finite");
  return axis_quintics(X_start.p, V.head<3>(), A.head<3>(), X_goal.p, T);
}

}  // namespace

Se3Interpolation::Se3Interpolation(const Pose& X_start, const Vector6d& V_start,
                                   const Vector6d& A_start, const Pose& X_goal, double duration)
    : X_start_(X_start),
      theta_goal_(so3::log(X_start.R.transpose() * X_goal.R)),
      position_(checked_position(X_start, V_start, A_start, X_goal, duration)),
      // θ̇(0) = R₀ᵀω₀ and θ̈(0) = R₀ᵀω̇₀ (Jl(0) = I, J̇l(0, θ̇)·θ̇ = 0)
      angle_(axis_quintics(Eigen::Vector3d::Zero(), X_start.R.transpose() * V_start.tail<3>(),
                           X_start.R.transpose() * A_start.tail<3>(), theta_goal_, duration)),
      duration_(duration) {
  // the end, computed once: at and after T the sample is exactly this pose at rest
  X_end_.R = X_start.R * so3::exp(theta_goal_);
  X_end_.p = X_goal.p;
}

void Se3Interpolation::rotation_vector(double t, Eigen::Vector3d& theta, Eigen::Vector3d& theta_dot,
                                       Eigen::Vector3d& theta_ddot) const noexcept {
  for (int k = 0; k < 3; ++k) {
    const Quintic::Sample s = angle_[static_cast<std::size_t>(k)].at(t);
    theta[k] = s.p;
    theta_dot[k] = s.v;
    theta_ddot[k] = s.a;
  }
}

Se3Interpolation::Sample Se3Interpolation::at(double t) const noexcept {
  Sample out;
  if (t >= duration_) {  // at rest at the goal (no round-off twist from the polynomials)
    out.X_WE = X_end_;
    return out;
  }
  for (int k = 0; k < 3; ++k) {
    const Quintic::Sample s = position_[static_cast<std::size_t>(k)].at(t);
    out.X_WE.p[k] = s.p;
    out.V_WE[k] = s.v;
    out.A_WE[k] = s.a;
  }
  Eigen::Vector3d theta, theta_dot, theta_ddot;
  rotation_vector(t, theta, theta_dot, theta_ddot);
  const Eigen::Matrix3d& R0 = X_start_.R;
  const Eigen::Matrix3d Jl = so3::left_jacobian(theta);
  out.X_WE.R = R0 * so3::exp(theta);
  out.V_WE.tail<3>() = R0 * (Jl * theta_dot);
  out.A_WE.tail<3>() =
      R0 * (so3::left_jacobian_derivative(theta, theta_dot) * theta_dot + Jl * theta_ddot);
  return out;
}

}  // namespace mjarm
