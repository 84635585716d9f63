#pragma once
/// @file
/// `ShelfPickTask`: the state machine of the shelf pick — approach, settle, hold, release — as a
/// `ReferenceSource` that a `Simulation` calls every control tick.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>

#include "mjarm/control/reference.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/pick_monitor.hpp"
#include "mjarm/tasks/tick_observer.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"

namespace mjarm {

class Recorder;

/// Phases of a shelf pick, in order. Each change is written to the recorder as a "phase" event.
enum class PickPhase {
  approach,  ///< the reference moves from the start to the pick point (tip outside tolerance)
  settle,    ///< the reference rests on the pick point; the tip is not inside the tolerance yet
  hold,      ///< the tip is inside the tolerance; the gripper reference is closed (1)
  release    ///< the hold lasted long enough; gripper reference open (0); the run ends
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const PickPhase*) {
  using E = PickPhase;
  return std::array{EnumName{E::approach, "approach"}, EnumName{E::settle, "settle"},
                    EnumName{E::hold, "hold"}, EnumName{E::release, "release"}};
}

/// Everything a `ShelfPickTask` needs, fixed before the run.
struct ShelfPickGoal {
  Pose X_WS;                   ///< pose of the tool frame at the start (world; m)
  Pose X_WT;                   ///< pose to reach: position = pick point, rotation = tool to hold
  Eigen::VectorXd q_start;     ///< joint values at the start (chain order) [rad or m]
  Eigen::VectorXd q_target;    ///< joint values that put the tool at X_WT (from IK) [rad or m]
  double approach_time = 0.3;  ///< duration T of the approach [s] (> 0)
  bool position_only = false;  ///< only the position counts (orientation error reported as 0)
  /// How far the integrator's velocities lag its positions [s] (≥ 0): velocity references are
  /// evaluated at t − velocity_lag. MuJoCo's semi-implicit Euler advances q_{k+1} = q_k +
  /// h·v_{k+1}, so the qvel a controller sees at t_k is the mean velocity over [t_k − h, t_k],
  /// i.e. the velocity at t_k − h/2: use h/2 there, 0 for RK4. Comparing it with the reference
  /// velocity at t_k would make the damping fight a phantom error of (h/2)·acceleration.
  double velocity_lag = 0.0;
  PickCriteria criteria;  ///< tolerance and hold time
};

/// The poses and joint values are checked against the chain by hand.
constexpr auto declared_fields(const ShelfPickGoal*) {
  using S = ShelfPickGoal;
  return declare<S>(
      "shelf pick task",
      field("approach_time", &S::approach_time, "s", Range::positive(), "duration of the approach"),
      field("position_only", &S::position_only, "only the position counts"),
      field("velocity_lag", &S::velocity_lag, "s", Range::non_negative(),
            "velocity references are evaluated this long before the positions'"),
      field("criteria", &S::criteria, "tolerance and hold time"));
}

/// The shelf pick as a reference source. From the start time t₀ (data.time at the first
/// `update`), with the approach of duration T built from the library's profiles (rest to rest,
/// i.e. the minimum-jerk quintic):
/// - task reference: the `Se3Interpolation` from X_S to X_T (position by a quintic per axis,
///   orientation by a quintic in the rotation vector relative to R_S, which rest to rest is the
///   geodesic R(t) = exp(s·ω)·R_S, ω = log(R_T·R_Sᵀ)); pose and twist rate at t, twist at
///   t − velocity_lag (world axes, linear first);
/// - joint reference: the `QuinticTrajectory` from q_S to q_T at rest (q = q_S + (q_T − q_S)·s),
///   q and q̈ at t, q̇ at t − velocity_lag (for computed torque, and as the null-space posture of
///   the task-space controllers);
/// - the tip (the chain's frame, read from data) is fed to a `PickMonitor` with t − t₀; the
///   phase follows its events; when the hold is complete the phase becomes release, the gripper
///   reference opens and `update` returns false (the run ends as finished).
/// `update` allocates nothing and never throws; phase changes and tolerance exits are written to
/// the recorder given to the constructor (if any).
class ShelfPickTask final : public ReferenceSource {
 public:
  /// @param chain the controlled chain (its frame is the tool tip)
  /// @param recorder where phase events go (may be null; must outlive the task)
  /// @throws Error when the goal's vectors do not fit the chain, hold NaN/inf, or the approach
  ///         time or criteria are not positive.
  ShelfPickTask(const Chain& chain, const ShelfPickGoal& goal, Recorder* recorder = nullptr);

  /// One tick (see the class comment). Returns false once released.
  bool update(const mjData& data, Reference& reference) noexcept override;

  PickPhase phase() const noexcept { return phase_; }
  const PickMonitor& monitor() const noexcept { return monitor_; }
  const PickMetrics& metrics() const noexcept { return monitor_.metrics(); }
  const ShelfPickGoal& goal() const noexcept { return goal_; }
  /// Distance from the start to the pick point [m].
  double distance() const noexcept { return (goal_.X_WT.p - goal_.X_WS.p).norm(); }
  /// Tip pose at the last `update` (world).
  const Pose& tip() const noexcept { return X_WE_; }
  /// Simulated time of the first `update` [s] (NaN before).
  double start_time() const noexcept { return t0_; }
  /// Calls @p observer at the start of every `update` with the tick's state (null: none). The
  /// observer must outlive the task's run; calling it adds no allocation of the task's own.
  void set_observer(TickObserver* observer) noexcept { observer_ = observer; }

 private:
  void enter(PickPhase phase, double t) noexcept;

  Chain chain_;
  ShelfPickGoal goal_;
  Recorder* recorder_;
  TickObserver* observer_ = nullptr;
  Se3Interpolation approach_;                // the task-space reference
  QuinticTrajectory joints_;                 // the joint-space reference
  Eigen::VectorXd q_scratch_, qdd_scratch_;  // for the lagged q̇ (sized at construction)
  PickMonitor monitor_;
  PickPhase phase_ = PickPhase::approach;
  bool started_ = false;
  double t0_;
  Pose X_WE_;
  std::array<char, 160> message_{};
};

}  // namespace mjarm
