#include "mjarm/trajectory/cartesian_trapezoid.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

const Pose& checked_pose(const Pose& X, const char* which) {
  if (!X.R.allFinite() || !X.p.allFinite())
    throw Error(std::string("Cartesian trapezoid: the ") + which + " pose must be finite");
  const double error = (X.R.transpose() * X.R - Eigen::Matrix3d::Identity()).norm();
  if (!(error <= 1e-6) || !(X.R.determinant() > 0.0))
    throw Error(std::string("Cartesian trapezoid: the ") + which +
                " rotation must be orthonormal with det +1 (‖RᵀR − I‖ = " + number_text(error) +
                ")");
  return X;
}

SyncedTrapezoid profile_of(const Pose& X0, const Pose& X1, const CartesianLimits& l) {
  check_fields(l);
  checked_pose(X0, "start");
  checked_pose(X1, "goal");
  const double d = (X1.p - X0.p).norm();
  const double theta = so3::log(X1.R * X0.R.transpose()).norm();
  return SyncedTrapezoid(Eigen::Vector2d::Zero(), Eigen::Vector2d(d, theta),
                         Eigen::Vector2d(l.max_velocity, l.max_angular_velocity),
                         Eigen::Vector2d(l.max_acceleration, l.max_angular_acceleration));
}

}  // namespace

CartesianTrapezoid::CartesianTrapezoid(const Pose& X_start, const Pose& X_goal,
                                       const CartesianLimits& limits)
    : X_start_(X_start), X_goal_(X_goal), profile_(profile_of(X_start, X_goal, limits)) {
  const Eigen::Vector3d line = X_goal.p - X_start.p;
  distance_ = line.norm();
  if (distance_ > 0.0) direction_ = line / distance_;
  const Eigen::Vector3d turn = so3::log(X_goal.R * X_start.R.transpose());
  angle_ = turn.norm();
  if (angle_ > 0.0) axis_ = turn / angle_;
}

CartesianTrapezoid::Sample CartesianTrapezoid::at(double t) const noexcept {
  Eigen::Vector2d s, v, a;
  profile_.at(t, s, v, a);
  Sample out;
  out.X_WE.p = X_start_.p + s[0] * direction_;
  out.X_WE.R = so3::exp(s[1] * axis_) * X_start_.R;
  out.V_WE.head<3>() = v[0] * direction_;
  out.V_WE.tail<3>() = v[1] * axis_;
  out.A_WE.head<3>() = a[0] * direction_;
  out.A_WE.tail<3>() = a[1] * axis_;
  if (t >= profile_.duration()) out.X_WE = X_goal_;  // exactly the goal at the end
  return out;
}

}  // namespace mjarm
