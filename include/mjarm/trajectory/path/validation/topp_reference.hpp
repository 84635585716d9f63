#pragma once
/// @file
/// An independent solve of the time-optimal path parameterization's grid problem, for
/// validation (tests and `mjarm bench topp`): the same grid, limits and constraint rows as
/// TimeOptimalPath (time_optimal_path.hpp), written here over all x_0 … x_N at once, with
/// u_i = (x_{i+1} − x_i)/2Δ_i, and solved as a convex program by Newton steps, each a dense QP
/// (qp/dense_qp.hpp), with none of the reachability code:
///
///     minimize T(x) = Σ 2Δ_i/(√x_i + √x_{i+1})   (the duration: s̈ constant on each step)
///     subject to x_0 = x_N = 0,  0 ≤ x_i ≤ min_j (v_j/q′_j(s_i))²,
///       |q′_j(s_i)·u_i + q″_j(s_i)·x_i| ≤ a_j,  |q′_j(s_{i+1})·u_i + q″_j(s_{i+1})·x_{i+1}| ≤ a_j
///
/// T is convex (1 over a concave positive function) and the constraints are linear, so a
/// Newton step from a feasible point stays feasible along its segment, and the iteration ends
/// at the grid problem's minimum duration — whatever the start. The default start is the
/// nearest feasible point to the velocity bounds (one QP); a given start (TOPP-RA's profile)
/// only saves iterations. TOPP-RA's duration can never be below this one (beyond rounding) if
/// its profile is feasible; how much it is above is the measured gap of its greedy forward pass.

#include <Eigen/Core>

#include "mjarm/qp/dense_qp.hpp"
#include "mjarm/trajectory/path/joint_path.hpp"

namespace mjarm {

/// The reference's answer.
struct ToppReference {
  qp::QpStatus status = qp::QpStatus::invalid_input;  ///< the QP's outcome
  Eigen::VectorXd squared_speeds;                     ///< x_0 … x_N (N + 1)
  double duration = 0.0;                              ///< the minimum T [s] (∞ unless solved)
  int iterations = 0;                                 ///< the QPs' active-set steps, all together
  int newton_steps = 0;                               ///< Newton steps taken
  bool solved() const noexcept { return status == qp::QpStatus::solved; }
};

/// Solves the grid problem of @p path on @p grid (s_0 = 0 … s_N = L, increasing) under
/// @p max_velocity and @p max_acceleration (see the file), from @p start (N + 1 squared speeds,
/// feasible; clipped to the bounds) or, when null, from the nearest feasible point to the velocity
/// bounds. Allocates (a dense QP of N + 1 variables and 2·n·N two-sided rows).
/// @throws Error when the sizes do not match or the grid has fewer than 2 points.
ToppReference solve_topp_reference(const JointPath& path, const Eigen::VectorXd& max_velocity,
                                   const Eigen::VectorXd& max_acceleration,
                                   const Eigen::VectorXd& grid,
                                   const Eigen::VectorXd* start = nullptr);

/// The worst relative excess of the grid profile @p squared_speeds over the constraints above
/// (velocity at each grid point, acceleration at both ends of each step; x_0, x_N and x ≥ 0
/// not included), evaluated from the path here: max over rows of |value|/limit − 1 (≤ 0 when
/// within).
double topp_grid_excess(const JointPath& path, const Eigen::VectorXd& max_velocity,
                        const Eigen::VectorXd& max_acceleration, const Eigen::VectorXd& grid,
                        const Eigen::VectorXd& squared_speeds);

/// Σ 2Δ_i/(√x_i + √x_{i+1}) [s]: the duration of the grid profile (s̈ constant on each step).
double topp_grid_duration(const Eigen::VectorXd& grid, const Eigen::VectorXd& squared_speeds);

}  // namespace mjarm
