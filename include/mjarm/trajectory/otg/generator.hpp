#pragma once
/// @file
/// `JerkLimitedGenerator`: time-optimal, jerk-limited, time-synchronized online trajectories for
/// n degrees of freedom (after Berscheid & Kröger 2021, "Jerk-limited real-time trajectory
/// generation with arbitrary target states"), fast enough to recompute at every control tick.
///
/// One calculation:
/// 1. per DoF, a brake pre-trajectory when the current state is beyond the limits
///    (otg/brake.hpp), then the time-optimal profile and the blocked intervals of
///    durations (otg/min_time.hpp) — for the DoFs that decide the duration only: the
///    one guessed slowest first, then each DoF that cannot take the duration synchronized so far
///    (checked by the positions it can reach then, otg/reach.hpp);
/// 2. the synchronized duration: the smallest one every DoF can take (otg/sync.hpp);
/// 3. for every DoF, a profile of exactly that duration: its extremal profile of that duration,
///    or the blend of the profiles to its lowest and highest reachable positions
///    (otg/fixed_time.hpp).
/// The velocity interface does the same with velocity targets (otg/velocity.hpp).

#include <span>
#include <vector>

#include "mjarm/trajectory/otg/block.hpp"
#include "mjarm/trajectory/otg/optimal_brake.hpp"
#include "mjarm/trajectory/otg/profile.hpp"
#include "mjarm/trajectory/otg/reach.hpp"

namespace mjarm {

struct TrajectorySample;  // trajectory/trajectory_sample.hpp

namespace jerk_detail {
struct UpPair;  // a DoF's problem in both directions (src/trajectory/otg/up.hpp)
}  // namespace jerk_detail

/// Outcome of a calculation or of a step along the trajectory.
enum class OtgStatus {
  working,                ///< a trajectory exists and the target is not reached yet
  finished,               ///< the target is reached (the time is at or past the duration)
  error_brake,            ///< a DoF's brake did not fit its profile (not expected: ≤ 3 phases)
  error_no_profile,       ///< step 1 found no time-optimal profile for a DoF
  error_synchronization,  ///< a DoF has no profile of the synchronized duration
  /// the trajectory failed its final check (OtgResult's tolerances): a DoF's profile ends off
  /// its target, exceeds a limit after its brake, or does not last the synchronized duration.
  /// Double precision: the motion (or the range it is blended from) is too large for the scale
  /// of its start and target — limits outside the supported range (docs/trajectory_otg.md,
  /// "Supported limits")
  error_precision,
};

constexpr auto declared_names(const OtgStatus*) {
  using S = OtgStatus;
  return std::array{
      EnumName{S::working, "working", "a trajectory exists and the target is not reached yet"},
      EnumName{S::finished, "finished", "the target is reached"},
      EnumName{S::error_brake, "error_brake", "a DoF's brake did not fit its profile"},
      EnumName{S::error_no_profile, "error_no_profile", "no time-optimal profile for a DoF"},
      EnumName{S::error_synchronization, "error_synchronization",
               "a DoF has no profile of the synchronized duration"},
      EnumName{S::error_precision, "error_precision", "the trajectory failed its final check"}};
}

/// Result of a calculation. A result that says working or finished has been checked: every
/// DoF's profile ends on its target, lasts the synchronized duration and keeps its limits after
/// its brake, to the tolerances below (else the status is error_precision).
struct OtgResult {
  /// Every DoF's profile ends with |Δp| ≤ this·max(1, |p₀|, |p_f|), |Δv| ≤ this·max(1, |v₀|,
  /// |v_f|) and |Δa| ≤ this·max(1, |a₀|, |a_f|) (start and target values; the velocity interface
  /// checks v and a only).
  static constexpr double kEndTolerance = 1e-8;
  /// After its brake no DoF exceeds (1 + this)·limit: |a| and |j| (and |v| for the position
  /// interface), at the analytic extrema of every phase.
  static constexpr double kLimitTolerance = 1e-9;
  /// Every DoF's profile lasts the synchronized duration T to this·max(1 s, T).
  static constexpr double kSyncTolerance = 1e-9;

  OtgStatus status = OtgStatus::error_no_profile;  ///< outcome
  double duration = 0.0;                           ///< synchronized duration [s] (brake included)
  int limiting_dof = -1;                           ///< the DoF that sets the duration
  int failed_dof = -1;                             ///< the DoF that failed (error statuses only)
  /// The largest end miss over the DoFs, relative as for kEndTolerance (0 when the calculation
  /// failed before its check).
  double end_error = 0.0;
  /// The largest limit excess over the DoFs after their brakes, relative (|x|/limit − 1; ≤ 0
  /// within the limits; 0 when the calculation failed before its check).
  double limit_excess = 0.0;
  /// The largest |profile duration − duration| over the DoFs [s] (0 when the calculation failed
  /// before its check).
  double sync_error = 0.0;
};

/// The generator. All storage is sized by the constructor; calculate(), at() and step()
/// allocate nothing.
class JerkLimitedGenerator {
 public:
  /// A generator for one DoF per entry of @p limits.
  /// @throws Error when @p limits is empty or a limit is not positive and finite (the message
  /// names the DoF and the limit).
  explicit JerkLimitedGenerator(std::span<const JerkLimits> limits);
  ~JerkLimitedGenerator();
  JerkLimitedGenerator(const JerkLimitedGenerator&);
  JerkLimitedGenerator(JerkLimitedGenerator&&) noexcept;
  JerkLimitedGenerator& operator=(const JerkLimitedGenerator&);
  JerkLimitedGenerator& operator=(JerkLimitedGenerator&&) noexcept;

