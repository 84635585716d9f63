#pragma once
/// @file
/// The docking motion: where the robot believes the socket is (`DockingOffset`), the plan
/// (start, standoff, seated poses; `plan_docking`) and `DockingTask`, the reference source of
/// approach, slow insertion and hold with the preload. docs/docking.md.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <numbers>
#include <optional>
#include <string_view>

#include "mjarm/control/reference.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/docking/centring.hpp"
#include "mjarm/tasks/docking/scene.hpp"
#include "mjarm/tasks/docking/search.hpp"
#include "mjarm/tasks/tick_observer.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {

class Recorder;

/// The error of the socket pose the robot believes in, in the socket's frame: the reference aims
/// at X_WS·(R_z(dyaw), (dx, dy, 0)) instead of the true X_WS. The peg then meets the chamfer off
/// its axis, and only compliance seats it.
struct DockingOffset {
  double dx = 0.0;    ///< [m], |dx| ≤ 0.05
  double dy = 0.0;    ///< [m], |dy| ≤ 0.05
  double dyaw = 0.0;  ///< about the socket's axis [rad], |dyaw| ≤ π
};

constexpr auto declared_fields(const DockingOffset*) {
  using S = DockingOffset;
  return declare<S>(
      "docking offset",
      field("dx", &S::dx, "m", Range::closed(-0.05, 0.05), "along the socket's x"),
      field("dy", &S::dy, "m", Range::closed(-0.05, 0.05), "along the socket's y"),
      field("dyaw", &S::dyaw, "rad", Range::closed(-std::numbers::pi, std::numbers::pi),
            "about the socket's axis"));
}

/// @throws Error naming the value when an offset is not finite or out of its range.
void check(const DockingOffset& offset);

/// The shape of the reference.
enum class DockingReference {
  /// Fast to a standoff above the believed socket (SE(3) interpolation, rest to rest), then a
  /// slow straight insertion down the believed axis (trapezoid in speed) to the bottom.
  two_phase,
  /// One SE(3) interpolation from the start to the believed seated pose (rest to rest).
  single_segment
};

/// The names (`to_string`, JSON and CLI spelling; Python binds `two_phase`, `single_segment`).
constexpr auto declared_names(const DockingReference*) {
  using E = DockingReference;
  return std::array{EnumName{E::two_phase, "two-phase"}, EnumName{E::single_segment, "single"}};
}

/// The reference called @p name ("two-phase", "single").
/// @throws Error naming the closest and listing the choices.
DockingReference docking_reference(std::string_view name);

/// Timing and sizes of the motion. Lengths in metres, times in seconds.
struct DockingMotion {
  DockingReference reference = DockingReference::two_phase;
  double start_height = 0.06;     ///< the tip above the true socket's top face at the start (> 0)
  double standoff = 0.005;        ///< two-phase: the tip above the top face where insertion starts
  double approach_time = 1.0;     ///< two-phase: start → standoff (> 0)
  double insertion_speed = 0.01;  ///< two-phase: cruise speed of the insertion (> 0)
  double insertion_acceleration = 0.05;  ///< two-phase: its acceleration (> 0)
  double single_time = 3.0;              ///< single-segment: start → seated (> 0)
  double preload = 5.0;       ///< force pushed along the insertion axis in the hold [N] (≥ 0)
  double preload_ramp = 0.3;  ///< linear ramp of the preload from the start of the hold (> 0)
  double hold_time = 2.0;     ///< from the reference's arrival at the bottom to the end (> 0)
  /// two-phase: miss detection and the search for the hole (pattern none: off)
  DockingSearchOptions search;
  /// two-phase, laws with a lateral release, no joint friction: centring in the bore by a probe
  DockingCentringOptions centring;
};

/// The standoff is checked against the start height by hand.
constexpr auto declared_fields(const DockingMotion*) {
  using S = DockingMotion;
  return declare<S>(
      "docking motion", field("reference", &S::reference, "the shape of the reference"),
      field("start_height", &S::start_height, "m", Range::positive(),
            "the tip above the true socket's top face at the start"),
      field("standoff", &S::standoff, "m", Range::non_negative(),
            "two-phase: the tip above the top face where insertion starts (< start_height)"),
      field("approach_time", &S::approach_time, "s", Range::positive(),
            "two-phase: start → standoff"),
      field("insertion_speed", &S::insertion_speed, "m/s", Range::positive(),
            "two-phase: cruise speed of the insertion"),
      field("insertion_acceleration", &S::insertion_acceleration, "m/s²", Range::positive(),
            "two-phase: acceleration of the insertion"),
      field("single_time", &S::single_time, "s", Range::positive(),
            "single-segment: start → seated"),
      field("preload", &S::preload, "N", Range::non_negative(),
            "force pushed along the insertion axis in the hold"),
      field("preload_ramp", &S::preload_ramp, "s", Range::positive(),
            "linear ramp of the preload from the start of the hold"),
      field("hold_time", &S::hold_time, "s", Range::positive(),
            "from the reference's arrival at the bottom to the end"),
      field("search", &S::search, "two-phase: miss detection and the search for the hole"),
      field("centring", &S::centring,
            "two-phase: centring in the bore from the contact excursion (se3, hqp-ac)"));
}

