#pragma once
/// @file
/// `TickObserver`: something that looks at the state of every control tick of a task's run
/// (a video, a live plot) without taking part in the control.

#include <mujoco/mujoco.h>

namespace mjarm {

/// Sees the simulation's state once per control tick, read-only. A task calls it at the start of
/// its `update`, when @p data holds fresh positions, velocities and kinematics (xpos, site poses)
/// for data.time. An observer must not change the run: it gets a const state and cannot stop
/// the run; failures are its own to keep (see `RunVideo::error`).
class TickObserver {
 public:
  virtual ~TickObserver() = default;
  /// One control tick at simulated time data.time [s].
  virtual void on_tick(const mjData& data) noexcept = 0;
};

}  // namespace mjarm
