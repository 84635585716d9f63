#include "mjarm/trajectory/smoothstep.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

namespace {

// the clipped values outside [0, 1]: 0 before (and for NaN), 1 after, flat
bool clipped_ramp(double x, RampSample& out) noexcept {
  if (x > 1.0) {
    out.s = 1.0;
    return true;
  }
  return !(x >= 0.0);
}

void require_ramp_value(double value, const char* what, bool allow_zero) {
  if (!std::isfinite(value) || value < 0.0 || (!allow_zero && value == 0.0))
    throw Error(std::string("smooth ramp: ") + what + " must be " +
                (allow_zero ? "≥ 0" : "positive") + " and finite, got " + number_text(value));
}

}  // namespace

RampSample smoothstep(double x) noexcept {
  RampSample out;
  if (clipped_ramp(x, out)) return out;
  out.s = x * x * (3.0 - 2.0 * x);
  out.ds = 6.0 * x * (1.0 - x);
  out.dds = 6.0 - 12.0 * x;
  out.ddds = -12.0;
  return out;
}

RampSample smootherstep(double x) noexcept {
  RampSample out;
  if (clipped_ramp(x, out)) return out;
  const double one = 1.0 - x;
  out.s = x * x * x * (10.0 + x * (-15.0 + 6.0 * x));
  out.ds = 30.0 * x * x * one * one;
  out.dds = 60.0 * x * one * (1.0 - 2.0 * x);
  out.ddds = 60.0 * (1.0 + x * (-6.0 + 6.0 * x));
  return out;
}

SmoothRamp::SmoothRamp(Kind kind, double duration) : kind_(kind), duration_(duration) {
  require_ramp_value(duration, "duration [s]", false);
}

double SmoothRamp::peak_slope(Kind kind) noexcept { return kind == Kind::smoothstep ? 1.5 : 1.875; }

double SmoothRamp::peak_curvature(Kind kind) noexcept {
  return kind == Kind::smoothstep ? 6.0 : 5.773502691896258;  // 10/√3
}

double SmoothRamp::peak_jerk(Kind kind) noexcept {
  return kind == Kind::smoothstep ? 12.0 : 60.0;  // |−12|; 60(6x² − 6x + 1) at x = 0, 1
}

double SmoothRamp::duration_for(Kind kind, double distance, double max_velocity,
                                double max_acceleration) {
  require_ramp_value(distance, "distance", true);
  require_ramp_value(max_velocity, "max velocity", false);
  require_ramp_value(max_acceleration, "max acceleration", false);
  // peak speed s′_max·d/T and peak acceleration s″_max·d/T² are both decreasing in T
  const double T = std::max(peak_slope(kind) * distance / max_velocity,
                            std::sqrt(peak_curvature(kind) * distance / max_acceleration));
  if (!std::isfinite(T))
    throw Error("smooth ramp: " + number_text(distance) + " at max velocity " +
                number_text(max_velocity) + " and max acceleration " +
                number_text(max_acceleration) + " takes longer than a double can hold");
  return T;
}

RampSample SmoothRamp::at(double t) const noexcept {
  const RampSample x =
      kind_ == Kind::smoothstep ? smoothstep(t / duration_) : smootherstep(t / duration_);
  const double T = duration_;
  return {x.s, x.ds / T, x.dds / (T * T), x.ddds / (T * T * T)};
}

void SmoothRamp::at(double t, TrajectorySample& sample) const {
  sample.resize(1);
  const RampSample s = at(t);
  sample.position[0] = s.s;
  sample.velocity[0] = s.ds;
  sample.acceleration[0] = s.dds;
  sample.jerk[0] = s.ddds;
}

}  // namespace mjarm
