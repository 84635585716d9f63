#pragma once
/// @file
/// `OmplPlanner`: sampling-based joint-space planning through OMPL (the Open Motion Planning
/// Library, Debian's libompl-dev 1.5) — RRT-Connect by default, PRM, RRT* or BIT* — with states
/// judged by MuJoCo's collision detection on a scratch `mjData` (`CollisionChecker`), motions by
/// OMPL's discrete motion validator at a set joint-space resolution, goals as a configuration, a
/// pose or a pose region (through `GlobalIk`), then path simplification and rest-to-rest timing
/// by the joint limits, every sample of the timed trajectory checked again. docs/planning.md.
///
/// No OMPL type appears here: OMPL stays a private dependency of the library.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/planning/joint_limits.hpp"
#include "mjarm/planning/joint_spline.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"

namespace mjarm {

/// The OMPL planner that searches.
enum class OmplPlannerType {
  rrtconnect,  ///< RRT-Connect: two trees grown towards each other (fast, not optimizing)
  prm,         ///< probabilistic roadmap (multi-query; builds its roadmap on a second thread)
  rrtstar,     ///< RRT*: asymptotically optimal tree
  bitstar      ///< Batch Informed Trees: asymptotically optimal, informed batches of samples
};

constexpr auto declared_names(const OmplPlannerType*) {
  using T = OmplPlannerType;
  return std::array{EnumName{T::rrtconnect, "rrtconnect", "RRT-Connect (default)"},
                    EnumName{T::prm, "prm", "probabilistic roadmap"},
                    EnumName{T::rrtstar, "rrtstar", "RRT*, asymptotically optimal"},
                    EnumName{T::bitstar, "bitstar", "Batch Informed Trees (BIT*)"}};
}

/// How a plan ended.
enum class OmplStatus {
  success,                ///< a checked, timed trajectory from the start to a goal
  no_path_within_budget,  ///< the planner found no path within the time budget
  start_in_collision,     ///< the start configuration touches something
  goal_in_collision,      ///< every goal configuration touches something
  goal_unreachable,       ///< the IK reached no goal pose (outside the workspace)
  invalid_input,          ///< a start or goal outside the joint ranges, or not finite
  /// the timed path touches something between the validator's states, also after a second
  /// search with the validator 4× finer
  trajectory_in_collision
};

constexpr auto declared_names(const OmplStatus*) {
  using S = OmplStatus;
  return std::array{
      EnumName{S::success, "success", "a checked, timed trajectory to a goal"},
      EnumName{S::no_path_within_budget, "no_path_within_budget",
               "no path found within the time budget"},
      EnumName{S::start_in_collision, "start_in_collision", "the start touches something"},
      EnumName{S::goal_in_collision, "goal_in_collision", "every goal touches something"},
      EnumName{S::goal_unreachable, "goal_unreachable", "the IK reached no goal pose"},
      EnumName{S::invalid_input, "invalid_input", "a start or goal outside the joint ranges"},
      EnumName{S::trajectory_in_collision, "trajectory_in_collision",
               "the timed path touches something between the validator's samples"}};
}

/// Two geoms or bodies allowed to touch (each a geom name, or a body name for all its geoms).
struct AllowedCollision {
  std::string first;
  std::string second;
};

/// Every setting of `OmplPlanner`.
struct OmplOptions {
  OmplPlannerType planner = OmplPlannerType::rrtconnect;  ///< which planner searches
  /// Wall-clock budget of the search [s], in (0, 3600]: the planner stops there.
  double time_budget = 5.0;
  /// The motion validator checks a straight joint-space motion every this much [rad] of
  /// Euclidean joint distance, in (0, 1].
  double resolution = 0.02;
  std::uint64_t seed = 1;  ///< every random draw of the plan (same seed, same path)
  bool simplify = true;    ///< OMPL's path simplifier (shortcuts, then smoothing)
  /// The optimizing planners (rrtstar, bitstar, prm) keep improving until the budget ends;
  /// without it they return their first solution.
  bool optimize = false;
  /// Pose goals: IK goals sampled and checked (a pose region draws one pose per sample), ≥ 1.
  int ik_goals = 8;
  double ik_timeout = 0.02;       ///< budget of each IK solve [s], in (0, 10]
  double collision_margin = 0.0;  ///< a contact counts below this signed distance [m] (≥ 0)
  /// Checked samples of the timed trajectory are at most this far apart in any joint [rad].
  double sample_step = 0.01;
  /// Also time the path as fast as the limits allow (`OmplResult::time_optimal`).
  bool time_optimal = true;
  /// Joint limits of the timing; empty vectors are filled by `joint_limits_from_model`.
  JointLimits limits;
  ModelLimitOptions model_limits;  ///< how the model's limits are derived
  /// Pairs allowed to touch (MuJoCo's parent–child filter already lets adjacent links touch).
  std::vector<AllowedCollision> allowed_collisions;
  /// OMPL's messages go to `OmplResult::log` (otherwise they are dropped).
  bool log = false;
};

/// The plain fields of `OmplOptions`; `limits`, `model_limits` and `allowed_collisions` are
/// checked on their own.
constexpr auto declared_fields(const OmplOptions*) {
  using S = OmplOptions;
  return declare<S>(
      "OMPL planner", field("planner", &S::planner, "which OMPL planner searches"),
      field("time_budget", &S::time_budget, "s", Range::open_closed(0.0, 3600.0),
            "wall-clock budget of the search"),
      field("resolution", &S::resolution, "rad", Range::open_closed(0.0, 1.0),
            "joint-space distance between the motion validator's checks"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of every random draw"),
      field("simplify", &S::simplify, "simplify the path (shortcuts, smoothing)"),
      field("optimize", &S::optimize, "optimizing planners use the whole budget"),
      field("ik_goals", &S::ik_goals, "", Range::closed(1, 1000), "IK goals sampled for a pose"),
      field("ik_timeout", &S::ik_timeout, "s", Range::open_closed(0.0, 10.0),
            "budget of each IK solve"),
      field("collision_margin", &S::collision_margin, "m", Range::non_negative(),
            "a contact counts below this signed distance"),
      field("sample_step", &S::sample_step, "rad", Range::open_closed(0.0, 1.0),
            "largest joint motion between checked trajectory samples"),
      field("time_optimal", &S::time_optimal, "also time the path as fast as the limits allow"),
      field("log", &S::log, "keep OMPL's messages in the result"));
}

/// @throws Error naming the option out of range.
void check(const OmplOptions& options);

/// A goal configuration (n joints).
struct JointGoal {
  Eigen::VectorXd q;
};

/// A goal pose of the chain's frame in the world, reached within @p tolerance.
struct PoseGoal {
  Pose X_WT;
  double position_tolerance = 1e-4;     ///< [m] (> 0)
  double orientation_tolerance = 1e-3;  ///< [rad] (> 0)
};

/// A goal region: the frame's origin anywhere in the axis-aligned box [lower, upper] (world, m)
/// and its orientation within @p orientation_tolerance [rad] of R_WT (rotation angle).
struct PoseRegionGoal {
  Eigen::Vector3d lower = Eigen::Vector3d::Zero();
  Eigen::Vector3d upper = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_WT = Eigen::Matrix3d::Identity();
  double orientation_tolerance = 0.1;
};

using OmplGoal = std::variant<JointGoal, PoseGoal, PoseRegionGoal>;

/// The result of `OmplPlanner::plan`.
struct OmplResult {
  OmplStatus status = OmplStatus::invalid_input;
  std::string message;                ///< one line for people
  std::vector<Eigen::VectorXd> path;  ///< joint-space knots, start to goal (on success only)
  double path_length = 0.0;           ///< Σ‖q_{k+1} − q_k‖₂ [rad]
  double planning_time = 0.0;         ///< wall-clock time of plan(): IK, search, simplification [s]
  std::int64_t validity_checks = 0;   ///< states judged by the collision checker
  int goal_states = 0;                ///< collision-free goal configurations given to OMPL
  JointSpline trajectory;             ///< rest-to-rest segments through the knots (on success)
  /// On success with `OmplOptions::time_optimal`: the C² spline through the knots timed by
  /// TOPP-RA (trajectory/path/) under 0.97 × the limits, every sample checked within the limits
  /// and touching nothing (retried with the knot spacing halved or a finer grid and lower limits,
  /// docs/planning.md); none when no such timing passes (`message` says why).
  std::optional<TimeOptimalPath> time_optimal;
  JointLimits limits;                 ///< the limits of the timing
  std::int64_t trajectory_samples = 0;  ///< samples of the trajectory checked
  std::vector<std::string> log;         ///< OMPL's messages (OmplOptions::log)
  bool ok() const noexcept { return status == OmplStatus::success; }
};

/// Plans collision-free joint motions of one chain in its model's scene (construct once, plan
/// many times; not thread-safe: OMPL's log routing is process-wide).
class OmplPlanner {
 public:
  /// @throws Error for invalid options, limits of the wrong size, or an allowed-collision name
  ///         that is neither a geom nor a body of the model (naming it).
  explicit OmplPlanner(const Chain& chain, const OmplOptions& options = {});
  ~OmplPlanner();
  OmplPlanner(OmplPlanner&&) noexcept;
  OmplPlanner& operator=(OmplPlanner&&) noexcept;

  const Chain& chain() const noexcept;
  const OmplOptions& options() const noexcept;

  /// Sets the joints that are not in the chain (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Plans from rest at @p q_start to rest at @p goal. Statuses instead of exceptions for what
  /// the scene decides (see `OmplStatus`).
  /// @throws Error when @p q_start or a joint goal does not have n entries, a pose goal is not
  ///         finite or not a rotation, a tolerance is not positive, a region's lower corner is
  ///         above its upper one, or OMPL throws (its message).
  OmplResult plan(const Eigen::VectorXd& q_start, const OmplGoal& goal);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjarm
