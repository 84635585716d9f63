#include "mjarm/teleop/viewer_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

// a due time within this of "now" counts as reached, so that exact multiples of a period
// computed with rounding error do not slip by one loop iteration
constexpr double kSlack = 1e-9;

// the next due time after an event at `due`, never in the past: missed events are skipped,
// not made up in a burst
double advance(double due, double period, double now) noexcept {
  const double next = due + period;
  return next <= now + kSlack ? now + period : next;
}

}  // namespace

ViewerSchedule::ViewerSchedule(const ViewerRates& rates, double control_period, double wall_start)
    : rates_(rates),
      period_(control_period),
      last_wall_(wall_start),
      next_render_(wall_start),
      next_input_(wall_start) {
  check_fields(rates);
  if (!std::isfinite(control_period) || control_period <= 0.0) {
    throw Error("viewer schedule: the control period must be positive and finite [s], got " +
                number_text(control_period));
  }
  if (!std::isfinite(wall_start)) throw Error("viewer schedule: wall_start must be finite");
}

void ViewerSchedule::set_control_period(double period) noexcept {
  if (std::isfinite(period) && period > 0.0) {
    period_ = period;
    owed_ = 0.0;
  }
}

ScheduleStep ViewerSchedule::update(double wall_now, bool paused) noexcept {
  ScheduleStep step;
  const double elapsed = std::isfinite(wall_now) ? std::max(0.0, wall_now - last_wall_) : 0.0;
  if (std::isfinite(wall_now)) last_wall_ = std::max(last_wall_, wall_now);
  const double now = last_wall_;

  if (now + kSlack >= next_input_) {
    step.poll_input = true;
    ++polls_;
    next_input_ = advance(next_input_, 1.0 / rates_.input_hz, now);
  }
  if (now + kSlack >= next_render_) {
    step.render = true;
    ++frames_;
    next_render_ = advance(next_render_, 1.0 / rates_.render_hz, now);
  }

  // physics: whole ticks of the simulated time owed, at most max_catch_up of it per update
  if (paused) {
    owed_ = 0.0;
    return step;
  }
  owed_ += elapsed * rates_.speed;
  const double cap = std::max(rates_.max_catch_up, period_);  // at least one tick fits
  if (owed_ > cap) {
    dropped_ += owed_ - cap;
    owed_ = cap;
  }
  const double ticks = std::floor(owed_ / period_ + kSlack);
  step.ticks = static_cast<int>(ticks);
  owed_ = std::max(0.0, owed_ - ticks * period_);
  ticks_ += step.ticks;
  return step;
}

double ViewerSchedule::next_due() const noexcept { return std::min(next_render_, next_input_); }

}  // namespace mjarm
