#pragma once
/// @file
/// `WaypointPlanner`: a Cartesian waypoint path turned into a checked, timed joint trajectory
/// (docs/planning.md): IK per waypoint, checks at every waypoint and at dense samples between
/// them, other IK branches and joint-space detours when a check fails, quintic segments with
/// non-zero velocities at interior waypoints, durations from the joint limits.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/ik/global_ik.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/result.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/planning/configuration_check.hpp"
#include "mjarm/planning/joint_limits.hpp"
#include "mjarm/planning/joint_spline.hpp"
#include "mjarm/planning/ompl_planner.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

/// How a plan ended.
enum class PlanStatus {
  ok,            ///< every waypoint and every sample passed: `PlanResult::trajectory` is set
  start_failed,  ///< the start configuration fails a check
  unreachable,   ///< no IK branch reaches the waypoint's pose within tolerance
  joint_limits,  ///< every IK solution of the waypoint is outside the joint ranges
  collision,     ///< every IK solution of the waypoint is in collision
  singular,      ///< every IK solution of the waypoint is too close to a singularity
  torque,        ///< every IK solution of the waypoint needs more than the torque limits
  blocked  ///< the waypoint passes, but no branch or detour gets there with every check passing
};

constexpr auto declared_names(const PlanStatus*) {
  using S = PlanStatus;
  return std::array{
      EnumName{S::ok, "ok", "every waypoint and every sample passed"},
      EnumName{S::start_failed, "start_failed", "the start configuration fails a check"},
      EnumName{S::unreachable, "unreachable", "no IK branch reaches the waypoint's pose"},
      EnumName{S::joint_limits, "joint_limits", "every IK solution is outside the joint ranges"},
      EnumName{S::collision, "collision", "every IK solution is in collision"},
      EnumName{S::singular, "singular", "every IK solution is too close to a singularity"},
      EnumName{S::torque, "torque", "every IK solution needs more than the torque limits"},
      EnumName{S::blocked, "blocked", "no branch or detour gets there with every check passing"}};
}

/// Every setting of `WaypointPlanner`.
struct PlanOptions {
  /// Joint limits; empty vectors are filled by `joint_limits_from_model` at the start.
  JointLimits limits;
  ModelLimitOptions model_limits;  ///< how the model's limits are derived
  CheckOptions checks;             ///< thresholds of the checks
  /// Samples between knots are at most this far apart in time [s] (> 0) …
  double sample_period = 0.01;
  /// … and so close that no joint moves more than this between two [rad or m] (> 0): the spacing
  /// is min(sample_period, sample_step / max_i v_max,i).
  double sample_step = 0.02;
  double min_segment_duration = 0.05;  ///< shortest segment [s] (> 0)
  PoseIkOptions ik;                    ///< the local IK from the previous waypoint
  int ik_branches = 8;                 ///< global-IK solves for other branches (≥ 0)
  /// Seeds of branch b are q_prev + (b/ik_branches)·branch_spread·u, u uniform in [−1, 1]ⁿ [rad].
  double branch_spread = 1.5;
  int detour_samples = 32;      ///< intermediate configurations tried for a detour (≥ 0)
  double detour_radius = 0.8;   ///< largest offset of a detour from the straight path [rad]
  int stretch_attempts = 4;     ///< a torque failure stretches a segment this often (≥ 0) …
  double stretch_factor = 1.5;  ///< … by this factor (> 1)
  std::uint64_t seed = 1;       ///< branch seeds and detours (same seed, same plan)
  /// Samples one segment may have (≥ 1): at the default spacing of 10 ms, 100000 samples are
  /// 1000 s of motion between two waypoints. Limits that make a longer segment (very slow
  /// velocities or accelerations) are out of proportion: refused before that segment is checked.
  std::int64_t max_segment_samples = 100000;
  /// States one plan may check in all (every sample of every segment tried: branches, detours,
  /// stretched and re-timed segments count again), ≥ 1. Checking takes tens of µs per sample, so
  /// the default bounds a plan to well under a minute; a plan that would pass it is refused
  /// before the segment that would.
  std::int64_t max_samples = 1000000;
  /// When the detour fails too, OMPL plans a joint-space path to the valid IK solution closest
  /// to the previous knot (`OmplPlanner` with `ompl`); its knots become via knots, each segment
  /// checked as every other.
  bool ompl_fallback = true;
  /// The fallback's options (its seed is replaced by the plan's; its collision margin by the
  /// checks'). A budget of 2 s: a waypoint is a short motion.
  OmplOptions ompl = default_fallback_options();

