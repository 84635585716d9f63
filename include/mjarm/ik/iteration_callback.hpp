#pragma once
/// @file
/// The optional per-iteration observer of the local IK solvers (`PositionIk`, `PoseIk`,
/// `MultiTargetIk`): what the closed-loop IK tutorials print every N iterations, without
/// editing the solver. Unset (the default), a solver neither calls nor allocates anything for
/// it: the only cost is one test of an empty `std::function` per iteration.
///
/// @code
/// PositionIkOptions options;
/// options.on_iteration = [](const IkIteration& it) {
///   if (it.iteration % 10 == 0) std::printf("%4d  %.3e m\n", it.iteration, it.position_error);
/// };
/// PositionIk ik(chain, options);
/// @endcode

#include <Eigen/Core>
#include <functional>

namespace mjarm {

/// One iterate of a local IK solve, as reported to `IkIterationCallback`.
struct IkIteration {
  /// 0 for the seed (clipped into the limits), then 1, 2, … after each accepted step; the last
  /// call has the solve's `IkResult::iterations`.
  int iteration = 0;
  /// ‖p_WT − p_WE‖ at this iterate [m] (multi-target: the worst target); NaN when a NaN
  /// appeared (the solve then ends with invalid_input).
  double position_error = 0.0;
  /// Rotation angle between target and achieved frame [rad] (multi-target: the worst pose
  /// target); 0 for position IK.
  double orientation_error = 0.0;
  /// The iterate (n, chain order); valid during the call only.
  const Eigen::VectorXd* q = nullptr;
};

/// Called by a local IK solver once per iterate, the seed's included, before the stopping tests.
/// It runs inside the solve: what it does (printing, storing) is the caller's cost, and it must
/// not throw (the solvers' loops are noexcept in spirit and leave no state to unwind).
using IkIterationCallback = std::function<void(const IkIteration&)>;

}  // namespace mjarm
