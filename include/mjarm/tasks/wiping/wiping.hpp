#pragma once
/// @file
/// Wiping a straight stroke on a table at a constant normal force: the laws by name, the
/// criteria, and `run_wiping`, one closed-loop run judged on the force's RMS error and the path's
/// cross-track error (docs/scenarios.md, the worked example of a new scenario).

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/run_video.hpp"
#include "mjarm/tasks/wiping/scene.hpp"
#include "mjarm/tasks/wiping/task.hpp"

namespace mjarm {

/// The force controllers that can wipe; both feed the reference's force F_ext forward.
enum class WipingLaw {
  osc,  ///< `OperationalSpaceController`, inertia shaped to `desired_inertia`, no measurement
  cic   ///< `CartesianImpedanceController`: the arm's own Λ, the F/T sensor, friction feed-forward
};

constexpr auto declared_names(const WipingLaw*) {
  using E = WipingLaw;
  return std::array{EnumName{E::osc, "osc", "operational-space impedance, inertia shaped"},
                    EnumName{E::cic, "cic", "Cartesian impedance, natural inertia, F/T sensor"}};
}

/// The law and its gains. Stiffness acts in world axes: x and y along the table (the path),
/// z normal to it (low: the fed-forward force presses, not the spring), rotations.
struct WipingControl {
  WipingLaw law = WipingLaw::cic;
  double lateral_stiffness = 2000.0;                ///< x, y [N/m]
  double normal_stiffness = 200.0;                  ///< z [N/m]
  double rotational_stiffness = 150.0;              ///< [N·m/rad]
  double damping_ratio = 1.0;                       ///< ζ of the critical damping
  std::array<double, 2> desired_inertia{3.0, 0.1};  ///< osc: M_d, translation and rotation
  double nullspace_stiffness = 10.0;                ///< posture toward the start [N·m/rad]
};

constexpr auto declared_fields(const WipingControl*) {
  using S = WipingControl;
  return declare<S>("wiping control", field("law", &S::law, "the force controller"),
                    field("lateral_stiffness", &S::lateral_stiffness, "N/m",
                          Range::closed(10.0, 20000.0), "stiffness along the table, x y"),
                    field("normal_stiffness", &S::normal_stiffness, "N/m",
                          Range::closed(1.0, 20000.0), "stiffness normal to the table, z"),
                    field("rotational_stiffness", &S::rotational_stiffness, "N·m/rad",
                          Range::closed(1.0, 2000.0), "stiffness of the tool's orientation"),
                    field("damping_ratio", &S::damping_ratio, "", Range::closed(0.1, 5.0),
                          "ζ of the critical damping"),
                    field("desired_inertia", &S::desired_inertia, "kg; kg·m²",
                          Range::closed(0.01, 100.0), "osc: M_d, translation and rotation"),
                    field("nullspace_stiffness", &S::nullspace_stiffness, "N·m/rad",
                          Range::closed(0.0, 200.0), "posture toward the start"));
}

/// When a stroke counts as wiped; every figure over the stroke (the reference moving).
struct WipingCriteria {
  double force_tolerance = 1.0;        ///< RMS of F_n − F_d [N]
  double path_tolerance = 0.002;       ///< largest cross-track distance of the tip [m]
  double min_contact_fraction = 0.99;  ///< of the stroke's ticks with the pad on the table
};

constexpr auto declared_fields(const WipingCriteria*) {
  using S = WipingCriteria;
  return declare<S>(
      "wiping criteria",
      field("force_tolerance", &S::force_tolerance, "N", Range::positive(),
            "RMS of the normal force's error"),
      field("path_tolerance", &S::path_tolerance, "m", Range::positive(),
            "largest cross-track distance of the tip"),
      field("min_contact_fraction", &S::min_contact_fraction, "", Range::closed(0.0, 1.0),
            "of the stroke's ticks with the pad on the table"));
}

/// The verdict of a run.
enum class WipingOutcome {
  wiped,         ///< every criterion held
  lost_contact,  ///< the pad left the table for too long
  force_off,     ///< the normal force's RMS error exceeded its tolerance
  off_path,      ///< the tip left the line by more than the tolerance
  collided,      ///< the arm (not the tool) touched the table
  diverged,      ///< the simulation diverged
  bad_command,   ///< the controller wrote NaN/inf
  interrupted    ///< SIGINT/SIGTERM
};

constexpr auto declared_names(const WipingOutcome*) {
  using E = WipingOutcome;
  return std::array{EnumName{E::wiped, "wiped"},
                    EnumName{E::lost_contact, "lost_contact"},
                    EnumName{E::force_off, "force_off"},
                    EnumName{E::off_path, "off_path"},
                    EnumName{E::collided, "collided"},
                    EnumName{E::diverged, "diverged"},
                    EnumName{E::bad_command, "bad_command"},
                    EnumName{E::interrupted, "interrupted"}};
}

/// What the stroke measured: F_n the normal force of the pad on the table (MuJoCo's contact
/// forces, not the sensor), the tip's cross-track distance to the line.
struct WipingMetrics {
  int samples = 0;                ///< ticks of the stroke
  double force_rms_error = 0.0;   ///< RMS of F_n − F_d [N]
  double force_max_error = 0.0;   ///< max |F_n − F_d| [N]
  double mean_force = 0.0;        ///< mean F_n [N]
  double path_rms_error = 0.0;    ///< RMS cross-track distance [m]
  double path_max_error = 0.0;    ///< max cross-track distance [m]
  double contact_fraction = 0.0;  ///< of the stroke's ticks in pad–table contact
  double peak_force = 0.0;        ///< max F_n over the whole run [N]
  double saturation = 0.0;        ///< fraction of the run's ticks with a clipped motor
  bool arm_contact = false;       ///< the arm (not the tool) touched the table
};

/// How to run one wipe.
struct WipingOptions {
  WipingSurface surface;
  WipingPath path;
  WipingMotion motion;
  WipingForceLoop force_loop;
  WipingControl control;
  WipingCriteria criteria;
  std::uint64_t seed = 1;         ///< draws the believed table height and the sensor's noise
  double max_acceleration = 1e6;  ///< divergence bound on |q̈| [rad/s²]
  /// A scene built for `surface` to share between runs (null: built for this run).
  std::shared_ptr<const WipingScene> scene;
  std::filesystem::path record;  ///< recording folder; empty: none
  std::filesystem::path video;   ///< MP4; empty: none
  /// "" (default): a free camera beside the table; "follow": one following the tool's tip.
  std::string camera;
  RunVideoOptions video_options;
};

/// What a wiping run did.
struct WipingReport {
  WipingPlan plan;
  RunResult run{};
  WipingMetrics metrics{};
  WipingOutcome outcome = WipingOutcome::wiped;
  std::filesystem::path recording{};
  std::string recording_error{};
  std::filesystem::path video{};
  std::string video_error{};
  bool video_written = false;
  bool ok() const noexcept { return outcome == WipingOutcome::wiped; }
};

/// One wipe: the scene (or the shared one), the plan, the law, the run to the end of the hold,
/// the metrics over the stroke and the verdict (the first criterion that fails, in the order of
/// `WipingOutcome`).
/// @throws Error for a value out of range, a shared scene of another surface, a stroke off the
///         table or out of reach, or an output that cannot be written
WipingReport run_wiping(const WipingOptions& options);

/// "wiped: force_rms_error=0.21 N path_max_error=0.4 mm contact=100%": the report in one line.
std::string wiping_result_line(const WipingReport& report);

}  // namespace mjarm
