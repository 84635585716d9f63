#pragma once
/// @file
/// How a `Simulation` runs: its mode, control period and divergence bound.

#include <limits>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/sim/contact_query.hpp"

namespace mjarm {

/// The three ways a `Simulation` moves the robot.
enum class SimulationMode {
  /// Positions are written directly (`Simulation::move`), forward kinematics only, time advanced
  /// by hand; no dynamics, no controllers. Optional contact check with rollback.
  kinematic,
  /// Position servos driven by position targets (`CommandKind::position`), plus gravity
  /// compensation on the servo-driven dofs.
  position,
  /// Motors driven by torques (`CommandKind::torque`): ctrl = τ ÷ (gear·gain), clipped.
  torque
};

constexpr auto declared_names(const SimulationMode*) {
  using M = SimulationMode;
  return std::array{EnumName{M::kinematic, "kinematic", "positions written directly, no dynamics"},
                    EnumName{M::position, "position", "position servos, gravity compensated"},
                    EnumName{M::torque, "torque", "motors driven by torques"}};
}

/// The number of whole @p step periods [s] in @p period [s] (to 1e-9 relative), for a control
/// period made of physics steps (or of controller periods).
/// @param what names the period in the message ("simulation: control_period")
/// @param step_name names the step ("the timestep")
/// @throws Error "<what> 0.015 s is not a whole multiple of the timestep 0.002 s (nearest:
///         0.016 s)", or when @p period is not positive and finite.
int whole_multiple(double period, double step, std::string_view what, std::string_view step_name);

/// Options of a `Simulation`; checked by its constructor (declared below).
struct SimulationOptions {
  SimulationMode mode = SimulationMode::torque;

  /// Control period [s]: the controllers run once per period. 0 means one physics step. Must be a
  /// whole multiple of the model's timestep (to 1e-9 relative).
  double control_period = 0.0;

  /// Position mode only: every physics step, add the bias forces qfrc_bias (gravity, Coriolis,
  /// centrifugal) of each dof driven by a position servo to qfrc_applied, so the servos do not
  /// sag under gravity. Ignored in the other modes. Switch it off for a controller that
  /// compensates through its servo targets (`GravityCompensationController`):
  /// `Simulation::add_controller` refuses that pairing.
  bool gravity_compensation = true;

  /// Divergence bound on |qacc| [rad/s² or m/s²]: a larger acceleration stops the run as diverged.
  /// +infinity leaves only the NaN/inf checks and MuJoCo's own (|x| > 1e10).
  double max_acceleration = 1e6;

  /// Step a private copy of the model (`Simulation::editable_model`) instead of the robot's
  /// shared one, so that its owner can change parameters between steps without touching other
  /// users of the `Robot` (domain randomization). A `WeldGrasp` gives the simulation a copy too
  /// (`Simulation::own_model()`); switching equality constraints needs none (`mjData::eq_active`).
  bool own_model = false;

  /// Kinematic mode only: a `move` that puts a geom of `contact_check_a` in contact with a geom of
  /// `contact_check_b` (as MuJoCo's collision detection reports it, i.e. within the geoms'
  /// margins) is rolled back and reported. Empty sets disable the check; an empty `b` with a
  /// non-empty `a` means "any other geom".
  GeomSet contact_check_a;
  GeomSet contact_check_b;
};

constexpr auto declared_fields(const SimulationOptions*) {
  using S = SimulationOptions;
  return declare<S>(
      "simulation", field("mode", &S::mode, "how the robot moves"),
      field("control_period", &S::control_period, "s", Range::non_negative(),
            "the controllers' period, a whole multiple of the timestep; 0: one physics step"),
      field("gravity_compensation", &S::gravity_compensation,
            "position mode: add the bias forces of the servo-driven dofs"),
      field("max_acceleration", &S::max_acceleration, "rad/s² or m/s²",
            Range::positive().or_infinity(), "divergence bound on |qacc|; +inf: none"),
      field("own_model", &S::own_model, "step a private copy of the model"));
}

}  // namespace mjarm
