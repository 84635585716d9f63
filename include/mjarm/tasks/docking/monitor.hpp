#pragma once
/// @file
/// What a docking run is judged on: one `DockingSample` per control tick (the ground truth of
/// the simulation: contacts, pose, joints), the seating criteria (`DockingCriteria`) and the
/// metrics computed from the samples (`evaluate_docking`, `DockingMetrics`). docs/docking.md.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/kinematics/manipulability.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/tasks/docking/scene.hpp"

namespace mjarm {

/// One control tick of a docking run, in world axes.
struct DockingSample {
  double t = 0.0;                    ///< time since the start of the motion [s]
  Pose X_WE;                         ///< the peg tip E
  Vector6d V_WE = Vector6d::Zero();  ///< its velocity [v; ω] [m/s; rad/s]
  Pose X_WD;                         ///< the reference pose of E at this tick
  /// Wrench of the socket on the peg, summed over their contacts: [f; τ] with τ about E's
  /// origin [N; N·m]. The ground truth from MuJoCo's contact forces, not a measurement.
  Vector6d F_peg = Vector6d::Zero();
  int contacts = 0;  ///< peg–socket contacts (active, within the margins)
  bool other_contact =
      false;             ///< any contact that is not peg–socket (arm on socket, peg on floor…)
  int other_geom1 = -1;  ///< the first such contact's geoms (−1 when none)
  int other_geom2 = -1;
  bool saturated = false;     ///< some motor was clipped to its torque limit this tick
  bool within_limits = true;  ///< every joint inside its range
  double joint_position_ratio =
      0.0;  ///< max over joints of |q − mid| / half range (1 = at a limit)
  double joint_velocity_ratio = 0.0;  ///< max over joints of |q̇| / v_max
  double manipulability = 0.0;        ///< √det(J·Jᵀ) of the full 6 × 7 J_WE
  bool finite = true;                 ///< pose, velocity, wrench and joints all finite
  // what the controller saw (filled by the run, not by the probe)
  Vector6d F_measured = Vector6d::Zero();  ///< its measured wrench on E (world, about E)
  Vector6d stiffness = Vector6d::Zero();   ///< its stiffness diagonal [N/m; N·m/rad]
};

/// Seating criteria (the issue's, docs/docking.md). Over the last `window` of the run: depth
/// reached, lateral and tilt small, settled, in contact; over the whole run: force, axial moment,
/// saturation, joint limits, other contacts, finiteness.
struct DockingCriteria {
  double window = 1.0;                                     ///< the final window judged [s]
  double depth_tolerance = 1e-3;                           ///< depth ≥ full depth − this [m]
  double max_lateral = 0.5e-3;                             ///< tip to bore axis [m]
  double max_tilt = 0.5 * 3.14159265358979323846 / 180.0;  ///< peg axis to bore axis [rad]
  double max_speed = 3e-3;                                 ///< tip speed [m/s]
  double max_angular_speed = 2.0 * 3.14159265358979323846 / 180.0;  ///< [rad/s]
  double min_contact_fraction = 0.95;  ///< of the window's samples in peg–socket contact
  double max_force = 40.0;             ///< peak ‖f‖ of the contact force [N]
  double max_axial_moment = 2.0;       ///< peak |τ·z_S| about the tip [N·m]
  double max_saturation = 0.01;        ///< fraction of ticks with a clipped motor
};

constexpr auto declared_fields(const DockingCriteria*) {
  using S = DockingCriteria;
  return declare<S>(
      "docking criteria",
      field("window", &S::window, "s", Range::positive(), "the final window judged"),
      field("depth_tolerance", &S::depth_tolerance, "m", Range::positive(),
            "depth ≥ full depth − this"),
      field("max_lateral", &S::max_lateral, "m", Range::positive(), "tip to bore axis"),
      field("max_tilt", &S::max_tilt, "rad", Range::positive(), "peg axis to bore axis"),
      field("max_speed", &S::max_speed, "m/s", Range::positive(), "tip speed"),
      field("max_angular_speed", &S::max_angular_speed, "rad/s", Range::positive(),
            "peg angular speed"),
      field("min_contact_fraction", &S::min_contact_fraction, "", Range::open_closed(0.0, 1.0),
            "of the window's samples in peg–socket contact"),
      field("max_force", &S::max_force, "N", Range::positive(), "peak ‖f‖ of the contact force"),
      field("max_axial_moment", &S::max_axial_moment, "N·m", Range::positive(),
            "peak |τ·z_S| about the tip"),
      field("max_saturation", &S::max_saturation, "", Range::open_closed(0.0, 1.0),
            "fraction of ticks with a clipped motor"));
}

/// @throws Error naming the criterion when one is out of its declared range.
void check(const DockingCriteria& criteria);

/// Where the socket is: the true socket frame S (z out of the hole) and the depth of the hole.
struct DockingGoal {
  Pose X_WS;                ///< the socket frame (docking_scene.hpp)
  double full_depth = 0.0;  ///< chamfer + bore depth [m]: the tip's depth when seated
};

/// Where the tip E stands in a socket S.
struct DockingInsertion {
  double depth = 0.0;    ///< below the top face, along the insertion direction −z_S [m]
  double lateral = 0.0;  ///< distance to the bore's axis [m]
  double tilt = 0.0;     ///< angle between the peg's axis z_E and the bore's axis −z_S [rad]
};

/// The insertion of the tip at @p X_WE in the socket at @p X_WS (what the seating criteria judge).
DockingInsertion docking_insertion(const Pose& X_WE, const Pose& X_WS) noexcept;

/// Metrics of one run. Axial = along the insertion direction −z_S; forces are the socket's on
/// the peg (positive axial force: the peg pushes into the socket).
struct DockingMetrics {
  int samples = 0;
  // ---- the whole run
  double peak_force = 0.0;          ///< max ‖f‖ [N]
  double peak_axial_force = 0.0;    ///< max f·z_S (the peg pushing in) [N]
  double peak_wrench = 0.0;         ///< max ‖[f; τ]‖ (τ about the tip) [N, N·m mixed]
  double peak_axial_moment = 0.0;   ///< max |τ·z_S| [N·m]
  double max_joint_position = 0.0;  ///< max |q − mid| / half range [% of the limit]
  double max_joint_velocity = 0.0;  ///< max |q̇| / v_max [% of the limit]
  double min_manipulability = 0.0;  ///< min √det(J·Jᵀ)
  /// RMS of ‖p_E − p_D‖ and of the rotation angle of R_Dᵀ·R_E over the samples before the first
  /// peg–socket contact (free motion; in contact the reference is meant to be left) [m], [rad].
  double position_rms = 0.0;
  double orientation_rms = 0.0;
  int free_samples = 0;              ///< samples in that RMS
  double saturation = 0.0;           ///< fraction of ticks with a clipped motor
  double first_contact_time = std::numeric_limits<double>::quiet_NaN();  ///< [s]; NaN: never
  bool joint_limits_ok = true;
  bool other_contact = false;
  int other_geom1 = -1, other_geom2 = -1;
  bool finite = true;
  // ---- the final window
  double steady_axial_force = 0.0;  ///< mean f·z_S [N]
  double steady_wrench = 0.0;       ///< mean ‖[f; τ]‖
  double steady_lateral = 0.0;      ///< mean tip distance to the bore axis [m]
  double steady_tilt = 0.0;         ///< mean angle of the peg axis to the bore axis [rad]
  double max_lateral = 0.0;         ///< the largest of those [m] …
  double max_tilt = 0.0;            ///< … [rad]
  double min_depth = 0.0;           ///< least tip depth below the top face [m]
  double max_speed = 0.0;           ///< [m/s]
  double max_angular_speed = 0.0;   ///< [rad/s]
  double contact_fraction = 0.0;    ///< of the window's samples in peg–socket contact
  // ---- the verdict
  bool seated = false;
  /// Why not (empty when seated): "depth", "lateral", "tilt", "not_settled", "contact",
  /// "force", "axial_moment", "saturation", "joint_limit", "other_contact", "non_finite",
  /// "too_short", plus the run's own ("diverged", "bad_command", "interrupted") added by the run.
  std::vector<std::string> failures;
};

constexpr auto declared_fields(const DockingMetrics*) {
  using S = DockingMetrics;
  return declare<S>(
      "docking metrics", field("seated", &S::seated, "the verdict"),
      field("failures", &S::failures, "why not seated: names, empty when seated"),
      field("peak_force", &S::peak_force, "N", "max ‖f‖ of the peg's contact force"),
      field("peak_axial_force", &S::peak_axial_force, "N", "max f·z_S (the peg pushing in)"),
      field("peak_wrench", &S::peak_wrench, "", "max ‖[f; τ]‖, τ about the tip (N, N·m mixed)"),
      field("peak_axial_moment", &S::peak_axial_moment, "N·m", "max |τ·z_S|"),
      field("steady_axial_force", &S::steady_axial_force, "N", "final window: mean f·z_S"),
      field("steady_wrench", &S::steady_wrench, "", "final window: mean ‖[f; τ]‖"),
      field("steady_lateral", &S::steady_lateral, "m", "final window: mean tip to bore axis"),
      field("steady_tilt", &S::steady_tilt, "rad", "final window: mean peg axis to bore axis"),
      field("max_lateral", &S::max_lateral, "m", "final window: largest tip to bore axis"),
      field("max_tilt", &S::max_tilt, "rad", "final window: largest peg axis to bore axis"),
      field("min_depth", &S::min_depth, "m", "final window: least tip depth below the top face"),
      field("max_speed", &S::max_speed, "m/s", "final window: largest tip speed"),
      field("max_angular_speed", &S::max_angular_speed, "rad/s",
            "final window: largest peg angular speed"),
      field("contact_fraction", &S::contact_fraction, "",
            "final window: fraction of samples in peg–socket contact"),
      field("max_joint_position_percent", &S::max_joint_position, "%",
            "max |q − mid| / half range, of the limit"),
      field("max_joint_velocity_percent", &S::max_joint_velocity, "%", "max |q̇| / v_max"),
      field("min_manipulability", &S::min_manipulability, "", "min √det(J·Jᵀ)"),
      field("position_rms", &S::position_rms, "m", "free motion: RMS of ‖p_E − p_D‖"),
      field("orientation_rms", &S::orientation_rms, "rad", "free motion: RMS rotation error"),
      field("free_samples", &S::free_samples, "", "samples before the first contact"),
      field("saturation", &S::saturation, "", "fraction of ticks with a clipped motor"),
      field("first_contact_time", &S::first_contact_time, "s",
            "first peg–socket contact; NaN (null) when never"),
      field("samples", &S::samples, "", "samples judged"),
      field("joint_limits_ok", &S::joint_limits_ok, "every sample within the joint limits"),
      field("other_contact", &S::other_contact, "a contact other than peg–socket"),
      field("finite", &S::finite, "every sample finite"));
}

/// The metrics of @p samples (in time order) against @p goal and @p criteria. A run shorter than
/// the window fails with "too_short"; an empty one gives zero metrics and that failure.
/// @throws Error for bad criteria (see `check`).
DockingMetrics evaluate_docking(std::span<const DockingSample> samples, const DockingGoal& goal,
                                const DockingCriteria& criteria = {});

/// Reads `DockingSample`s out of a docking scene's `mjData`. Allocates nothing per sample.
class DockingProbe {
 public:
  /// @param max_velocity joint speed limits (7) [rad/s]
  /// @throws Error when @p max_velocity has the wrong size or an entry not > 0.
  DockingProbe(const DockingScene& scene, const Eigen::VectorXd& max_velocity);

  /// The sample of @p d, whose contacts, constraint forces and kinematics belong to the same
  /// state (after `mj_step2`, `mj_forward` or a `Simulation` tick: the state at the start of the
  /// last step), with @p t the time to store, @p X_WD the reference and @p saturated the
  /// simulation's saturation flag of that tick.
  void sample(const mjModel& m, const mjData& d, double t, const Pose& X_WD, bool saturated,
              DockingSample& out) noexcept;

 private:
  Chain chain_;
  GeomSet peg_, socket_;
  int tip_ = -1;
  Eigen::VectorXd max_velocity_, q_, qd_;
  Manipulability manipulability_;
};

}  // namespace mjarm