/// @throws Error naming the value when a size or time is out of range (the search's radius is
///         checked against the socket by `plan_docking`).
void check(const DockingMotion& motion);

/// Phases, in order; each change is written to the recorder as a "phase" event.
enum class DockingPhase {
  approach,  ///< two-phase: to the standoff; single-segment: the whole move
  insert,    ///< two-phase: the slow insertion (again from the drop after a search)
  search,    ///< two-phase, after a miss: the planar search at a held contact force
  hold       ///< the reference rests on the believed seated pose; the preload ramps in
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const DockingPhase*) {
  using E = DockingPhase;
  return std::array{EnumName{E::approach, "approach"}, EnumName{E::insert, "insert"},
                    EnumName{E::search, "search"}, EnumName{E::hold, "hold"}};
}

/// Everything fixed before the run.
struct DockingPlan {
  DockingOffset offset;
  Pose X_WS;                   ///< the true socket
  Pose X_WB;                   ///< the socket the robot believes in: X_WS·(R_z(dyaw), (dx, dy, 0))
  Pose X_start;                ///< E at the start: above the true socket by start_height, peg down
  Pose X_standoff;             ///< E above the believed socket by the standoff
  Pose X_seated;               ///< E seated in the believed socket (the reference's end)
  Eigen::VectorXd q_start;     ///< the arm at X_start (IK from the home keyframe) [rad]
  double full_depth = 0.0;     ///< chamfer + bore depth [m]
  double clearance = 0.0;      ///< radial clearance at a bore face, bore − peg radius [m]
  double approach_time = 0.0;  ///< [s]
  double insert_time = 0.0;    ///< [s] (0 for single-segment)
  double hold_time = 0.0;      ///< [s]
  double duration() const noexcept { return approach_time + insert_time + hold_time; }
};

/// The phase durations of a run with @p motion in a socket of @p geometry: approach, insert
/// (0 for single-segment), hold [s] (as `plan_docking` sets them).
/// @throws Error for a bad motion.
std::array<double, 3> docking_phase_times(const DockingMotion& motion,
                                          const DockingGeometry& geometry);

/// The arm at @p X_WE (E: the peg tip): pose IK from the `home` keyframe with a pull towards it
/// (the start of a docking run and of the tracking gate).
/// @throws Error naming the pose when IK does not converge.
Eigen::VectorXd docking_start_configuration(const DockingScene& scene, const Pose& X_WE);

/// The plan of a docking run: poses, the start configuration by IK (pose IK from the home
/// keyframe with a pull towards it), segment durations (without a search: the planned run).
/// @throws Error for a bad offset or motion (the search's options included, against the
///         socket's size), or when IK cannot reach the start.
DockingPlan plan_docking(const DockingScene& scene, const DockingOffset& offset,
                         const DockingMotion& motion);

/// The docking reference, one control tick at a time. From t₀ (data.time at the first update):
/// approach and insert as `DockingReference` says, then hold on X_seated with the preload
/// reference.task.F_ext = P·min(1, (t − t_hold)/ramp)·u (u = −z_B, the believed insertion
/// direction: the force E should exert on the socket). reference.joint.q is q_start (the
/// null-space posture), velocities at t − velocity_lag (see `ShelfPickGoal::velocity_lag`).
/// `update` returns false at t₀ + duration; it allocates nothing and never throws.
/// With a `ContactChannel` attached (`attach`) and a search pattern, the insertion watches for
/// a miss (`DockingSearchOptions`): it then searches in the believed socket's plane around the
/// tip's position at the miss, the lateral release disarmed and F_ext = contact force along u,
/// until the drop, when a new insertion goes straight down from the tip to the seated depth and
/// the hold follows; a search past its radius or timeout ends the run (`search_exhausted`).
/// With a channel whose law releases (`ContactChannel::releases`) and centring enabled, each
/// insertion centres the peg in the bore (`BoreCentring`): the release disarmed from the
/// centring's start to the hold, the reference shifted laterally to the believed-from-contact
/// axis.
class DockingTask final : public ReferenceSource {
 public:
  /// @param recorder where phase events go (may be null; must outlive the task)
  DockingTask(const DockingPlan& plan, const DockingMotion& motion, double velocity_lag = 0.0,
              Recorder* recorder = nullptr);

