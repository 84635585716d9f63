#pragma once
/// @file
/// `run_pick_place`: one pick-and-place trial end to end — draw or take the object and target,
/// compose the scene, check the reach, simulate the 14-state machine under the chosen mode and
/// grasp, judge it against every success criterion, record, film. See docs/pick_place.md.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/sim/grasp_monitor.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/sim/weld_grasp.hpp"
#include "mjarm/tasks/pick_place/scene.hpp"
#include "mjarm/tasks/pick_place/task.hpp"
#include "mjarm/tasks/pick_place/video.hpp"

namespace mjarm {

/// What a trial is judged by.
struct PickPlaceCriteria {
  double placement_tolerance = 0.005;  ///< horizontal distance object ↔ target at the end [m]
  double rest_speed = 0.001;           ///< the object's speed at the end below this [m/s]
  double max_tilt = 5.0 * 3.14159265358979323846 / 180.0;  ///< object tilt at the end [rad]
  /// Longest time one actuator may stay clipped without a break [s].
  double max_saturation_time = 0.2;
  GraspMonitorOptions grasp;  ///< slip 2 mm (event), drop 15 mm (lost during transport)
};

/// `grasp` is checked by its monitor.
constexpr auto declared_fields(const PickPlaceCriteria*) {
  using S = PickPlaceCriteria;
  return declare<S>(
      "pick and place",
      field("placement_tolerance", &S::placement_tolerance, "m", Range::positive(),
            "horizontal distance object ↔ target at the end"),
      field("rest_speed", &S::rest_speed, "m/s", Range::positive(),
            "the object's speed at the end below this"),
      field("max_tilt", &S::max_tilt, "rad", Range::positive(), "object tilt at the end"),
      field("max_saturation_time", &S::max_saturation_time, "s", Range::non_negative(),
            "longest time one actuator may stay clipped without a break"));
}

/// Where a seed draws a trial from (uniform in each range).
struct PickPlaceRanges {
  std::array<double, 2> half_size{0.012, 0.02};  ///< cube half extent [m]
  std::array<double, 2> mass{0.02, 0.10};        ///< [kg]
  std::array<double, 2> friction{0.5, 1.2};      ///< sliding friction of the object
  std::array<double, 2> yaw{-0.785, 0.785};      ///< about the vertical [rad]
  double min_separation = 0.08;                  ///< object start ↔ target, horizontal [m]
};

/// Each range [low, high] is checked by the draw (`draw_pick_place_trial`): not reversed, within
/// the bounds below.
constexpr auto declared_fields(const PickPlaceRanges*) {
  using S = PickPlaceRanges;
  return declare<S>(
      "pick and place ranges",
      field("half_size", &S::half_size, "m", Range::closed(1e-3, 0.05),
            "cube half extent drawn from [low, high]"),
      field("mass", &S::mass, "kg", Range::closed(1e-4, 10.0),
            "object mass drawn from [low, high]"),
      field("friction", &S::friction, "", Range::closed(0.0, 5.0),
            "object sliding friction drawn from [low, high]"),
      field("yaw", &S::yaw, "rad", Range::closed(-3.141592653589793, 3.141592653589793),
            "object yaw drawn from [low, high]"),
      field("min_separation", &S::min_separation, "m", Range::closed(0.0, 1.0),
            "object start ↔ target, horizontal"));
}

/// One trial's draw: everything random about it.
struct PickPlaceTrial {
  std::uint64_t seed = 1;
  PickPlaceObject object;                  ///< size, mass, friction, position, yaw
  std::array<double, 2> target{0.0, 0.0};  ///< x y [m]
};

/// How to run one pick and place.
struct PickPlaceOptions {
  std::string robot = "arm6";
  GraspKind grasp = GraspKind::weld;
  SimulationMode mode = SimulationMode::position;
  std::uint64_t seed = 1;
  PickPlaceRanges ranges;
  /// Fixed instead of drawn (the rest is still drawn from the seed): object centre x y, target
  /// x y [m], cube half extent [m].
  std::optional<std::array<double, 2>> object_position;
  std::optional<std::array<double, 2>> target_position;
  std::optional<double> object_half_size;
  /// The classic scene edits: a 7.5 mm cube, finger travel [0, 0.012] m, finger servo gain 3200.
  bool classic = false;
  PickPlaceMotion motion;
  PickPlaceCriteria criteria;
  WeldGraspOptions weld;          ///< solref [0.002, 1]
  double grasp_force = 8.0;       ///< the fingers' squeeze once touching [N]
  int noslip_iterations = 10;     ///< MuJoCo's noslip solver iterations (0: off)
  double impratio = 1.0;          ///< MuJoCo's impratio (≥ 1)
  double control_period = 0.0;    ///< [s]; 0 = one physics step (2 ms)
  double max_acceleration = 1e6;  ///< divergence bound on |q̈| (`SimulationOptions`)
  std::filesystem::path record;   ///< recording directory; empty: none
  int state_decimation = 1;
  PickPlaceVideo video;  ///< MP4 of one or more cameras; empty path: none
};

/// Why a trial failed (the first that applies, in this order).
enum class PickPlaceFailure {
  none,           ///< success
  diverged,       ///< the simulation diverged (the reason says where)
  bad_command,    ///< a controller wrote NaN/inf
  interrupted,    ///< Ctrl-C
  time_limit,     ///< the machine did not finish in its own time plus a second
  not_grasped,    ///< a finger did not touch the object when GRASP ended
  dropped,        ///< the object slipped > drop distance between GRASP and RELEASE
  table_contact,  ///< a robot geom touched the table
  saturated,      ///< an actuator stayed clipped longer than allowed
  misplaced,      ///< horizontal placement error above tolerance
  tilted,         ///< the object ended tilted
  not_resting     ///< the object still moved at the end
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const PickPlaceFailure*) {
  using E = PickPlaceFailure;
  return std::array{EnumName{E::none, "none"},
                    EnumName{E::diverged, "diverged"},
                    EnumName{E::bad_command, "bad_command"},
                    EnumName{E::interrupted, "interrupted"},
                    EnumName{E::time_limit, "time_limit"},
                    EnumName{E::not_grasped, "not_grasped"},
                    EnumName{E::dropped, "dropped"},
                    EnumName{E::table_contact, "table_contact"},
                    EnumName{E::saturated, "saturated"},
                    EnumName{E::misplaced, "misplaced"},
                    EnumName{E::tilted, "tilted"},
                    EnumName{E::not_resting, "not_resting"}};
}

/// What one trial did.
struct PickPlaceReport {
  PickPlaceTrial trial;
  std::string robot;
  GraspKind grasp = GraspKind::weld;
  SimulationMode mode = SimulationMode::position;
  RunResult run{};
  PickPlaceTrace trace{};
  bool success = false;
  PickPlaceFailure failure = PickPlaceFailure::none;
  std::string reason;                             ///< one line: why it failed (empty on success)
  double placement_error = PickPlaceTrace::kNaN;  ///< horizontal, object ↔ target, at the end [m]
  double final_speed = PickPlaceTrace::kNaN;      ///< object speed at the end [m/s]
  double tilt = PickPlaceTrace::kNaN;             ///< object tilt at the end [rad]
  double cycle_time = PickPlaceTrace::kNaN;       ///< start → DONE [s]
  double control_period = 0.0;                    ///< [s]
  std::filesystem::path recording{};
  std::string recording_error{};
  std::vector<std::filesystem::path> videos{};          ///< the MP4s asked for
  std::vector<std::filesystem::path> videos_written{};  ///< those written complete
  std::int64_t video_frames = 0;
  std::string video_error{};
  bool ok() const noexcept { return success; }
};

/// The tool pointing straight down (z_T = −z_W), its heading the home tool heading @p R_home's x
/// axis in the horizontal plane, turned about the vertical by @p yaw [rad].
Eigen::Matrix3d grasp_rotation(const Eigen::Matrix3d& R_home, double yaw);

/// The grasp yaw closest to zero that puts the fingers across the faces of a box @p object (its
/// yaw reduced modulo a quarter turn for a square box, half a turn otherwise); 0 for a cylinder.
double grasp_yaw(const PickPlaceObject& object);

/// The trial a seed draws for @p robot (object and target in the robot's table region, at least
/// `min_separation` apart; size, mass, friction, yaw in their ranges), with the options' fixed
/// values in place of the drawn ones.
/// @throws Error for an unknown robot or ranges that are empty, reversed or not finite.
PickPlaceTrial draw_pick_place_trial(const PickPlaceOptions& options);

/// Runs one trial. Everything that can be checked is checked before the first step: the robot,
/// the object, the reach (every tool pose of the machine is solved by IK from the home posture;
/// an out-of-reach object or target gets a message with the arm's reach), the recording folder
/// and the video. A run that diverges is a failed trial with the reason (the recording keeps the
/// rows up to the fault), not an exception.
/// @throws Error for bad options or input, an unreachable object or target, an unwritable
///         recording folder or video.
PickPlaceReport run_pick_place(const PickPlaceOptions& options);

}  // namespace mjarm
