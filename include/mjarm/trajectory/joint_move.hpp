#pragma once
/// @file
/// `JointMove`: a move of n axes from a start state to a target state under per-axis limits,
/// made by the profile kind asked for — trapezoid, quintic, smoothstep, smootherstep or
/// jerk-limited —, timed within the limits (or in a given duration), with its exact peaks and
/// the limits they break. A `TrajectoryProfile` over whichever profile the kind builds: what
/// `mjarm traj` samples, prints and plots.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <variant>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "mjarm/trajectory/smooth_ramp_trajectory.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {

/// The profile kinds a `JointMove` is made of.
enum class ProfileKind {
  trapezoid,     ///< `SyncedTrapezoid`: trapezoidal velocity, the axes finishing together
  quintic,       ///< `QuinticTrajectory` timed by `shortest_quintic_duration`
  smoothstep,    ///< `SmoothRampTrajectory` of smoothstep (C¹)
  smootherstep,  ///< `SmoothRampTrajectory` of smootherstep (C², minimum jerk)
  jerk_limited,  ///< `JerkLimitedGenerator`: time-optimal under a jerk limit too
};

/// The names are `mjarm traj`'s KIND.
constexpr auto declared_names(const ProfileKind*) {
  using K = ProfileKind;
  return std::array{EnumName{K::trapezoid, "trapezoid", "trapezoidal velocity"},
                    EnumName{K::quintic, "quintic", "quintic polynomial, shortest duration"},
                    EnumName{K::smoothstep, "smoothstep", "smoothstep ramp (C¹)"},
                    EnumName{K::smootherstep, "smootherstep", "smootherstep ramp (C², minimum jerk)"},
                    EnumName{K::jerk_limited, "jerk-limited", "time-optimal under a jerk limit too"}};
}

/// What a profile kind is and what it takes.
struct ProfileKindInfo {
  ProfileKind kind;
  const char* name;     ///< to_string(kind)
  const char* summary;  ///< one line saying what it is (`mjarm traj --help` prints it)
  /// It takes start and target velocities and accelerations (else it moves rest to rest).
  bool moving_ends;
  /// It takes a given duration (else its duration follows from the limits).
  bool given_duration;
  /// It needs a jerk limit.
  bool jerk_limit;
};

/// Every kind, in the order of `ProfileKind`.
const std::array<ProfileKindInfo, 5>& profile_kinds() noexcept;

/// What a kind is and takes.
const ProfileKindInfo& profile_kind_info(ProfileKind kind) noexcept;

/// The boundary states and limits of a move of n axes (units u per axis: m, rad, …).
struct JointMoveRequest {
  Eigen::VectorXd start;                ///< q₀ [u] (n)
  Eigen::VectorXd start_velocity;       ///< q̇₀ [u/s] (n; empty: at rest)
  Eigen::VectorXd start_acceleration;   ///< q̈₀ [u/s²] (n; empty: 0)
  Eigen::VectorXd target;               ///< q₁ [u] (n)
  Eigen::VectorXd target_velocity;      ///< q̇₁ [u/s] (n; empty: at rest)
  Eigen::VectorXd target_acceleration;  ///< q̈₁ [u/s²] (n; empty: 0)
  Eigen::VectorXd max_velocity;         ///< v_max [u/s] (n, positive)
  Eigen::VectorXd max_acceleration;     ///< a_max [u/s²] (n, positive)
  /// j_max [u/s³] (n, positive; a NaN entry: no jerk limit on that axis; empty: none at all).
  /// The jerk-limited kind needs every entry; the others are only checked against it.
  Eigen::VectorXd max_jerk;
  /// The duration T [s] instead of the shortest within the limits (the kinds that take one).
  std::optional<double> duration;
};