  bool update(const mjData& data, Reference& reference) noexcept override;

  DockingPhase phase() const noexcept { return phase_; }
  /// The pose reference of the last update.
  const Pose& reference_pose() const noexcept { return X_WD_; }
  /// Simulated time of the first update (NaN before).
  double start_time() const noexcept { return t0_; }
  /// Calls @p observer at every update (a video); may be null.
  void set_observer(TickObserver* observer) noexcept { observer_ = observer; }
  /// Enables miss detection and search (two-phase, pattern not none) and the centring
  /// (two-phase, enabled, a law that releases): the measured wrench and the release switch from
  /// @p channel (must outlive the task), the tip from the site @p tip_site of the model the task
  /// runs on.
  void attach(ContactChannel& channel, int tip_site) noexcept;

  /// Misses detected (searches started).
  int searches() const noexcept { return searches_; }
  /// True when a search ended past its radius or timeout (the run then ended).
  bool search_exhausted() const noexcept { return exhausted_; }
  /// Time spent searching, over all searches [s].
  double search_time() const noexcept { return search_total_; }
  /// Time of the first miss and of the last drop since the start [s] (NaN: none).
  double miss_time() const noexcept { return miss_time_; }
  double drop_time() const noexcept { return drop_time_; }
  /// The lateral excursion that started the last insertion's centring [m] (zero: none).
  const Eigen::Vector3d& centring_excursion() const noexcept { return centring_.excursion(); }
  /// When the hold begins (or began) since the start [s]: later than planned after a search.
  double hold_start() const noexcept { return hold_start_; }
  /// The longest a run can take: the plan plus the search's timeout and a new insertion [s].
  double max_duration() const noexcept;

 private:
  /// Pose, twist and acceleration of the reference at @p t since the start (approach,
  /// insertion, hold).
  Se3Interpolation::Sample at(double t) const noexcept;
  void enter(DockingPhase phase, double t) noexcept;
  /// The tip's position (world) from the model's kinematics of @p data.
  Eigen::Vector3d tip(const mjData& data) const noexcept;
  /// Insert phase: true once the miss has held for its dwell.
  bool missed(const mjData& data, double t) noexcept;
  enum class SearchStep { searching, dropped, exhausted };
  /// The search's reference at @p t, or the drop (a new insertion begun) or its end.
  SearchStep search(const mjData& data, double t, Reference& reference) noexcept;
  /// Centring (`BoreCentring`): decides at its depth, disarms and re-arms the release, and
  /// shifts the insertion's or the hold's reference @p now and its lagged velocity.
  void centre(const mjData& data, double t, double t_hold, Se3Interpolation::Sample& now,
              Se3Interpolation::Sample& lagged) noexcept;
  /// A new insertion from the tip straight down to the seated depth, starting at @p t.
  void restart_insertion(const mjData& data, double t) noexcept;

  DockingPlan plan_;
  DockingMotion motion_;
  double velocity_lag_;
  Recorder* recorder_;
  TickObserver* observer_ = nullptr;
  Se3Interpolation approach_;
  std::optional<TrapezoidProfile> insertion_;
  Eigen::Vector3d direction_;  // u = −z_B, world
  DockingPhase phase_ = DockingPhase::approach;
  bool started_ = false;
  double t0_;
  Pose X_WD_;
  // the current insertion (the planned one, or from a drop) and the hold after it
  Pose insert_from_;
  double insert_start_;  // since t₀ [s]
  double hold_start_;
  Pose X_hold_;
  // miss detection and search
  ContactChannel* channel_ = nullptr;
  int tip_site_ = -1;
  bool search_on_ = false;
  bool centring_on_ = false;
  bool rearm_at_hold_ = false;  // the centring disarmed the release
  BoreCentring centring_;
  std::optional<SearchPath> path_;
  double miss_since_;  // NaN: no miss pending
  double search_start_ = 0.0;
  double search_total_ = 0.0;
  double trim_ = 0.0;
  double last_t_ = 0.0;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  int searches_ = 0;
  bool exhausted_ = false;
  double miss_time_;
  double drop_time_;
};

}  // namespace mjarm
