#include "mjarm/trajectory/ramped_command.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

RampedCommand::RampedCommand(double full_travel_time, double lower, double upper,
                             SmoothRamp::Kind kind)
    : full_travel_time_(full_travel_time), lower_(lower), upper_(upper), kind_(kind) {
  if (!(full_travel_time > 0.0) || !std::isfinite(full_travel_time))
    throw Error("ramped command: the full travel time must be positive and finite, got " +
                number_text(full_travel_time) + " s");
  if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower < upper))
    throw Error("ramped command: the range must be finite with lower < upper, got [" +
                number_text(lower) + ", " + number_text(upper) + "]");
  reset(lower);
}

void RampedCommand::reset(double value) noexcept {
  value_ = std::isnan(value) ? lower_ : std::clamp(value, lower_, upper_);
  target_ = from_ = value_;
  rate_ = duration_ = elapsed_ = 0.0;
}

double RampedCommand::update(double target, double dt) noexcept {
  if (!std::isnan(target)) {
    target = std::clamp(target, lower_, upper_);
    if (target != target_) {  // a new ramp from where the command is
      target_ = target;
      from_ = value_;
      duration_ = full_travel_time_ * std::abs(target_ - from_) / (upper_ - lower_);
      elapsed_ = 0.0;
    }
  }
  if (!std::isfinite(dt) || dt <= 0.0) return value_;
  elapsed_ += dt;
  if (elapsed_ >= duration_) {  // arrived: exactly the target, at rest
    value_ = target_;
    rate_ = 0.0;
    return value_;
  }
  const RampSample s = SmoothRamp(kind_, duration_).at(elapsed_);
  value_ = from_ + (target_ - from_) * s.s;
  rate_ = (target_ - from_) * s.ds;
  return value_;
}

}  // namespace mjarm
