#pragma once
/// @file
/// Closed-form inverse kinematics of 6R arms, from the joint geometry read off the model.
///
/// The chain's forward kinematics is written as a product of exponentials (PoE) at its reference
/// configuration q₀ (the model's qpos0, where MuJoCo's hinge angles are zero):
///   X_WE(q) = e^{[S₁](q₁−q₀₁)} ⋯ e^{[S₆](q₆−q₀₆)} · M,
/// each S_i the screw of a hinge (axis ω_i through the point a_i, world frame) and M = X_WE(q₀).
/// Two families are recognised, each with a tolerance (`AnalyticIkOptions::geometry_tolerance`):
/// - spherical wrist: axes 4, 5, 6 meet at one point (the wrist centre), axes 2 and 3 parallel,
///   axis 1 not parallel to them (PUMA, KUKA KR, ABB IRB, Stäubli, ...);
/// - parallel shoulder-elbow-wrist (the UR family): axes 2, 3, 4 parallel, axis 1 and axis 5 not
///   parallel to them, axes 5 and 6 intersecting (UR3/5/10/16, their e-series, ...).
/// Both are solved by Paden–Kahan subproblems on the PoE form, giving up to 8 branches: 2
/// (shoulder) × 2 (elbow) × 2 (wrist). Each angle comes with its cosine and sine from the
/// subproblems, so the solve calls no sine or cosine. Every branch is checked by the PoE forward
/// kinematics before it is returned, so a numerical failure drops a branch instead of returning a
/// wrong one.
///
/// Conventions: joint values in chain order, each wrapped into its limits by ±2π where that is
/// possible (`within_limits` says whether all six are); `closest_to` picks, per joint, the 2π
/// shift nearest the seed. At a singular configuration (wrist θ5 = 0, wrist centre on the
/// shoulder axis, elbow stretched or folded) a branch family has a free angle or two branches
/// coincide: one representative is returned and flagged `singular`.

#include <Eigen/Core>
#include <array>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

namespace detail {
struct Angle;
}

/// Which closed-form structure a chain has.
enum class AnalyticIkFamily {
  spherical_wrist,    ///< axes 4, 5, 6 concurrent; axes 2 ∥ 3
  parallel_shoulder,  ///< axes 2 ∥ 3 ∥ 4; axes 5 and 6 intersect (UR)
};

constexpr auto declared_names(const AnalyticIkFamily*) {
  using F = AnalyticIkFamily;
  return std::array{
      EnumName{F::spherical_wrist, "spherical_wrist", "axes 4, 5, 6 meet; axes 2 and 3 parallel"},
      EnumName{F::parallel_shoulder, "parallel_shoulder",
               "axes 2, 3, 4 parallel; axes 5 and 6 meet (UR)"}};
}

/// Options of `AnalyticIk`.
struct AnalyticIkOptions {
  /// Axes count as parallel when the sine of their angle is below this, and as intersecting
  /// when the lines pass within this distance [m] (> 0).
  double geometry_tolerance = 1e-9;
  /// A branch is flagged singular when its measure of the free angle (sine of the wrist angle,
  /// sine of the elbow angle, distance of the wrist centre from the shoulder axis over the arm's
  /// length) is below this (> 0).
  double singularity_tolerance = 1e-6;
  /// A branch whose own forward kinematics misses the target by more than this [m and rad] is
  /// dropped (counted in `AnalyticIkSolution::dropped`) (> 0).
  double verify_tolerance = 1e-8;
  /// Check every branch by the PoE forward kinematics (about a third of the cost of a solve). Off,
  /// branches are returned unchecked and their errors are NaN.
  bool check_branches = true;
};

constexpr auto declared_fields(const AnalyticIkOptions*) {
  using S = AnalyticIkOptions;
  return declare<S>("analytic IK",
                    field("geometry_tolerance", &S::geometry_tolerance, "m, rad", Range::positive(),
                          "axes parallel / intersecting within this"),
                    field("singularity_tolerance", &S::singularity_tolerance, "", Range::positive(),
                          "flag a branch singular below this measure"),
                    field("verify_tolerance", &S::verify_tolerance, "m, rad", Range::positive(),
                          "drop a branch whose forward kinematics misses by more"),
                    field("check_branches", &S::check_branches,
                          "check every branch by forward kinematics (off: errors are NaN)"));
}

/// The PoE geometry of a 6R chain at its reference configuration (world frame).
struct AnalyticIkGeometry {
  std::array<Eigen::Vector3d, 6> axis{};    ///< unit joint axes ω_i
  std::array<Eigen::Vector3d, 6> anchor{};  ///< a point a_i on each axis [m]
  Pose M;                                   ///< X_WE at the reference configuration
  Vector6d q_reference = Vector6d::Zero();  ///< where the PoE angles are zero (qpos0)
  /// The wrist centre (spherical wrist) or the meeting point of axes 5 and 6 (UR) [m].
  Eigen::Vector3d wrist = Eigen::Vector3d::Zero();
  double length = 1.0;  ///< a length scale of the arm [m] (for relative tolerances)
};

