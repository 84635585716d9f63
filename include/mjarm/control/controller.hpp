#pragma once

#include <mujoco/mujoco.h>

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/command.hpp"
#include "mjarm/control/reference.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// One control law. It reads the current state from `mjData` and a `Reference`, and writes a
/// `JointCommand` for its chain.
///
/// Contract: `data` has fresh kinematics and dynamics for its qpos/qvel (the state after
/// `mj_forward`, or after `mj_step1` in a split step): xpos/xmat, site poses, M, qfrc_bias are
/// valid. `compute` never allocates, never throws and never writes to `data`; it may use only
/// its own preallocated workspace.
class Controller {
 public:
  virtual ~Controller() = default;

  /// Short identifier, e.g. "osc", "ct", "joint-pd".
  virtual std::string_view name() const noexcept = 0;

  /// Whether `compute` writes torques or position targets.
  virtual CommandKind command_kind() const noexcept = 0;

  /// The chain this controller commands; `command.value` has chain().size() entries.
  virtual const Chain& chain() const noexcept = 0;

  /// Computes one tick's command. `command.value` must already have chain().size() entries.
  virtual void compute(const mjData& data, const Reference& reference,
                       JointCommand& command) noexcept = 0;

  /// True when the commands already cancel the bias forces (gravity, possibly Coriolis) through
  /// the servo targets, as `GravityCompensationController` does. A `Simulation` in position mode
  /// with `SimulationOptions::gravity_compensation` on also adds those forces, so it refuses such
  /// a controller rather than compensate twice.
  virtual bool compensates_bias() const noexcept { return false; }

  /// Forgets internal state (integrators, filters) before a new run.
  virtual void reset() noexcept {}

  /// Names of the controller internals a recorder logs each tick (fixed after construction).
  virtual std::span<const std::string> internal_names() const noexcept { return {}; }

  /// Values of those internals from the last `compute`, same order as `internal_names()`.
  virtual std::span<const double> internal_values() const noexcept { return {}; }
};

}  // namespace mjarm
