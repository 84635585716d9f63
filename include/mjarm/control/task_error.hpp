#pragma once
/// @file
/// The end-effector error shared by the task-space controllers: translation error of E's origin
/// and log-map orientation error, both in world axes, linear first.

#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Which end-effector directions a task-space controller regulates.
enum class TaskMode {
  pose,     ///< 6 rows: position and orientation of E
  position  ///< 3 rows: position of E's origin only (orientation left free)
};

/// Number of task rows m of @p mode: 6 for pose, 3 for position.
constexpr int task_rows(TaskMode mode) noexcept { return mode == TaskMode::pose ? 6 : 3; }

constexpr auto declared_names(const TaskMode*) {
  return std::array{EnumName{TaskMode::pose, "pose", "6 rows: position and orientation"},
                    EnumName{TaskMode::position, "position", "3 rows: position of E's origin"}};
}

/// The pose error of E relative to the desired frame D, in world axes, linear first:
///
///     e = [p_WD − p_WE;  log(R_WD·R_WEᵀ)]   (m; rad)
///
/// The angular part is the rotation vector ω (world axes, ‖ω‖ ≤ π) with exp(ω)·R_WE = R_WD:
/// turning E about ω brings it onto D. Translation and rotation are decoupled (this is not the
/// SE(3) log, whose linear part mixes in the rotation); to first order ė = V_WD − V_WE with V
/// the world-aligned twists [v; ω] of D and E.
/// @param X_WE pose of the end-effector frame E in W
/// @param X_WD desired pose of E in W
Vector6d task_error(const Pose& X_WE, const Pose& X_WD) noexcept;

}  // namespace mjarm
