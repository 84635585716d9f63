#pragma once
/// @file
/// `TaskPdController`: task-space PD through the Jacobian transpose, with gravity compensation.

#include <array>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/task_error.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Gains of a `TaskPdController`. Entries are [x, y, z, rx, ry, rz] in world axes; in
/// `TaskMode::position` only the first three are used (and checked).
struct TaskPdOptions {
  TaskMode mode = TaskMode::pose;  ///< 6-D pose or 3-D position task
  /// Kp: stiffness [N/m for x, y, z; N·m/rad for rx, ry, rz] (≥ 0).
  Vector6d stiffness = (Vector6d() << 600.0, 600.0, 600.0, 40.0, 40.0, 40.0).finished();
  /// Kd: damping [N·s/m; N·m·s/rad] (≥ 0).
  Vector6d damping = (Vector6d() << 60.0, 60.0, 60.0, 4.0, 4.0, 4.0).finished();
  /// Adds the gravity torques g(q) (true) or not (false: a pure spring-damper).
  bool gravity_compensation = true;
  /// Joint damping added in joint space, −d·q̇ [N·m·s/rad or N·s/m] (≥ 0): damps the self-motion
  /// of a redundant arm, which Jᵀ never sees. 0 by default (the plain law).
  double joint_damping = 0.0;
};

constexpr auto declared_fields(const TaskPdOptions*) {
  using S = TaskPdOptions;
  return declare<S>("task-pd", field("mode", &S::mode, "6-D pose or 3-D position task"),
                    field("stiffness", &S::stiffness, "N/m; N·m/rad", Range::non_negative(),
                          "Kp, [x, y, z, rx, ry, rz] world axes"),
                    field("damping", &S::damping, "N·s/m; N·m·s/rad", Range::non_negative(),
                          "Kd, [x, y, z, rx, ry, rz] world axes"),
                    field("gravity_compensation", &S::gravity_compensation, "add g(q)"),
                    field("joint_damping", &S::joint_damping, "N·m·s/rad or N·s/m",
                          Range::non_negative(), "joint-space damping −d·q̇"));
}

/// Task-space PD (Jacobian-transpose) control of the chain's frame E:
///
///     τ = Jᵀ·(Kp·e + Kd·ė) + g(q) − d·q̇
///
/// with e = task_error(X_WE, X_WD) (world axes, linear first), ė = V_WD − J·q̇, J the
/// world-aligned Jacobian (its first 3 rows in position mode) and g the gravity torques. Reads
/// `reference.task` (X_WE, V_WE). For a static target the rest state is exact (gravity is
/// cancelled and nothing else acts at rest); a moving target is tracked with a lag, since the
/// arm's inertia is not fed forward (use `AccelerationController` or the operational-space one).
///
/// Internals: position_error [m], orientation_error [rad] (0 in position mode).
class TaskPdController final : public Controller {
 public:
  /// @throws Error when a gain is negative or not finite.
  explicit TaskPdController(const Chain& chain, const TaskPdOptions& options = {});

  std::string_view name() const noexcept override { return "task-pd"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  const TaskPdOptions& options() const noexcept { return options_; }

  /// One tick; a command of the wrong size is left untouched.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  TaskPdOptions options_;
  int rows_ = 6;
  ChainDynamics dynamics_;
  Vector6d wrench_ = Vector6d::Zero();
  std::array<std::string, 2> names_{"position_error", "orientation_error"};
  std::array<double, 2> values_{0.0, 0.0};
};

}  // namespace mjarm
