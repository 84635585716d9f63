#pragma once
/// @file
/// `PickPlaceTask`: the 14-state pick-and-place machine of the classic teaching code as a
/// `ReferenceSource` — Cartesian segments on trapezoidal profiles, smoothstep finger motion, the
/// weld switched on and off at the right instants, and the figures a trial is judged by.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "mjarm/control/reference.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/sim/grasp_monitor.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/tick_observer.hpp"
#include "mjarm/trajectory/cartesian_trapezoid.hpp"

namespace mjarm {

class Recorder;
class Simulation;
class WeldGrasp;

/// The states, in order. Each change is a "phase" event of the recorder.
enum class PickPlaceState {
  approach,  ///< tool to approach_height above the object, grasp orientation
  dwell_a,
  descend,  ///< down to descend_height above the object's centre
  dwell_b,
  grasp,  ///< fingers close along a smoothstep over grip_time; then the weld (weld grasp)
  dwell_c,
  lift,  ///< straight up to lift_height above the object's start
  dwell_d,
  move,  ///< across to move_height above the target
  dwell_e,
  place,  ///< down to place_height above the target
  dwell_f,
  release,  ///< weld off, fingers open along a smoothstep over release_time
  done      ///< hold still for settle_time; then the trial is judged
};

/// The names (`to_string`, JSON and CLI spelling; Python binds them in lower case).
constexpr auto declared_names(const PickPlaceState*) {
  using E = PickPlaceState;
  return std::array{EnumName{E::approach, "APPROACH"}, EnumName{E::dwell_a, "DWELL_A"},
                    EnumName{E::descend, "DESCEND"},   EnumName{E::dwell_b, "DWELL_B"},
                    EnumName{E::grasp, "GRASP"},       EnumName{E::dwell_c, "DWELL_C"},
                    EnumName{E::lift, "LIFT"},         EnumName{E::dwell_d, "DWELL_D"},
                    EnumName{E::move, "MOVE"},         EnumName{E::dwell_e, "DWELL_E"},
                    EnumName{E::place, "PLACE"},       EnumName{E::dwell_f, "DWELL_F"},
                    EnumName{E::release, "RELEASE"},   EnumName{E::done, "DONE"}};
}

/// How the object is held.
enum class GraspKind {
  weld,     ///< fingers close, then a weld holds the object (switched on where it is)
  friction  ///< only the finger contact forces hold it
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const GraspKind*) {
  using E = GraspKind;
  return std::array{EnumName{E::weld, "weld"}, EnumName{E::friction, "friction"}};
}

/// The kind called @p name. @throws Error "unknown grasp 'x'; choices: weld, friction".
GraspKind grasp_kind(std::string_view name);

/// Every constant of the machine, the classic defaults. Heights are those of the tool frame
/// above the object's centre (at the start, for APPROACH/DESCEND/LIFT) or above the target
/// (where the object's centre rests, for MOVE/PLACE) [m].
struct PickPlaceMotion {
  double approach_height = 0.055;
  double descend_height = 0.010;
  double lift_height = 0.12;
  double move_height = 0.12;
  double place_height = 0.055;
  double dwell_time = 0.5;    ///< each DWELL_* [s] (≥ 0)
  double grip_time = 0.6;     ///< GRASP: fingers close along a smoothstep [s] (> 0)
  double release_time = 0.6;  ///< RELEASE: fingers open along a smoothstep [s] (> 0)
  /// Limits of the Cartesian segments (trapezoids, `CartesianTrapezoid`): v_max = 0.07 m/s and
  /// a_max = 0.9 m/s² along the line; the tool's turn (APPROACH) under 0.5 rad/s, 3 rad/s².
  CartesianLimits limits;
  double settle_time = 1.0;  ///< DONE lasts this long before the result is judged [s] (> 0)
};

/// approach_height ≥ descend_height is checked by hand.
constexpr auto declared_fields(const PickPlaceMotion*) {
  using S = PickPlaceMotion;
  return declare<S>(
      "pick and place",
      field("approach_height", &S::approach_height, "m", Range::positive(),
            "APPROACH: the tool above the object's centre"),
      field("descend_height", &S::descend_height, "m", Range::non_negative(),
            "DESCEND: the tool above the object's centre"),
      field("lift_height", &S::lift_height, "m", Range::positive(),
            "LIFT: the tool above the object's start"),
      field("move_height", &S::move_height, "m", Range::positive(),
            "MOVE: the tool above the target"),
      field("place_height", &S::place_height, "m", Range::non_negative(),
            "PLACE: the tool above the target"),
      field("dwell_time", &S::dwell_time, "s", Range::non_negative(), "each DWELL_*"),
      field("grip_time", &S::grip_time, "s", Range::positive(), "GRASP: the fingers close"),
      field("release_time", &S::release_time, "s", Range::positive(), "RELEASE: the fingers open"),
      field("limits", &S::limits, "speed limits of the Cartesian segments"),
      field("settle_time", &S::settle_time, "s", Range::positive(),
            "DONE lasts this long before the result is judged"));
}

/// @throws Error naming the first constant out of range.
void check(const PickPlaceMotion& motion);

/// Where the machine goes.
struct PickPlaceGoal {
  Pose X_WS;               ///< tool pose at the start (world)
  Eigen::Vector3d object;  ///< object centre at the start (world) [m]
  Eigen::Vector3d target;  ///< where the object's centre should come to rest (world) [m]
  Eigen::Matrix3d R_grasp = Eigen::Matrix3d::Identity();  ///< tool orientation from APPROACH on
  Eigen::VectorXd posture;  ///< reference.joint.q (null-space posture), chain order; may be empty
  GraspKind grasp = GraspKind::weld;
  /// Velocity references are taken at t − velocity_lag (h/2 for semi-implicit Euler, see
  /// `ShelfPickGoal::velocity_lag`) [s] (≥ 0).
  double velocity_lag = 0.0;
};

/// The window after the weld is switched on over which its jump is measured [s]: 2.5 time
/// constants of the stiffest weld MuJoCo allows at a 2 ms step (it clamps the time constant to
/// two steps), so a weld written from a stale pose has done most of its yank by then.
inline constexpr double kWeldJumpWindow = 0.01;

/// What the machine saw while it ran (NaN: did not happen).
struct PickPlaceTrace {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  PickPlaceState state = PickPlaceState::approach;  ///< the state at the last update
  double start_time = kNaN;                         ///< simulated time of the first update [s]
  double done_time = kNaN;  ///< time DONE was entered, relative to the start: the cycle time [s]
  bool closed = false;      ///< both fingers touched the object when GRASP ended
  double closing_force = kNaN;  ///< grasp force then [N]
  bool welded = false;          ///< the weld was switched on
  /// The weld jump [m]: how far switching the weld on moved the object — the largest distance,
  /// over the first `kWeldJumpWindow`, between the object and where its velocity at the switch
  /// would have carried it (the arm and fingers are still settling at a fraction of a mm/s when
  /// GRASP ends; that drift is not the switch's doing). A weld written from a stale pose yanks
  /// the object by millimetres within that window.
  double weld_jump = kNaN;
  /// Largest deviation of the object from the pose the weld holds it at (relative to the
  /// gripper, `WeldGrasp::deviation`) over DWELL_C: how far the soft weld stretches under the
  /// finger forces and the arm's own settling [m].
  double weld_settle = kNaN;
  bool slipped = false;        ///< the object moved > slip_distance relative to the gripper
  bool dropped = false;        ///< ... > drop_distance: lost between GRASP and RELEASE
  double dropped_time = kNaN;  ///< relative to the start [s]
  double max_slip = 0.0;       ///< largest slip between GRASP and RELEASE [m]
  /// Mean and largest grasp force from LIFT to the end of DWELL_F (the transport) [N].
  double transport_force_mean = kNaN;
  double transport_force_max = kNaN;
  bool table_contact = false;        ///< a robot geom touched the table
  double table_contact_time = kNaN;  ///< first time, relative to the start [s]
  /// Longest run of consecutive control ticks with one actuator's command clipped, and the
  /// actuator.
  std::int64_t longest_saturation = 0;
  int saturated_actuator = -1;
};

constexpr auto declared_fields(const PickPlaceTrace*) {
  using S = PickPlaceTrace;
  return declare<S>(
      "pick and place trace", field("state", &S::state, "the state at the end"),
      field("start_time", &S::start_time, "s", "simulated time of the first update"),
      field("done_time", &S::done_time, "s", "DONE entered, from the start: the cycle time"),
      field("closed", &S::closed, "both fingers touched the object when GRASP ended"),
      field("closing_force", &S::closing_force, "N", "grasp force then"),
      field("welded", &S::welded, "the weld was switched on"),
      field("weld_jump", &S::weld_jump, "m", "how far switching the weld on moved the object"),
      field("weld_settle", &S::weld_settle, "m", "how far the weld stretched over DWELL_C"),
      field("slipped", &S::slipped, "the object moved more than slip_distance in the gripper"),
      field("dropped", &S::dropped, "… more than drop_distance: lost between GRASP and RELEASE"),
      field("dropped_time", &S::dropped_time, "s", "from the start"),
      field("max_slip", &S::max_slip, "m", "largest slip between GRASP and RELEASE"),
      field("transport_force_mean", &S::transport_force_mean, "N",
            "mean grasp force from LIFT to the end of DWELL_F"),
      field("transport_force_max", &S::transport_force_max, "N", "largest of it"),
      field("table_contact", &S::table_contact, "a robot geom touched the table"),
      field("table_contact_time", &S::table_contact_time, "s", "first time, from the start"),
      field("longest_saturation", &S::longest_saturation, "ticks",
            "longest run of ticks with one actuator's command clipped"),
      field("saturated_actuator", &S::saturated_actuator, "", "that actuator; -1: none"));
}

/// The pick and place as a reference source: the state schedule is fixed at construction (every
/// segment is a `CartesianTrapezoid` between the goal's poses, every dwell and finger ramp a
/// fixed time), so `update` only samples it, switches the grasp at the state changes and keeps
/// the `PickPlaceTrace`. Allocation-free, never throws; the run ends (update returns false)
/// settle_time after DONE was entered.
///
/// Reference: task pose, twist and rate of the current segment (zero twist while dwelling);
/// gripper fraction 0 (open) until GRASP, smoothstep to 1 over grip_time, 1 until RELEASE,
/// smoothstep back to 0 over release_time; joint posture = goal.posture.
class PickPlaceTask final : public ReferenceSource {
 public:
  /// @param simulation the simulation the task runs in (read: contacts, saturation)
  /// @param arm the arm chain; its frame is the tool
  /// @param monitor the grasp monitor of this simulation (closed at the end of GRASP, opened at
  ///        RELEASE)
  /// @param weld the weld grasp (weld kind only; null for friction)
  /// @param table_watch a `Simulation::watch_contacts` handle of robot vs table
  /// @param recorder where phase and grasp events go (may be null)
  /// @throws Error for bad motion constants, a goal that is not finite, a weld kind without a
  ///         weld, or a posture of the wrong size.
  PickPlaceTask(Simulation& simulation, const Chain& arm, const PickPlaceGoal& goal,
                const PickPlaceMotion& motion, GraspMonitor& monitor, WeldGrasp* weld,
                int table_watch, Recorder* recorder = nullptr);

