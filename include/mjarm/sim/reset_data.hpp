#pragma once
/// @file
/// `reset_data`: MuJoCo's reset without clearing the scratch stack.

#include <mujoco/mujoco.h>

namespace mjarm {

/// Puts @p d in the state `mj_resetData` leaves it in — the info header (stack pointer, usage
/// statistics, warnings, timers, solver statistics, sizes, time, energy) and every array of the
/// main buffer zero, qpos = qpos0, mocap bodies at their model poses — without clearing the stack.
/// The stack is scratch that MuJoCo writes before it reads; clearing it is most of the cost of
/// `mj_resetData` (10 MB, 0.3 ms, on the panda scenes: an environment resets every episode).
/// Byte for byte the same main buffer and header as `mj_resetData` (tests/sim/reset_data_test).
void reset_data(const mjModel& m, mjData& d) noexcept;

}  // namespace mjarm
