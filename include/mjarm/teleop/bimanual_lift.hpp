#pragma once
/// @file
/// The scripted bimanual task: both hands of a two-handed `TeleopSession` grasp a bar lying
/// across a table by its two ends (fingers closing across the bar's thickness), lift it, hold it,
/// and the outcome is judged from the bar's pose. It drives the session only through its targets
/// (a `SessionRecorder`), exactly as a person at the viewer would, so the recorded session
/// replays to the same motion. The bundled scene is `dual_arm_box` (docs/teleop.md).

#include <cstdint>
#include <functional>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/teleop/session_log.hpp"

namespace mjarm {

/// Geometry and timing of the scripted lift.
struct BimanualLiftOptions {
  std::string object = "bar";     ///< free body to lift
  double grasp_offset = 0.16;     ///< grasp points at ±this along the bar's long axis [m]
  double grasp_height = 0.02;     ///< tool frames this far above the bar's centre [m]
  double approach_height = 0.12;  ///< pre-grasp height above the grasp [m]
  double lift_height = 0.2;       ///< how high the bar is to be lifted [m]
  double approach_time = 2.0;     ///< [s] to the pre-grasp poses
  double descend_time = 1.0;      ///< [s] down to the grasp
  double close_time = 1.0;        ///< [s] closing the fingers
  double lift_time = 2.5;         ///< [s] lifting
  double hold_time = 1.0;         ///< [s] holding at the top
  double tolerance = 0.01;        ///< the bar must rise lift_height − this, and not sink by more
};

constexpr auto declared_fields(const BimanualLiftOptions*) {
  using S = BimanualLiftOptions;
  return declare<S>(
      "bimanual lift", field("object", &S::object, "free body to lift"),
      field("grasp_offset", &S::grasp_offset, "m", Range::finite(),
            "grasp points at ±this along the bar's long axis"),
      field("grasp_height", &S::grasp_height, "m", Range::finite(),
            "tool frames this far above the bar's centre"),
      field("approach_height", &S::approach_height, "m", Range::non_negative(),
            "pre-grasp height above the grasp"),
      field("lift_height", &S::lift_height, "m", Range::non_negative(), "how high to lift the bar"),
      field("approach_time", &S::approach_time, "s", Range::non_negative(), "to the pre-grasp poses"),
      field("descend_time", &S::descend_time, "s", Range::non_negative(), "down to the grasp"),
      field("close_time", &S::close_time, "s", Range::non_negative(), "closing the fingers"),
      field("lift_time", &S::lift_time, "s", Range::non_negative(), "lifting"),
      field("hold_time", &S::hold_time, "s", Range::non_negative(), "holding at the top"),
      field("tolerance", &S::tolerance, "m", Range::non_negative(),
            "the bar must rise lift_height − this, and not sink by more"));
}

/// What the scripted lift did.
struct BimanualLiftResult {
  bool success = false;  ///< lifted by lift_height − tolerance and held through the hold
  double start_z = 0.0;  ///< bar height at the start [m]
  double end_z = 0.0;    ///< at the end [m]
  double lifted = 0.0;   ///< end_z − start_z [m]
  double sag = 0.0;      ///< largest drop of the bar below its height at the start of the hold [m]
  double grasp_force[2] = {0.0, 0.0};  ///< finger normal force per hand at the end [N]
  std::int64_t ticks = 0;
  std::string failure;  ///< why it failed (empty on success)
};

/// Runs the scripted lift on @p recorder's session (which must have two hands, left first).
/// @param on_tick optional: sees the session after every tick (a video, a progress bar)
/// @throws Error when the session does not have two hands or the model has no body
///         `options.object` with a free joint.
BimanualLiftResult run_bimanual_lift(SessionRecorder& recorder,
                                     const BimanualLiftOptions& options = {},
                                     const std::function<void(const TeleopSession&)>& on_tick = {});

}  // namespace mjarm