/// What `analyze_analytic_ik` found: a family, or the reason there is none.
struct AnalyticIkStructure {
  bool solvable = false;
  AnalyticIkFamily family = AnalyticIkFamily::spherical_wrist;
  std::string reason;  ///< why the chain is refused (empty when solvable)
  AnalyticIkGeometry geometry;
};

/// Reads the chain's geometry at qpos0 and detects its family; never throws for a chain that is
/// merely unsolvable (the reason says why: not 6 joints, a slide joint, a joint off the frame's
/// path, no family).
/// @throws Error for invalid options.
AnalyticIkStructure analyze_analytic_ik(const Chain& chain, const AnalyticIkOptions& options = {});

/// @throws Error naming the offending option.
void check(const AnalyticIkOptions& options);

/// How a solve ended.
enum class AnalyticIkStatus {
  solved,             ///< at least one branch (see `AnalyticIkSolution::count`)
  out_of_reach,       ///< no branch: the target's wrist point is beyond the arm's reach
  no_verified_branch  ///< branches were found but none passed the forward-kinematics check
};

constexpr auto declared_names(const AnalyticIkStatus*) {
  using S = AnalyticIkStatus;
  return std::array{
      EnumName{S::solved, "solved", "at least one branch"},
      EnumName{S::out_of_reach, "out_of_reach", "the target is beyond the arm's reach"},
      EnumName{S::no_verified_branch, "no_verified_branch",
               "no branch passed the forward-kinematics check"}};
}

/// One solution branch.
struct AnalyticIkBranch {
  Vector6d q = Vector6d::Zero();   ///< joint values [rad], wrapped into the limits when possible
  bool within_limits = false;      ///< all six joints within their limits
  bool singular = false;           ///< at (or within the tolerance of) a singular configuration
  double position_error = 0.0;     ///< by the PoE forward kinematics [m]
  double orientation_error = 0.0;  ///< [rad]
};

/// Every branch of one solve (fixed storage: solving allocates nothing).
struct AnalyticIkSolution {
  AnalyticIkStatus status = AnalyticIkStatus::out_of_reach;
  int count = 0;    ///< valid entries of `branches`
  int dropped = 0;  ///< branches that failed the forward-kinematics check
  std::array<AnalyticIkBranch, 8> branches{};
};

/// Closed-form IK of one 6R chain (see the file comment). Construction analyses the chain and
/// allocates; `solve` allocates nothing.
class AnalyticIk {
 public:
  /// @throws Error with the reason when the chain is not analytically solvable, or for invalid
  ///         options.
  explicit AnalyticIk(const Chain& chain, const AnalyticIkOptions& options = {});

  const Chain& chain() const noexcept { return chain_; }
  const AnalyticIkOptions& options() const noexcept { return options_; }
  AnalyticIkFamily family() const noexcept { return structure_.family; }
  const AnalyticIkGeometry& geometry() const noexcept { return structure_.geometry; }

  /// Every branch reaching the world pose @p X_WT of the chain's frame.
  /// @throws Error for a non-finite or non-rotation target (the only allocation).
  void solve(const Pose& X_WT, AnalyticIkSolution& solution) const;
  AnalyticIkSolution solve(const Pose& X_WT) const;

  /// The branch closest to @p seed (n = 6): per joint, the 2π shift nearest the seed within the
  /// limits, written into @p q; returns its index, or −1 when there is none (no branch, or none
  /// within limits when @p within_limits_only).
  int closest_to(const AnalyticIkSolution& solution, const Eigen::Ref<const Eigen::VectorXd>& seed,
                 Eigen::Ref<Eigen::VectorXd> q, bool within_limits_only = true) const noexcept;

  /// Forward kinematics by the PoE form (agrees with MuJoCo's to ~1e-15 on the chain).
  Pose forward(const Vector6d& q) const noexcept;

 private:
  /// Wraps the six PoE angles θ into joint values and checks the branch; appends it when it
  /// passes.
  void add_branch(const Pose& X_WT, const detail::Angle* theta, bool singular,
                  AnalyticIkSolution& solution) const noexcept;
  void solve_spherical_wrist(const Pose& X_WT, AnalyticIkSolution& solution) const noexcept;
  void solve_parallel_shoulder(const Pose& X_WT, AnalyticIkSolution& solution) const noexcept;

  Chain chain_;
  AnalyticIkOptions options_;
  AnalyticIkStructure structure_;
  Vector6d lower_, upper_;
  /// UR family with axis 6 parallel to axes 2–4 at qpos0 and axis 5 perpendicular to them.
  bool tool_axis_along_shoulder_ = false;
};

}  // namespace mjarm
