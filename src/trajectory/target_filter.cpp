#include "mjarm/trajectory/target_filter.hpp"

#include <cmath>
#include <exception>
#include <span>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/lie/so3_jacobian.hpp"

namespace mjarm {

namespace {

std::vector<JerkLimits> filter_limits(const TargetFilterLimits& l) {
  check_fields(l);
  const JerkLimits linear{l.velocity, l.acceleration, l.jerk};
  const JerkLimits angular{l.angular_velocity, l.angular_acceleration, l.angular_jerk};
  return {linear, linear, linear, angular, angular, angular};
}

bool finite_pose(const Pose& X) noexcept { return X.p.allFinite() && X.R.allFinite(); }

}  // namespace

TargetFilter::TargetFilter(const TargetFilterLimits& limits)
    : limits_(limits), otg_(filter_limits(limits)) {}

void TargetFilter::reset(const Pose& X_WR) noexcept {
  X_WR_ = X_WR;
  X_WT_ = X_WR;
  R_A_ = X_WR.R;
  for (int i = 0; i < 3; ++i) {
    state_[static_cast<std::size_t>(i)] = {X_WR.p[i], 0.0, 0.0};
    state_[static_cast<std::size_t>(i + 3)] = {};
  }
  V_WR_.setZero();
  A_WR_.setZero();
  settled_ = true;
  status_ = OtgStatus::finished;
}

void TargetFilter::stop() noexcept {
  V_WR_.setZero();
  A_WR_.setZero();
  for (KinematicState& s : state_) s.v = s.a = 0.0;
}

// from the current state (re-anchored: φ = 0, φ̇ = ω, φ̈ = ω̇) to the target at rest
void TargetFilter::recalculate() noexcept {
  R_A_ = X_WR_.R;
  const Eigen::Vector3d phi_T = so3::log(X_WT_.R * R_A_.transpose());
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    state_[k] = {X_WR_.p[i], V_WR_[i], A_WR_[i]};
    state_[k + 3] = {0.0, V_WR_[i + 3], A_WR_[i + 3]};
    goal_[k] = {X_WT_.p[i], 0.0, 0.0};
    goal_[k + 3] = {phi_T[i], 0.0, 0.0};
  }
  try {
    status_ = otg_.calculate(state_, goal_).status;
  } catch (const std::exception&) {  // only for a state the checks above let through
    status_ = OtgStatus::error_no_profile;
  }
  settled_ = false;
  if (status_ != OtgStatus::working && status_ != OtgStatus::finished) stop();
}

const Pose& TargetFilter::update(const Pose& X_WT, double dt) noexcept {
  if (!std::isfinite(dt) || dt <= 0.0) return X_WR_;
  if (finite_pose(X_WT) && (X_WT.p != X_WT_.p || X_WT.R != X_WT_.R)) {
    X_WT_ = X_WT;
    recalculate();
  }
  if (settled_) return X_WR_;
  if (status_ != OtgStatus::working && status_ != OtgStatus::finished) return X_WR_;  // stopped

  status_ = otg_.step(dt, state_);
  if (status_ == OtgStatus::finished) {  // land exactly, at rest
    reset(X_WT_);
    return X_WR_;
  }
  Eigen::Vector3d phi, phi_dot, phi_ddot;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    X_WR_.p[i] = state_[k].p;
    V_WR_[i] = state_[k].v;
    A_WR_[i] = state_[k].a;
    phi[i] = state_[k + 3].p;
    phi_dot[i] = state_[k + 3].v;
    phi_ddot[i] = state_[k + 3].a;
  }
  // R = Exp(φ)·R_A: ω = Jl(φ)·φ̇, ω̇ = Jl(φ)·φ̈ + J̇l(φ, φ̇)·φ̇ (world axes)
  const Eigen::Matrix3d Jl = so3::left_jacobian(phi);
  X_WR_.R = so3::exp(phi) * R_A_;
  V_WR_.tail<3>() = Jl * phi_dot;
  A_WR_.tail<3>() = Jl * phi_ddot + so3::left_jacobian_derivative(phi, phi_dot) * phi_dot;
  return X_WR_;
}

}  // namespace mjarm