/// The peaks of |q̇|, |q̈| and |q⃛| over a move, per axis.
struct TrajectoryPeaks {
  Eigen::VectorXd velocity;      ///< [u/s]
  Eigen::VectorXd acceleration;  ///< [u/s²]
  /// [u/s³]; +∞ where the acceleration steps (a trapezoid's switches)
  Eigen::VectorXd jerk;
};

/// A limit a peak breaks.
struct LimitViolation {
  /// Which limit.
  enum class Quantity { velocity, acceleration, jerk };
  Eigen::Index axis = 0;                   ///< the axis
  Quantity quantity = Quantity::velocity;  ///< the limit broken
  double peak = 0.0;                       ///< the peak [u/s, u/s² or u/s³]
  double limit = 0.0;                      ///< the limit it exceeds
};

/// A move made by one profile kind (see the file). Construction plans it (and allocates);
/// `at` allocates nothing once its sample has n entries.
class JointMove {
 public:
  /// The profile a kind builds.
  using Profile =
      std::variant<SyncedTrapezoid, QuinticTrajectory, SmoothRampTrajectory, JerkLimitedGenerator>;

  /// Plans the move of @p kind from @p request: the trapezoid and the jerk-limited generator
  /// take the shortest duration their limits allow; the quintic and the ramps take the given
  /// duration or else the shortest within the velocity and acceleration limits (the quintic's
  /// exactly, `shortest_quintic_duration`). A jerk-limited start beyond its limits brakes first.
  /// @throws Error when a size differs or is 0, a value is not finite, a limit is not positive,
  ///         the request does not suit the kind (moving ends for a rest-to-rest kind, a duration
  ///         for a kind that takes none, no jerk limit for the jerk-limited kind), no quintic
  ///         duration keeps the limits (its status and axis named), or the jerk-limited generator
  ///         refuses the target or finds no trajectory (its status and axis named; for
  ///         error_precision the check it failed and by how much).
  JointMove(ProfileKind kind, const JointMoveRequest& request);

  /// The kind.
  ProfileKind kind() const noexcept { return kind_; }
  /// The request, its empty vectors filled (zeros; NaN for no jerk limit).
  const JointMoveRequest& request() const noexcept { return request_; }
  /// The profile behind the move (its kind's alternative).
  const Profile& profile() const noexcept { return profile_; }

  /// The duration T [s] (0 when nothing moves).
  double duration() const noexcept { return duration_; }
  /// The number of axes n.
  Eigen::Index dofs() const noexcept { return request_.start.size(); }
  /// q, q̇, q̈, q⃛ at @p t [s] into @p sample (resized to n when it is not): the profile's own
  /// sample (time clamped to [0, T]; the jerk-limited one continues at constant acceleration
  /// after T with zero jerk).
  void at(double t, TrajectorySample& sample) const;

  /// The exact peaks per axis: at the analytic extrema of each profile (a jerk-limited axis that
  /// starts beyond its limits: from the end of its brake on, the jerk over the whole move).
  const TrajectoryPeaks& peaks() const noexcept { return peaks_; }
  /// Each peak above its limit by more than 1e-9 relative (none is the move within its limits).
  std::vector<LimitViolation> violations() const;

  /// The axis whose limits set the duration: the trapezoid's slowest axis, the ramp's, the
  /// quintic's (`shortest_quintic_duration`), the jerk-limited generator's limiting DoF; −1 when
  /// the duration was given or nothing moves.
  Eigen::Index limiting_axis() const noexcept { return limiting_axis_; }
  /// The quintic's duration search (the quintic kind without a given duration; else nullopt).
  const std::optional<QuinticDuration>& quintic_duration() const noexcept {
    return quintic_duration_;
  }

 private:
  ProfileKind kind_;
  JointMoveRequest request_;
  std::optional<QuinticDuration> quintic_duration_;
  Profile profile_;
  double duration_ = 0.0;
  TrajectoryPeaks peaks_;
  Eigen::Index limiting_axis_ = -1;
};

}  // namespace mjarm
