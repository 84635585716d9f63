#include "mjarm/tasks/pick_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

void check(const PickCriteria& criteria, std::string_view owner) {
  check_fields(criteria, owner, "criteria.");
  if (!(criteria.steady_window <= criteria.hold_time))
    throw Error(std::string(owner) + ": criteria.steady_window must be ≤ hold_time (" +
                number_text(criteria.hold_time) + " s), got " +
                number_text(criteria.steady_window) + " s");
}

PickMonitor::PickMonitor(const Eigen::Vector3d& p_start, const Eigen::Vector3d& p_target,
                         const PickCriteria& criteria)
    : target_(p_target), direction_(Eigen::Vector3d::Zero()), criteria_(criteria) {
  if (!p_start.allFinite()) throw Error("PickMonitor: the start point holds NaN/inf");
  if (!p_target.allFinite()) throw Error("PickMonitor: the target point holds NaN/inf");
  check(criteria, "pick monitor");
  const Eigen::Vector3d d = p_target - p_start;
  if (d.norm() > 1e-12) direction_ = d.normalized();
}

PickEvent PickMonitor::observe(double t, const Eigen::Vector3d& p_WE,
                               double orientation_error) noexcept {
  if (metrics_.held) return PickEvent::none;
  ++metrics_.samples;
  const Eigen::Vector3d offset = p_WE - target_;
  const double error = offset.norm();
  metrics_.final_error = error;
  // NaN compares false: a NaN tip counts as outside
  const bool now_inside = error <= criteria_.tolerance;

  PickEvent event = PickEvent::none;
  if (now_inside && !inside_) {
    event = PickEvent::entered;
    inside_ = true;
    entry_time_ = t;
    stay_sum_ = 0.0;
    stay_max_ = 0.0;
    stay_orientation_max_ = 0.0;
    stay_samples_ = 0;
    steady_sum_ = 0.0;
    steady_max_ = 0.0;
    steady_samples_ = 0;
    if (std::isnan(metrics_.first_entry_time)) metrics_.first_entry_time = t;
  } else if (!now_inside && inside_) {
    event = PickEvent::left;
    inside_ = false;
    ++metrics_.exits;
  }

  // overshoot: from the first entry on, how far past the target along the approach
  if (!std::isnan(metrics_.first_entry_time) && std::isfinite(error)) {
    const double past = direction_.isZero() ? error : std::max(0.0, offset.dot(direction_));
    metrics_.overshoot = std::max(metrics_.overshoot, past);
  }

  if (inside_) {
    stay_sum_ += error;
    stay_max_ = std::max(stay_max_, error);
    stay_orientation_max_ = std::max(stay_orientation_max_, orientation_error);
    ++stay_samples_;
    // a tick grid accumulates round-off: allow a nanosecond
    if (t - entry_time_ >= criteria_.hold_time - criteria_.steady_window - 1e-9) {
      steady_sum_ += error;
      steady_max_ = std::max(steady_max_, error);
      ++steady_samples_;
    }
    if (t - entry_time_ >= criteria_.hold_time - 1e-9) {
      event = PickEvent::held;
      metrics_.held = true;
      metrics_.time_to_tolerance = entry_time_;
      metrics_.hold_end_time = t;
      metrics_.hold_mean = stay_sum_ / static_cast<double>(stay_samples_);
      metrics_.hold_max = stay_max_;
      metrics_.steady_state_mean = steady_sum_ / static_cast<double>(steady_samples_);
      metrics_.steady_state_max = steady_max_;
      metrics_.orientation_error_max = stay_orientation_max_;
    }
  }
  return event;
}

}  // namespace mjarm
