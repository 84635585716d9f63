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

#include "mjarm/control/cartesian_impedance.hpp"
#include "mjarm/control/controller.hpp"
#include "mjarm/control/hqp_ac.hpp"
#include "mjarm/control/se3_impedance.hpp"
#include "mjarm/control/wrench_source.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/friction_feed_forward.hpp"
#include "mjarm/dynamics/task_space.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/tasks/docking/scene.hpp"
#include "mjarm/tasks/docking/search.hpp"

namespace mjarm {

/// The control laws the docking task compares.
enum class DockingLaw {
  cic,     ///< Cartesian impedance control (`CartesianImpedanceController`, the arm's own Λ)
  hqp_ac,  ///< hierarchical QP with adaptive compliance (`HqpAcController`)
  se3      ///< SE(3) Lie-group impedance with a contact-triggered lateral release
           ///< (`Se3ImpedanceController`)
};

/// The names (`to_string`, JSON and CLI spelling; Python binds `hqp_ac`).
constexpr auto declared_names(const DockingLaw*) {
  using E = DockingLaw;
  return std::array{EnumName{E::cic, "cic"}, EnumName{E::hqp_ac, "hqp-ac"},
                    EnumName{E::se3, "se3"}};
}

/// The law called @p name. @throws Error naming the closest and listing the choices.
DockingLaw docking_law(std::string_view name);
/// Every law, in the order of the docs' tables.
std::span<const DockingLaw> docking_laws() noexcept;

/// Where the controller's measured wrench comes from.
enum class ForceSource {
  sensor,   ///< the F/T sensor pair at the flange (site `iiwa/peg/ft`), the peg's weight removed
  observer  ///< the momentum observer's contact-only estimate (sensorless)
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const ForceSource*) {
  using E = ForceSource;
  return std::array{EnumName{E::sensor, "sensor"}, EnumName{E::observer, "observer"}};
}

/// Gains and settings, per law where they differ (docs/docking.md lists the tuned values and
/// why). Matrices act on [x, y, z, rx, ry, rz]: E's axes for se3, world axes for cic and hqp-ac.
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
  // ---- se3 and hqp-ac
  /// The axes released on contact, E's own [x, y, z, rx, ry, rz] (E's x and y: the peg yields
  /// sideways to the chamfer and to the bore). se3: its stiffness on them goes to zero; hqp-ac
  /// (translational axes only): the reference follows E along them (see `DockingController`).
  std::array<bool, 6> release_axes{true, true, false, false, false, false};
  double release_force = 3.0;      ///< measured ‖f‖ that starts the release [N] (> 0)
  double release_duration = 0.25;  ///< smoothstep [s] (> 0)
  // ---- cic
  Vector6d cic_stiffness =
      (Vector6d() << 1000.0, 1000.0, 1000.0, 60.0, 60.0, 60.0).finished();  ///< K [N/m; N·m/rad]
  double cic_damping_ratio = 1.0;  ///< D = 2ζ·√(Λ_ii·K_i)
  // ---- hqp-ac
  /// K0 [N/m; N·m/rad] (world axes); in free space K_r = K0/2, in contact down to 0.3·K0.
  Vector6d hqp_stiffness = (Vector6d() << 1500.0, 1500.0, 1500.0, 150.0, 150.0, 150.0).finished();
  // ---- all
  double nullspace_stiffness = 10.0;  ///< posture toward reference.joint.q [N·m/rad]
  double nullspace_damping = 5.0;     ///< [N·m·s/rad]
  /// Friction feed-forward from the model's dof_frictionloss (a no-op on the plain model); each
  /// law adds its own.
  bool friction_feed_forward = true;
  /// Its sign: the joint velocity (measured: 0.7 mm RMS in free motion with the Franka friction
  /// against 1.9 mm following the torque, docs/docking.md) or the commanded torque.
  FrictionMode friction_mode = FrictionMode::velocity;
  double control_period = 0.002;  ///< the observer's step [s] (> 0)
};

/// `release_axes` and `friction_mode` are bound by hand.
constexpr auto declared_fields(const DockingControllerOptions*) {
  using S = DockingControllerOptions;
  return declare<S>(
      "docking controller", field("law", &S::law, "the control law"),
      field("source", &S::source, "where the measured wrench comes from"),
      field("sensor_cutoff", &S::sensor_cutoff, "Hz", Range::positive().or_infinity(),
            "low-pass cut-off on the sensor's wrench; inf: none"),
      field("se3_inertia", &S::se3_inertia, "kg; kg·m²", Range::positive(), "se3: A (6,)"),
      field("se3_stiffness", &S::se3_stiffness, "N/m; N·m/rad", Range::positive(), "se3: K (6,)"),
      field("se3_damping_ratio", &S::se3_damping_ratio, "", Range::positive(),
            "se3: D = 2ζ·√(A·K) per axis"),
      field("release_force", &S::release_force, "N", Range::positive(),
            "measured ‖f‖ that starts the release"),
      field("release_duration", &S::release_duration, "s", Range::positive(),
            "smoothstep of the release"),
      field("cic_stiffness", &S::cic_stiffness, "N/m; N·m/rad", Range::positive(), "cic: K (6,)"),
      field("cic_damping_ratio", &S::cic_damping_ratio, "", Range::positive(),
            "cic: D = 2ζ·√(Λ_ii·K_i)"),
      field("hqp_stiffness", &S::hqp_stiffness, "N/m; N·m/rad", Range::positive(),
            "hqp-ac: K0 (6,), world axes"),
      field("nullspace_stiffness", &S::nullspace_stiffness, "N·m/rad", Range::non_negative(),
            "posture toward reference.joint.q"),
      field("nullspace_damping", &S::nullspace_damping, "N·m·s/rad", Range::non_negative(),
            "posture damping"),
      field("friction_feed_forward", &S::friction_feed_forward,
            "friction feed-forward from the model's dof_frictionloss"),
      field("control_period", &S::control_period, "s", Range::positive(), "the observer's step"));
}

