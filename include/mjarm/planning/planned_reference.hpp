#pragma once
/// @file
/// `PlannedReference`: a planned joint trajectory as the `ReferenceSource` of a simulation run —
/// the joint reference (q, q̇, q̈) and the Cartesian reference of the chain's frame E (pose,
/// twist and acceleration by forward kinematics) — which also measures how well E tracks it.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <variant>

#include "mjarm/control/reference.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/planning/joint_spline.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

/// How far E stayed from its reference over the ticks of a run.
struct TrackingError {
  double max_position = 0.0;       ///< max ‖p_ref − p_WE‖ [m]
  double rms_position = 0.0;       ///< root mean square of ‖p_ref − p_WE‖ [m]
  double final_position = 0.0;     ///< at the last tick [m]
  double max_orientation = 0.0;    ///< max angle of R_refᵀ·R_WE [rad]
  double final_orientation = 0.0;  ///< at the last tick [rad]
  std::int64_t ticks = 0;          ///< ticks measured
};

/// The reference at time t after the first `update` (t = data.time − t₀):
///   joint: q(t), q̇(t − lag), q̈(t) from the spline (clamped: at rest at the end);
///   task:  X_WE = FK(q(t)), V_WE = J(q)·q̇, A_WE = J(q)·q̈ + J̇(q, q̇)·q̇ (world-aligned, linear
///          first; J̇q̇ from `ChainKinematics::bias_acceleration`).
/// `update` returns false once t > duration + hold_time (the run ends as finished). It also
/// compares E's pose in @p data with the reference and accumulates `TrackingError`. After the
/// first tick (which sizes the reference) it allocates nothing and never throws.
class PlannedReference final : public ReferenceSource {
 public:
  /// @param velocity_lag evaluate q̇ this much earlier [s] (≥ 0): h/2 for MuJoCo's semi-implicit
  ///        Euler, 0 for RK4 (see `ShelfPickGoal::velocity_lag`)
  /// @throws Error when the spline is empty or does not fit the chain, or hold_time /
  ///         velocity_lag is negative or not finite.
  PlannedReference(const Chain& chain, JointSpline trajectory, double hold_time = 0.5,
                   double velocity_lag = 0.0);
  /// The same for a time-optimal path (trajectory/path/): q, q̇, q̈ from its timing.
  /// @throws Error as above, or when the path is not solved.
  PlannedReference(const Chain& chain, TimeOptimalPath trajectory, double hold_time = 0.5,
                   double velocity_lag = 0.0);

  bool update(const mjData& data, Reference& reference) noexcept override;

  /// The reference at trajectory time @p t [s] (no tracking measured). Sizes @p reference.
  void evaluate(double t, Reference& reference) noexcept;

  /// The spline tracked (nullptr when it is a time-optimal path).
  const JointSpline* spline() const noexcept { return std::get_if<JointSpline>(&trajectory_); }
  const TrackingError& tracking() const noexcept { return tracking_; }
  /// The run time the source asks for: duration + hold [s].
  double run_time() const noexcept { return duration_ + hold_time_; }
  /// Forgets the start time and the tracking figures.
  void reset() noexcept;

 private:
  PlannedReference(const Chain& chain, JointSpline spline, double hold_time, double velocity_lag,
                   std::optional<TimeOptimalPath> path);
  /// q, q̇, q̈ of the trajectory at @p t into the given vectors.
  void sample(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) noexcept;

  Chain chain_;
  std::variant<JointSpline, TimeOptimalPath> trajectory_;
  double duration_ = 0.0;
  TrajectorySample sample_;  // a time-optimal path's sample
  double hold_time_;
  double velocity_lag_;
  ChainKinematics reference_kin_;  // FK of the reference
  ChainKinematics state_kin_;      // FK of the simulated state
  Matrix6Xd J_;
  Eigen::VectorXd q_, qd_, qdd_, lagged_q_, lagged_qdd_, state_q_;
  bool started_ = false;
  double t0_ = 0.0;
  double sum_squares_ = 0.0;
  TrackingError tracking_;
};

}  // namespace mjarm
