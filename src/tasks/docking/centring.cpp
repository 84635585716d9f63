#include "mjarm/tasks/docking/centring.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {

void BoreCentring::reset() noexcept {
  decided_ = false;
  last_t_ = -1.0;
  last_d_.setZero();
  found_ = false;
  stage_ = Stage::idle;
  from_.setZero();
  direction_.setZero();
  move_from_.setZero();
  target_.setZero();
}

bool BoreCentring::decide(double depth, const Eigen::Vector3d& p_tip, const Eigen::Vector3d& p_ref,
                          const Eigen::Vector3d& u, double t) noexcept {
  if (!options_.enabled || decided_) return false;
  const Eigen::Vector3d e = p_tip - p_ref;
  const Eigen::Vector3d d = e - e.dot(u) * u;  // in the believed socket's plane
  const bool settled = last_t_ >= 0.0 && t > last_t_ &&
                       (d - last_d_).norm() <= options_.settle_speed * (t - last_t_);
  last_t_ = t;
  last_d_ = d;
  if (!(depth >= options_.start_depth)) return false;
  if (!(depth <= options_.latest_depth)) {
    decided_ = true;  // too late for it
    return false;
  }
  const double n = d.norm();
  if (!std::isfinite(n) || n < options_.min_excursion) {  // nothing moved it
    decided_ = true;
    return false;
  }
  if (!settled) return false;
  decided_ = true;
  u_ = u;
  stage_ = Stage::probing;
  start_ = t;
  from_ = d;
  direction_ = d / n;
  return true;
}

void BoreCentring::update(const Eigen::Vector3d& p_tip, const Eigen::Vector3d& p_ref,
                          double t) noexcept {
  if (stage_ != Stage::probing) return;
  const double travel = probe_travel(t);
  const Eigen::Vector3d probe = from_ + travel * direction_;
  const Eigen::Vector3d e = p_tip - p_ref;
  const Eigen::Vector3d tip = e - e.dot(u_) * u_;
  const double lag = (probe - tip).dot(direction_);
  if (lag >= options_.contact_lag) {  // the wall stops the peg: the axis is c behind it
    found_ = true;
    target_ = tip - clearance_ * direction_;
  } else if (travel >= options_.probe_travel || !std::isfinite(lag)) {
    target_ = from_;  // no wall where one must be: back to the start
  } else {
    return;
  }
  stage_ = Stage::moving;
  move_start_ = t;
  move_from_ = probe;
}

double BoreCentring::probe_travel(double t) const noexcept {
  // speed v·s(τ/T) with s = x²(3 − 2x): travel v·T·(x³ − x⁴/2) over the ramp, then v·(τ − T/2)
  const double T = options_.probe_ramp, tau = std::max(0.0, t - start_);
  if (tau >= T) return options_.probe_speed * (tau - 0.5 * T);
  const double x = tau / T;
  return options_.probe_speed * T * (x * x * x - 0.5 * x * x * x * x);
}

double BoreCentring::probe_speed(double t) const noexcept {
  return options_.probe_speed * smoothstep((t - start_) / options_.probe_ramp).s;
}

Eigen::Vector3d BoreCentring::shift(double t) const noexcept {
  switch (stage_) {
    case Stage::idle:
      return Eigen::Vector3d::Zero();
    case Stage::probing:
      return from_ + probe_travel(t) * direction_;
    case Stage::moving:
      return move_from_ +
             smoothstep((t - move_start_) / options_.duration).s * (target_ - move_from_);
  }
  return Eigen::Vector3d::Zero();
}

Eigen::Vector3d BoreCentring::shift_rate(double t) const noexcept {
  switch (stage_) {
    case Stage::idle:
      return Eigen::Vector3d::Zero();
    case Stage::probing:
      return probe_speed(t) * direction_;
    case Stage::moving:
      return (smoothstep((t - move_start_) / options_.duration).ds / options_.duration) *
             (target_ - move_from_);
  }
  return Eigen::Vector3d::Zero();
}

}  // namespace mjarm
