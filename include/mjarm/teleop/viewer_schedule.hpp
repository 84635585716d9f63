#pragma once
/// @file
/// `ViewerSchedule`: the interactive viewer's clock. Rendering and input polling run at fixed
/// wall-clock rates; physics advances by whole control ticks to keep simulated time up with the
/// wall clock, with a cap so that a machine too slow for real time slows the simulation down
/// instead of piling up an ever-growing backlog.
///
/// The schedule only does arithmetic on the times it is given: the window loop passes the real
/// clock, scripted runs and tests pass a virtual one (so they are deterministic).

#include <cstdint>

#include "mjarm/fields.hpp"

namespace mjarm {

/// Rates of the viewer loop.
struct ViewerRates {
  double render_hz = 60.0;  ///< frames drawn per wall-clock second (> 0)
  double input_hz = 20.0;   ///< input polls per wall-clock second (> 0)
  double speed = 1.0;       ///< simulated seconds per wall-clock second (> 0)
  /// Largest amount of simulated time [s] one `update` may ask for (> 0; at least one control
  /// period is always allowed). Whatever the wall clock owes beyond it is dropped: a slow machine
  /// then runs slower than real time, at the rate it can, while frames and input keep coming.
  double max_catch_up = 0.05;
};

constexpr auto declared_fields(const ViewerRates*) {
  using S = ViewerRates;
  return declare<S>(
      "viewer schedule",
      field("render_hz", &S::render_hz, "Hz", Range::positive(), "frames drawn per wall second"),
      field("input_hz", &S::input_hz, "Hz", Range::positive(), "input polls per wall second"),
      field("speed", &S::speed, "", Range::positive(), "simulated seconds per wall second"),
      field("max_catch_up", &S::max_catch_up, "s", Range::positive(),
            "largest simulated time one update may ask for"));
}

/// What the loop should do at one `ViewerSchedule::update`.
struct ScheduleStep {
  bool poll_input = false;  ///< poll the window's events (and read the panel)
  bool render = false;      ///< draw a frame
  int ticks = 0;            ///< control ticks to simulate now (0 while paused)
};

/// The viewer's wall-clock scheduler. No allocation, no exception after construction.
///
///     ViewerSchedule schedule(rates, session.control_period(), clock.now());
///     while (open) {
///       const ScheduleStep step = schedule.update(clock.now(), paused);
///       if (step.poll_input) poll();
///       session.step(step.ticks);
///       if (step.render) draw();
///       sleep_until(schedule.next_due());
///     }
class ViewerSchedule {
 public:
  /// @param rates          loop rates (checked)
  /// @param control_period simulated time of one control tick [s] (> 0)
  /// @param wall_start     wall-clock time of the first `update` [s]: input and a frame are due
  ///                       at once then
  /// @throws Error when a rate, the speed, max_catch_up or the period is not positive and finite,
  ///         or @p wall_start is not finite.
  ViewerSchedule(const ViewerRates& rates, double control_period, double wall_start);

  /// Advances the clock to @p wall_now [s] (a time earlier than the last one counts as no time
  /// passing). While @p paused the wall clock accrues no simulated time.
  ScheduleStep update(double wall_now, bool paused) noexcept;

  /// Wall-clock time [s] of the next due frame or input poll: the loop may sleep until then.
  double next_due() const noexcept;

  /// Forgets simulated time owed (after a reset or a mode change).
  void clear_backlog() noexcept { owed_ = 0.0; }

  /// Changes the simulated time per tick [s] (> 0; ignored otherwise), e.g. after a mode change.
  void set_control_period(double period) noexcept;

  const ViewerRates& rates() const noexcept { return rates_; }
  double control_period() const noexcept { return period_; }  ///< [s]
  std::int64_t frames() const noexcept { return frames_; }    ///< frames asked for so far
  std::int64_t polls() const noexcept { return polls_; }      ///< input polls asked for so far
  std::int64_t ticks() const noexcept { return ticks_; }      ///< control ticks asked for so far
  /// Simulated time [s] dropped because physics could not keep up with the wall clock.
  double dropped() const noexcept { return dropped_; }

 private:
  ViewerRates rates_;
  double period_;
  double last_wall_;
  double next_render_;
  double next_input_;
  double owed_ = 0.0;  // simulated time owed to the wall clock, < one period after an update
  double dropped_ = 0.0;
  std::int64_t frames_ = 0;
  std::int64_t polls_ = 0;
  std::int64_t ticks_ = 0;
};

}  // namespace mjarm