  bool update(const mjData& data, Reference& reference) noexcept override;

  PickPlaceState state() const noexcept { return trace_.state; }
  const PickPlaceTrace& trace() const noexcept { return trace_; }
  const PickPlaceGoal& goal() const noexcept { return goal_; }
  /// Start time of each state relative to the task's start [s], and when DONE ends (15 values).
  const std::array<double, 15>& schedule() const noexcept { return schedule_; }
  /// The five segments: APPROACH, DESCEND, LIFT, MOVE, PLACE.
  const std::array<CartesianTrapezoid, 5>& segments() const noexcept { return segments_; }
  /// The tool poses the segments go through: above the object, grasp, lifted, above the
  /// target, release (world).
  void set_observer(TickObserver* observer) noexcept { observer_ = observer; }

 private:
  void enter(PickPlaceState state, double t) noexcept;
  void grasp_event(double t, const char* what) noexcept;

  Simulation* simulation_;
  Chain arm_;
  PickPlaceGoal goal_;
  PickPlaceMotion motion_;
  GraspMonitor* monitor_;
  WeldGrasp* weld_;
  int table_watch_;
  Recorder* recorder_;
  TickObserver* observer_ = nullptr;
  std::array<CartesianTrapezoid, 5> segments_;
  std::array<double, 15> schedule_{};
  PickPlaceTrace trace_;
  bool started_ = false;
  double force_sum_ = 0.0;
  std::int64_t force_samples_ = 0;
  std::vector<std::int64_t> saturation_run_;          // per actuator: consecutive saturated ticks
  Eigen::Vector3d p_weld_ = Eigen::Vector3d::Zero();  // object position when welded (world)
  Eigen::Vector3d v_weld_ = Eigen::Vector3d::Zero();  // ... and its velocity
  std::array<char, 200> message_{};
};

}  // namespace mjarm