/// @throws Error naming the option when a gain or setting is out of range.
void check(const DockingControllerOptions& options);

/// One of the docking laws with its force source, the wrench of the environment on E (world
/// axes, about E's origin) from `WrenchSource`: the F/T sensor at the flange (the peg's weight
/// taken out; one physics step old) or the momentum observer's contact-only estimate (one
/// control period old).
/// - **cic**: `CartesianImpedanceController` (natural inertia, integral on with joint friction,
///   friction feed-forward), owning its source; the preload reference.task.F_ext fed forward.
/// - **hqp-ac**: `HqpAcController` (adaptive compliance, two QPs with hard bounds; the iiwa14's
///   joint speed limits, the motors' torque ranges), owning its source. Its reference gets two
///   things from this wrapper: the preload reference.task.F_ext folded into the acceleration
///   target, A_d + Λ⁻¹·F_ext (exactly the force F_p of its b = A_d + Λ⁻¹·(F_r + F_p) − J̇·q̇, at
///   the hold as for the other laws; its own contact-latched preload is off), and the release:
///   once the measured ‖f‖ of the previous tick reaches `release_force`, the target position is
///   moved by s(t)·P·(p − p_d), P the projector on E's released axes, s a smoothstep over
///   `release_duration`, so that K_r acts on (I − s·P)·e. K_r ≥ 0.3·K0 by design: without the
///   release its spring holds the peg against the wall of a bore whose believed axis is off by
///   more than the radial clearance (docs/docking.md).
/// - **se3**: `Se3ImpedanceController`, configured with its wrench feed-forward (the preload
///   F_ext as a shift of the target by K⁻¹·F_ext on the axes it keeps: its spring makes the
///   force) and its friction feed-forward (`friction_mode`; the damping is cancelled by the law
///   already), and fed by this wrapper: the sensor's wrench through a first-order low-pass
///   (`sensor_cutoff`), in E's axes; the observer told the torque the motors apply (clipped to
///   their ranges). A non-finite sensor reading is skipped (the last good value
///   kept) and counted.
/// `compute` allocates nothing and never throws.
class DockingController final : public Controller, public ContactChannel {
 public:
  /// @throws Error for bad options, or for `ForceSource::sensor` on a scene without the F/T
  ///         sensor pair (naming the site).
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
  const Vector6d& measured_wrench() const noexcept override { return wrench_; }
  /// The search's switch (`ContactChannel`): off undoes the release of se3 and hqp-ac and
  /// keeps contact from starting one; cic has none.
  void set_release_armed(bool armed) noexcept override;
  /// se3 and hqp-ac release; the plain cic does not.
  bool releases() const noexcept override { return options_.law != DockingLaw::cic; }
  /// The diagonal of the stiffness in force at the last compute [N/m; N·m/rad] (se3: K(t)
  /// during a release; hqp-ac: the adaptive K_r, (I − s·P)·K_r during the release, world axes;
  /// cic: K).
  const Vector6d& stiffness() const noexcept { return stiffness_; }
  /// Ticks whose sensor reading was not finite (taken as zero, or the last good value for se3).
  std::int64_t bad_wrench_ticks() const noexcept { return bad_wrench_ticks_; }
  /// The laws (null for the others).
  const Se3ImpedanceController* se3() const noexcept { return se3_.get(); }
  const CartesianImpedanceController* cic() const noexcept { return cic_.get(); }
  const HqpAcController* hqp_ac() const noexcept { return hqp_.get(); }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override;

 private:
  void compute_se3(const mjData& data, const Reference& reference, JointCommand& command) noexcept;
  void compute_hqp(const mjData& data, const Reference& reference, JointCommand& command) noexcept;
  /// reference_ = @p reference (no allocation after the first tick).
  void copy_reference(const Reference& reference) noexcept;

  DockingControllerOptions options_;
  ChainDynamics dynamics_;
  std::unique_ptr<Se3ImpedanceController> se3_;
  std::unique_ptr<CartesianImpedanceController> cic_;
  std::unique_ptr<HqpAcController> hqp_;
  Controller* law_ = nullptr;
  std::optional<WrenchSource> source_;           // se3 only: the others own theirs
  std::optional<TaskSpaceDynamics> task_space_;  // hqp-ac: Λ⁻¹ for the preload
  bool release_started_ = false;                 // hqp-ac's release
  bool release_armed_ = true;
  double release_start_ = 0.0;
  double release_ = 0.0;
  double alpha_ = 1.0;  // low-pass gain per control tick
  Vector6d wrench_ = Vector6d::Zero();
  Vector6d stiffness_ = Vector6d::Zero();
  std::int64_t bad_wrench_ticks_ = 0;
  Reference reference_;  // the law's reference (preload shift), reused storage
  Eigen::VectorXd lower_, upper_, tau_;
  std::vector<std::string> names_;
  mutable std::vector<double> values_;
};

}  // namespace mjarm
