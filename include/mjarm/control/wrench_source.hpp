#pragma once
/// @file
/// `WrenchSource`: where a compliant controller gets the external wrench on its end effector —
/// an F/T sensor (with the tool's weight taken out) or the momentum observer (sensorless) — as
/// the wrench the environment exerts on E, in world axes, about E's origin.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <optional>
#include <string>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/force_torque_sensor.hpp"
#include "mjarm/dynamics/momentum_observer.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// Which signal a controller takes the external wrench from.
enum class WrenchSourceKind {
  none,      ///< no measurement: the wrench is always zero
  sensor,    ///< a force/torque sensor pair on a site (`ForceTorqueSensor`)
  observer,  ///< the generalized-momentum observer of the chain (`MomentumObserver`)
};

constexpr auto declared_names(const WrenchSourceKind*) {
  using K = WrenchSourceKind;
  return std::array{EnumName{K::none, "none", "no measurement: zero wrench"},
                    EnumName{K::sensor, "sensor", "a force/torque sensor pair on a site"},
                    EnumName{K::observer, "observer", "the generalized-momentum observer"}};
}

/// Settings of a `WrenchSource`.
struct WrenchSourceOptions {
  WrenchSourceKind kind = WrenchSourceKind::none;  ///< none, sensor or observer
  /// sensor: the site that carries the `<force>` and `<torque>` sensors (e.g. the flange).
  std::string site;
  /// sensor: when sensordata was computed relative to the state the controller reads
  /// (`after_step` for `Simulation`'s Euler split step: one physics step old).
  SensorTiming timing = SensorTiming::after_step;
  /// sensor: subtract the weight of everything the sensor carries (the subtree of the sensor's
  /// body: body_subtreemass at subtree_com), so that a tool at rest in free space reads zero.
  /// The tool's inertial forces when it accelerates are not subtracted.
  bool compensate_tool_weight = true;
  /// observer: its gains and Cᵀ·q̇ method.
  MomentumObserverOptions observer;
  /// observer: use the contact-only estimate (the model's joint friction and damping taken out,
  /// `MomentumObserver::contact_wrench`) rather than every disturbance (`wrench`).
  bool contact_only = true;
  /// observer: the time between two control ticks [s] (> 0), the step over which the observer
  /// predicts the momentum; 0 (default) measures it from data.time between ticks (the model's
  /// timestep before the second tick).
  double control_period = 0.0;
};

// `observer` stays undeclared: the observer checks its gains, only when it is the source
constexpr auto declared_fields(const WrenchSourceOptions*) {
  using S = WrenchSourceOptions;
  return declare<S>(
      "wrench source", field("kind", &S::kind, "none, sensor or observer"),
      field("site", &S::site, "sensor: the site carrying the force and torque sensors"),
      field("timing", &S::timing, "sensor: when sensordata was computed"),
      field("compensate_tool_weight", &S::compensate_tool_weight,
            "sensor: subtract the weight the sensor carries"),
      field("contact_only", &S::contact_only, "observer: the contact-only estimate"),
      field("control_period", &S::control_period, "s", Range::non_negative(),
            "observer: time between two ticks; 0: measured"));
}

/// The external wrench on the chain's frame E for a controller: F_E = [f; τ] (N; N·m), the
/// wrench the environment exerts on E, in world axes, torque about E's origin.
///
/// - **sensor**: F_E = −S − [m·g; (c − p_E) × m·g], with S the sensor reading moved to world
///   axes about p_E (`ForceTorqueSensor::read_world`), m and c the mass and centre of mass of
///   the sensor body's subtree and g the model's gravity (with `compensate_tool_weight`). The
///   reading is one physics step old after `mj_step`/`mj_step1` (`SensorTiming::after_step`).
/// - **observer**: F_E = the observer's F̂ (contact-only by default). The observer needs the
///   torque the motors apply: the controller calls `record_command` with it each tick, after
///   computing it, and `measure` returns the estimate of the previous tick (one control period
///   old, as a sensor reading after a step would be).
/// - **none**: F_E = 0.
///
/// `measure` and `record_command` allocate nothing and never throw.
class WrenchSource {
 public:
  /// @throws Error for the sensor kind when the site does not exist (naming it, with the closest
  ///         names) or carries no force or torque sensor (naming the site and the missing
  ///         sensor), for an observer option out of range, or for a control period not ≥ 0
  ///         and finite.
  WrenchSource(const Chain& chain, const WrenchSourceOptions& options = {});

  WrenchSourceKind kind() const noexcept { return options_.kind; }
  const WrenchSourceOptions& options() const noexcept { return options_; }

  /// Takes this tick's measurement for the state in @p d, with E at @p X_WE (the chain frame's
  /// pose in @p d, e.g. `ChainDynamics::pose`). A non-finite reading gives status non_finite
  /// and a zero wrench.
  WrenchStatus measure(const mjData& d, const Pose& X_WE) noexcept;

  /// Observer only (a no-op otherwise): the motor torque @p tau (n, chain order) commanded for
  /// the state in @p d, whose dynamics @p dynamics holds. Returns the observer's status (ok for
  /// the other kinds).
  ObserverStatus record_command(const mjData& d, const ChainDynamics& dynamics,
                                const Eigen::Ref<const Eigen::VectorXd>& tau) noexcept;

  /// The wrench of the last `measure` (world axes, about E's origin) [N; N·m].
  const Vector6d& wrench() const noexcept { return wrench_; }
  /// Status of the last `measure`.
  WrenchStatus status() const noexcept { return status_; }
  /// Simulation time the last measurement refers to [s].
  double time() const noexcept { return time_; }

  /// Forgets the observer's estimate and the last measurement.
  void reset() noexcept;

  /// The sensor (sensor kind), else nullptr.
  const ForceTorqueSensor* sensor() const noexcept { return sensor_ ? &*sensor_ : nullptr; }
  /// The observer (observer kind), else nullptr.
  const MomentumObserver* observer() const noexcept { return observer_ ? &*observer_ : nullptr; }

 private:
  WrenchSourceOptions options_;
  const mjModel* model_ = nullptr;
  std::optional<ForceTorqueSensor> sensor_;
  std::optional<MomentumObserver> observer_;
  int tool_body_ = -1;      // the sensor site's body (its subtree is the tool)
  double tool_mass_ = 0.0;  // body_subtreemass of it [kg]
  Vector6d wrench_ = Vector6d::Zero();
  WrenchStatus status_ = WrenchStatus::ok;
  double time_ = 0.0;
  double last_command_time_ = 0.0;
  bool has_command_time_ = false;
  double period_ = 0.0;  // the observer's step [s]
};

}  // namespace mjarm
