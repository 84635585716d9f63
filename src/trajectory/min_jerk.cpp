#include "mjarm/trajectory/min_jerk.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(std::string("MinJerkProfile: ") + what + " must be positive and finite, got " +
                std::to_string(value));
}

}  // namespace

MinJerkProfile::MinJerkProfile(double duration) : duration_(duration) {
  require_positive(duration, "duration [s]");
}

MinJerkProfile::Sample MinJerkProfile::at(double t) const noexcept {
  Sample out;
  if (!(t > 0.0)) return out;  // also NaN
  if (t >= duration_) {
    out.s = 1.0;
    return out;
  }
  const double T = duration_;
  const double tau = t / T;
  const double tau2 = tau * tau;
  const double one = 1.0 - tau;
  // Horner forms of the quintic and its derivatives
  out.s = tau2 * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
  out.ds = 30.0 * tau2 * one * one / T;
  out.dds = 60.0 * tau * one * (1.0 - 2.0 * tau) / (T * T);
  return out;
}

double MinJerkProfile::duration_for(double distance, double max_velocity, double max_acceleration,
                                    double min_duration) {
  if (!(distance >= 0.0) || !std::isfinite(distance))
    throw Error("MinJerkProfile::duration_for: distance must be ≥ 0 and finite, got " +
                std::to_string(distance));
  require_positive(max_velocity, "max_velocity");
  require_positive(max_acceleration, "max_acceleration");
  require_positive(min_duration, "min_duration [s]");
  const double by_velocity = kPeakVelocity * distance / max_velocity;
  const double by_acceleration = std::sqrt(kPeakAcceleration * distance / max_acceleration);
  return std::max({min_duration, by_velocity, by_acceleration});
}

}  // namespace mjarm
