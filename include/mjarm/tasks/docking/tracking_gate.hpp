#pragma once
/// @file
/// The free-space tracking gate of the docking controllers: a circle (r = 0.10 m, 0.2 Hz) and
/// then a figure-eight in the world's y-z plane above the socket, no contact, the peg held
/// pointing down; position and orientation RMS per controller. docs/docking.md.

#include <array>
#include <memory>
#include <string>

#include "mjarm/control/reference.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/docking/controller.hpp"
#include "mjarm/tasks/docking/scene.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"

namespace mjarm {

/// The gate's path and timing.
struct TrackingGateOptions {
  DockingControllerOptions controller;        ///< law, force source, gains (the docking ones)
  bool joint_friction = false;                ///< the friction variant of the scene
  std::shared_ptr<const DockingScene> scene;  ///< shared compiled scene; null: built
  double radius = 0.10;           ///< r of the circle; the eight spans ±r in y and ±r/2 in z [m]
  double frequency = 0.2;         ///< f: one loop per 1/f seconds at cruise [Hz]
  double ramp_time = 1.0;         ///< the phase speed ramps in and out over this (< 1/f) [s]
  double height = 0.15;           ///< the start point: the tip this far above the socket's top [m]
  double settle_time = 0.5;       ///< at rest after the eight, still measured [s]
  double max_acceleration = 1e6;  ///< divergence bound on |q̈| [rad/s²]
};

/// The ramp against the loop and the radius against the height are checked by hand.
constexpr auto declared_fields(const TrackingGateOptions*) {
  using S = TrackingGateOptions;
  return declare<S>(
      "tracking gate",
      field("controller", &S::controller, "law, force source, gains (the docking ones)"),
      field("joint_friction", &S::joint_friction, "the friction variant of the scene"),
      field("radius", &S::radius, "m", Range::positive(), "r of the circle"),
      field("frequency", &S::frequency, "Hz", Range::positive(), "loops per second at cruise"),
      field("ramp_time", &S::ramp_time, "s", Range::positive(),
            "the phase speed ramps in and out over this (< 1/frequency)"),
      field("height", &S::height, "m", Range::positive(),
            "the start point: the tip this far above the socket's top"),
      field("settle_time", &S::settle_time, "s", Range::non_negative(),
            "at rest after the eight, still measured"),
      field("max_acceleration", &S::max_acceleration, "rad/s²", Range::positive(),
            "divergence bound on |q̈|"));
}

/// @throws Error naming the value when a size or time is out of range.
void check(const TrackingGateOptions& options);

/// The two loops.
enum class GateSegment { circle, figure_eight };

/// The reference of the gate at @p t seconds from its start (world axes, linear first): each loop
/// starts and ends at rest at the start point c, its phase φ(t) running 0 → 2π with the speed
/// φ̇ = ω·smootherstep ramped in over `ramp_time`, ω = 2πf held, and ramped out:
///   circle:        p = c + r·(0, sin φ, 1 − cos φ)
///   figure-eight:  p = c + r·(0, sin φ, ½·sin 2φ)
/// then rest at c. The orientation is held (R = @p X_start.R); velocity and acceleration are the
/// exact derivatives. Each loop lasts 1/f + ramp_time.
Se3Interpolation::Sample tracking_gate_reference(const TrackingGateOptions& options,
                                                 const Pose& X_start, double t) noexcept;

/// The gate's duration: two loops and the settle time [s].
double tracking_gate_duration(const TrackingGateOptions& options) noexcept;

/// Errors over a stretch of the gate.
struct TrackingErrors {
  int samples = 0;
  double position_rms = 0.0;     ///< RMS of ‖p_E − p_ref‖ [m]
  double orientation_rms = 0.0;  ///< RMS of the angle of R_refᵀ·R_E [rad]
  double max_position = 0.0;     ///< [m]
  double max_orientation = 0.0;  ///< [rad]
};

/// What the gate measured.
struct TrackingGateReport {
  std::string controller;  ///< "cic", "hqp-ac", "se3"
  ForceSource source = ForceSource::sensor;
  RunResult run{};
  Pose X_start;                           ///< the start point c with the held orientation
  std::array<TrackingErrors, 2> loops{};  ///< circle, figure-eight
  TrackingErrors total;                   ///< both loops and the settle time
  int contact_ticks = 0;                  ///< ticks with any contact (must be 0: free space)
  bool ok() const noexcept { return run.ok() && contact_ticks == 0; }
};

/// The gate's targets (issue 13 §4), on the RMS over both loops and the settle time.
struct TrackingGateTargets {
  double position_rms = 0.2e-3;                                    ///< [m]
  double orientation_rms = 0.05 * 3.14159265358979323846 / 180.0;  ///< [rad]
};

/// True when the run finished without contact and both RMS figures are within @p targets.
bool passes(const TrackingGateReport& report, const TrackingGateTargets& targets = {}) noexcept;

/// Runs the gate: the arm starts at rest at c (IK from the home keyframe), the chosen docking
/// controller tracks the reference in a torque-mode simulation (2 ms), and the tip's errors are
/// taken after every tick against the reference of that tick. Stops on Ctrl-C like a run.
/// @throws Error for bad options or controller options, an unreachable start, or a sensor-based
///         controller on a scene without the F/T sensor.
TrackingGateReport run_tracking_gate(const TrackingGateOptions& options);

}  // namespace mjarm