  static OmplOptions default_fallback_options() {
    OmplOptions o;
    o.time_budget = 2.0;
    return o;
  }
};

/// The plain fields of `PlanOptions`; `limits` (one entry per joint), `model_limits`, `checks`,
/// `ik` and `ompl` are checked on their own.
constexpr auto declared_fields(const PlanOptions*) {
  using S = PlanOptions;
  return declare<S>(
      "waypoint planner",
      field("sample_period", &S::sample_period, "s", Range::positive(),
            "largest time between checked samples"),
      field("sample_step", &S::sample_step, "rad or m", Range::positive(),
            "largest joint motion between checked samples"),
      field("min_segment_duration", &S::min_segment_duration, "s", Range::positive(),
            "shortest segment"),
      field("ik_branches", &S::ik_branches, "", Range::non_negative(),
            "global-IK solves for other branches"),
      field("branch_spread", &S::branch_spread, "rad", Range::positive(),
            "spread of the branch seeds around the previous configuration"),
      field("detour_samples", &S::detour_samples, "", Range::non_negative(),
            "intermediate configurations tried for a detour"),
      field("detour_radius", &S::detour_radius, "rad", Range::positive(),
            "largest offset of a detour from the straight path"),
      field("stretch_attempts", &S::stretch_attempts, "", Range::non_negative(),
            "how often a torque failure stretches a segment"),
      field("stretch_factor", &S::stretch_factor, "", Range{1.0, Range::inf, true, false, false},
            "how much each stretch lengthens the segment"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of branch seeds and detours"),
      field("max_segment_samples", &S::max_segment_samples, "", Range::at_least(1),
            "samples one segment may have"),
      field("max_samples", &S::max_samples, "", Range::at_least(1),
            "states one plan may check in all"),
      field("ompl_fallback", &S::ompl_fallback,
            "plan with OMPL (RRT-Connect) when the detour fails"));
}

/// @throws Error naming the option out of range.
void check(const PlanOptions& options);

/// What happened at one waypoint; its fields are documented where they are declared, below.
struct WaypointReport {
  int index = 0;
  Pose X_WT;
  Eigen::VectorXd q;
  IkStatus ik = IkStatus::not_converged;
  double position_error = 0.0;
  double orientation_error = 0.0;
  int branch = 0;
  bool detour = false;
  int ompl_knots = 0;        ///< via knots OMPL added before it (the fallback; 0: none)
  ConfigurationCheck check;  ///< the checks at the waypoint (at rest)
  double min_sigma = 0.0;
  double max_torque_ratio = 0.0;
  double time = 0.0;
  std::string message;
};

/// The fields of `WaypointReport` but `check` (a `ConfigurationCheck`, reported on its own).
constexpr auto declared_fields(const WaypointReport*) {
  using S = WaypointReport;
  return declare<S>(
      "waypoint",
      field("index", &S::index, "", "position in the path (0 = first waypoint after the start)"),
      field("X_WT", &S::X_WT, "the pose asked for"),
      field("q", &S::q, "rad or m",
            "the configuration chosen, the best IK iterate on failure (n,)"),
      field("ik", &S::ik, "status of the IK that chose q"),
      field("position_error", &S::position_error, "m", "position error at q"),
      field("orientation_error", &S::orientation_error, "rad", "orientation error at q"),
      field("branch", &S::branch, "",
            "0: local IK from the previous waypoint; b ≥ 1: global branch b"),
      field("detour", &S::detour, "True when a via configuration was inserted before it"),
      field("ompl_knots", &S::ompl_knots, "", "via knots the OMPL fallback added before it"),
      // over the samples of the segments that arrive here (the final trajectory when ok)
      field("min_sigma", &S::min_sigma, "", "smallest σmin on the way here"),
      field("max_torque_ratio", &S::max_torque_ratio, "", "largest |τ|/τ_max on the way here"),
      field("time", &S::time, "s", "arrival time in the trajectory (when ok)"),
      field("message", &S::message, "\"ok\" or why it failed"));
}

/// The result of `WaypointPlanner::plan`.
struct PlanResult {
  PlanStatus status = PlanStatus::unreachable;
  int failed_waypoint = -1;  ///< index of the waypoint that failed (−1: none, or the start)
  std::string message;       ///< one line for people
  std::vector<WaypointReport> waypoints;  ///< one per waypoint reached or tried
  JointSpline trajectory;                 ///< the timed trajectory (when ok)
  JointLimits limits;                     ///< the limits used
  double sample_spacing = 0.0;            ///< time between checked samples [s]
  std::int64_t samples = 0;               ///< states checked along the trajectory
  bool ok() const noexcept { return status == PlanStatus::ok; }
};

/// Plans through Cartesian waypoints for one chain (construct once, plan many times). Never
/// writes a caller's `mjData`: the checks and the IK run on their own scratch state.
class WaypointPlanner {
 public:
  /// @throws Error for invalid options (limits of the wrong size, non-positive values).
  explicit WaypointPlanner(const Chain& chain, const PlanOptions& options = {});

  const Chain& chain() const noexcept { return chain_; }
  const PlanOptions& options() const noexcept { return options_; }

  /// Sets the joints that are not in the chain (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Plans from rest at @p q_start through @p waypoints (poses of the chain's frame in the world)
  /// to rest at the last one.
  /// @throws Error when @p waypoints is empty, a waypoint is not finite or not a rotation,
  ///         @p q_start does not fit the chain, or a segment would have more than
  ///         `PlanOptions::max_segment_samples` samples or the plan more than `max_samples` in
  ///         all (limits out of proportion).
  PlanResult plan(const Eigen::VectorXd& q_start, const std::vector<Pose>& waypoints);

 private:
  struct SegmentCheck {
    bool ok = false;
    ConfigurationCheck failure;  // the first failing sample
    double time = 0.0;           // its time in the segment [s]
    double duration = 0.0;       // the (possibly stretched) rest-to-rest duration [s]
    double min_sigma = 0.0;
    double max_torque_ratio = 0.0;
  };

  SegmentCheck check_rest_segment(const Eigen::VectorXd& a, const Eigen::VectorXd& b);
  /// Samples segment k of @p spline; returns false at the first failing sample.
  bool check_spline_segment(const JointSpline& spline, int k, SegmentCheck& out);
  double sample_spacing() const noexcept;
  /// Sample intervals of a segment of @p duration [s] (≥ 1).
  /// @throws Error beyond `max_segment_samples` (limits out of proportion: tiny velocities or
  ///         accelerations, or huge velocities with tiny accelerations).
  int sample_intervals(double duration) const;
  /// Counts the m + 1 samples of a segment of @p duration against `max_samples`.
  /// @throws Error, before any of them is checked, when the plan would pass the bound.
  void spend_samples(int m, double duration);

  Chain chain_;
  PlanOptions options_;
  JointLimits limits_;  // resolved per plan
  Random rng_;
  Eigen::VectorXd fixed_qpos_;
  Eigen::VectorXd q_, qd_, qdd_;             // sample buffers
  ConfigurationChecker* checker_ = nullptr;  // valid during plan()
  std::int64_t checked_ = 0;                 // samples checked by this plan() so far
};

}  // namespace mjarm
