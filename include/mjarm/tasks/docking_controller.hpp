#pragma once
/// @file
/// `DockingController`: the controllers of the docking task by name (cic, hqp-ac, se3), each fed
/// the wrench of the environment on the peg tip from the F/T sensor at the flange or from the
/// momentum observer (sensorless), with the preload and the friction feed-forward. docs/docking.md.

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/control/se3_impedance.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/force_torque_sensor.hpp"
#include "mjarm/dynamics/friction_feed_forward.hpp"
#include "mjarm/dynamics/momentum_observer.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/tasks/docking_scene.hpp"

namespace mjarm {

/// The control laws the docking task compares.
enum class DockingLaw {
  cic,     ///< Cartesian impedance (operational space, the arm's own task inertia)
  hqp_ac,  ///< hierarchical QP with adaptive compliance
  se3      ///< SE(3) Lie-group impedance with a contact-triggered lateral release
};

/// Human name ("cic", "hqp-ac", "se3").
const char* to_string(DockingLaw law) noexcept;
/// The law called @p name. @throws Error listing the choices.
DockingLaw docking_law(std::string_view name);
/// Every law, in the order of the docs' tables.
std::span<const DockingLaw> docking_laws() noexcept;

/// Where the controller's measured wrench comes from.
enum class ForceSource {
  sensor,   ///< the F/T sensor pair at the flange (site `iiwa/peg/ft`), the peg's weight removed
  observer  ///< the momentum observer's contact-only estimate (sensorless)
};

/// Human name ("sensor", "observer").
const char* to_string(ForceSource source) noexcept;

/// Gains and settings, per law where they differ (docs/docking.md lists the tuned values and
/// why). Matrices act on [x, y, z, rx, ry, rz]: E's axes for se3, world axes for cic.
struct DockingControllerOptions {
  DockingLaw law = DockingLaw::se3;
  ForceSource source = ForceSource::sensor;
  /// Cut-off of the first-order low-pass on the sensor's wrench [Hz] (> 0; +inf: none). A real
  /// F/T sensor is read through such a filter; without it the SE(3) law, which cancels the
  /// measured wrench one physics step late, chatters against the stiff contact.
  double sensor_cutoff = 30.0;
  // ---- se3
  Vector6d se3_inertia =
      (Vector6d() << 5.0, 5.0, 5.0, 0.2, 0.2, 0.2).finished();  ///< A [kg; kg·m²]
  Vector6d se3_stiffness =
      (Vector6d() << 1000.0, 1000.0, 1000.0, 60.0, 60.0, 60.0).finished();  ///< K [N/m; N·m/rad]
  double se3_damping_ratio = 1.0;  ///< D = 2ζ·√(A·K) per axis
  /// The axes released on contact (E's x and y: the peg yields sideways to the chamfer).
  std::array<bool, 6> se3_release{true, true, false, false, false, false};
  double release_force = 3.0;      ///< ‖f‖ that starts the release [N]
  double release_duration = 0.25;  ///< smoothstep [s]
  // ---- cic
  Vector6d cic_stiffness =
      (Vector6d() << 1000.0, 1000.0, 1000.0, 60.0, 60.0, 60.0).finished();  ///< K [N/m; N·m/rad]
  double cic_damping_ratio = 1.0;  ///< D = 2ζ·√(Λ_ii·K_i)
  // ---- all
  double nullspace_stiffness = 10.0;  ///< posture toward reference.joint.q [N·m/rad]
  double nullspace_damping = 5.0;     ///< [N·m·s/rad]
  /// Friction feed-forward from the model's dof_frictionloss (a no-op on the plain model).
  bool friction_feed_forward = true;
  /// Its sign: the joint velocity (measured: 0.7 mm RMS in free motion with the Franka friction
  /// against 1.9 mm following the torque, docs/docking.md) or the commanded torque.
  FrictionMode friction_mode = FrictionMode::velocity;
  double control_period = 0.002;  ///< the observer's step [s] (> 0)
};

/// @throws Error naming the option when a gain or setting is out of range.
void check(const DockingControllerOptions& options);

/// One of the docking laws with its force source. Each tick:
/// 1. the measured wrench F_m of the environment on E (world axes, about E's origin): the
///    sensor's reading −S − [m·g; (c − p_E) × m·g] (S moved to world axes about p_E, the peg's
///    weight m·g at its centre of mass c taken out; one physics step old) through the low-pass,
///    or the observer's contact-only F̂ (one control period old);
/// 2. the law: se3 gets F_m in E's axes (`Se3ImpedanceController::set_measured_wrench`); the
///    preload reference.task.F_ext (the wrench E should exert, world axes) becomes a shift of
///    its target by K⁻¹·F_ext on the axes not released (the SE(3) law has no force
///    feed-forward: its spring makes the force); cic feeds F_ext forward itself;
/// 3. the friction feed-forward (`friction_mode`): velocity mode f⊙tanh(q̇/v₀), or torque mode
///    f⊙tanh(s·τ_m/f) on the part τ_m = τ − h + τ_passive of the torque that moves the joints
///    (following the whole τ would push every joint against gravity at rest); the joint
///    damping is cancelled by the law already (qfrc_passive), not twice;
/// 4. the observer is told the torque the motors will apply (τ clipped to their ranges).
/// A non-finite sensor reading is taken as zero for the tick and counted. `compute` allocates
/// nothing and never throws.
class DockingController final : public Controller {
 public:
  /// @throws Error for bad options, for `ForceSource::sensor` on a scene without the F/T sensor
  ///         pair (naming the site), or for hqp-ac before that law is built.
  DockingController(const DockingScene& scene, const DockingControllerOptions& options);
  ~DockingController() override;

  std::string_view name() const noexcept override { return to_string(options_.law); }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return dynamics_.chain(); }
  const DockingControllerOptions& options() const noexcept { return options_; }

  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  void reset() noexcept override;

  /// The measured wrench the law used at the last compute (world axes, about E) [N; N·m].
  const Vector6d& measured_wrench() const noexcept { return wrench_; }
  /// The diagonal of the stiffness in force at the last compute [N/m; N·m/rad] (se3: K(t)
  /// during a release).
  const Vector6d& stiffness() const noexcept { return stiffness_; }
  /// Ticks whose sensor reading was not finite (taken as zero).
  std::int64_t bad_wrench_ticks() const noexcept { return bad_wrench_ticks_; }
  /// The SE(3) law (null for the others).
  const Se3ImpedanceController* se3() const noexcept { return se3_.get(); }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override;

 private:
  void measure(const mjData& data) noexcept;

  DockingControllerOptions options_;
  ChainDynamics dynamics_;
  std::unique_ptr<Se3ImpedanceController> se3_;
  std::unique_ptr<OperationalSpaceController> cic_;
  Controller* law_ = nullptr;
  std::optional<ForceTorqueSensor> sensor_;
  std::optional<MomentumObserver> observer_;
  FrictionFeedForward friction_;
  double peg_mass_ = 0.0;
  Eigen::Vector3d peg_com_E_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  double alpha_ = 1.0;  // low-pass gain per physics step
  bool filtered_ = false;
  Vector6d wrench_ = Vector6d::Zero();
  Vector6d stiffness_ = Vector6d::Zero();
  std::int64_t bad_wrench_ticks_ = 0;
  Reference reference_;  // the law's reference (preload shift), reused storage
  Eigen::VectorXd lower_, upper_, tau_, move_;
  std::vector<std::string> names_;
  mutable std::vector<double> values_;
};

}  // namespace mjarm