  /// Number of degrees of freedom.
  int dofs() const noexcept { return static_cast<int>(limits_.size()); }
  /// The limits of DoF @p i.
  const JerkLimits& limits(int i) const { return limits_.at(static_cast<std::size_t>(i)); }

  /// Position interface: the synchronized time-optimal trajectory from @p current to @p target
  /// (p, v, a each). A current state beyond the limits is braked into them first. Restarts the
  /// clock of step() at 0.
  /// @throws Error when a span's size is not dofs(), a value is not finite, or a target state
  /// is outside the limits (|v| > v_max, |a| > a_max, or not reachable without exceeding v_max:
  /// |v − a·|a|/(2 j_max)| > v_max); the message names the DoF and the value.
  OtgResult calculate(std::span<const KinematicState> current,
                      std::span<const KinematicState> target);

  /// Velocity interface: reach the velocities and accelerations of @p target (positions
  /// ignored) time-optimally under the acceleration and jerk limits, synchronized. A current
  /// acceleration beyond its limit is ramped into it first. Restarts the clock of step() at 0.
  /// @throws Error as calculate(); a target velocity may not exceed its limit either.
  OtgResult calculate_velocity(std::span<const KinematicState> current,
                               std::span<const KinematicState> target);

  /// The result of the last calculation.
  const OtgResult& result() const noexcept { return result_; }
  /// Synchronized duration of the last calculation [s].
  double duration() const noexcept { return result_.duration; }
  /// The profile of DoF @p i from the last calculation (brake phases first).
  const JerkProfile& profile(int i) const { return profiles_.at(static_cast<std::size_t>(i)); }
  /// Number of brake phases at the start of profile(@p i) (0 when the DoF started within its
  /// limits).
  int brake_phases(int i) const { return brake_phases_.at(static_cast<std::size_t>(i)); }
  /// Duration of the brake phases of profile(@p i) [s].
  double brake_duration(int i) const { return brake_durations_.at(static_cast<std::size_t>(i)); }
  /// What step 1 found for DoF @p i in the last calculation (after its brake). A position
  /// calculation runs step 1 only for the DoFs that decide the synchronized duration; for the
  /// others it runs here, on first use.
  const JerkBlock& block(int i) const;

  /// The state of every DoF at time @p t [s] of the last trajectory into @p out (its first
  /// min(size, dofs()) entries).
  void at(double t, std::span<JerkSample> out) const noexcept;
  /// The same into @p sample (resized to dofs() when it is not; trajectory/trajectory_sample.hpp),
  /// the jerk 0 after the duration: the generator as a `TrajectoryProfile`.
  void at(double t, TrajectorySample& sample) const;

  /// Online use: advances the clock by @p dt [s] and writes the state then into @p state (its
  /// first min(size, dofs()) entries). @return working, finished once the clock reached the
  /// duration, or the error of the last calculation.
  OtgStatus step(double dt, std::span<KinematicState> state) noexcept;
  /// The clock of step() [s].
  double time() const noexcept { return time_; }

 private:
  void check_states(std::span<const KinematicState> current, std::span<const KinematicState> target,
                    bool velocity_interface) const;
  bool solve_step1(int i) const noexcept;
  // the final check of a calculated trajectory (OtgResult's tolerances); sets result_.status
  void check_result(std::span<const KinematicState> current,
                    std::span<const KinematicState> target) noexcept;

  std::vector<JerkLimits> limits_;
  std::vector<JerkProfile> profiles_;
  mutable std::vector<JerkBlock> blocks_;  // filled on demand by block()
  std::vector<JerkReach> reach_;
  std::vector<KinematicState> targets_;
  std::vector<double> estimates_;
  std::vector<int> order_;
  std::vector<jerk_detail::UpPair> problems_;  // per DoF, after its brake
  mutable std::vector<char> solved_;  // step 1 done for the DoF (for blocks_)
  bool velocity_interface_ = false;
  std::vector<double> brake_durations_;
  std::vector<int> brake_phases_;
  std::vector<KinematicState> after_brake_;
  OptimalBrakeScratch brake_scratch_;  // the brake chosen for the whole motion (position)
  OtgResult result_;
  double time_ = 0.0;
};

}  // namespace mjarm
