#pragma once
/// @file
/// Time-optimal path parameterization (TOPP) of a `JointPath` under per-joint velocity and
/// acceleration limits, by reachability analysis (TOPP-RA: Pham & Pham, "A New Approach to
/// Time-Optimal Path Parameterization based on Reachability Analysis", IEEE T-RO 2018).
///
/// The path parameter s ∈ [0, L] is cut into N equal steps s_0 … s_N (Δ = L/N); the unknowns
/// are x_i = ṡ² at s_i and u_i = s̈ on step i, with x_{i+1} = x_i + 2Δ·u_i (s̈ constant on a
/// step). With q̇ = q′ṡ and q̈ = q′s̈ + q″ṡ², the limits are, per joint j:
///   velocity      q′_j(s_i)²·x_i ≤ v_j²
///   acceleration  |q′_j(s)·u_i + q″_j(s)·x(s)| ≤ a_j  at both ends of step i: s = s_i with x_i
///                 (collocation) and s = s_{i+1} with x_{i+1} (the paper's first-order
///                 interpolation), so that both one-sided accelerations at every grid point hold.
/// The backward pass computes each grid point's controllable set K_i (the x from which the end
/// x_N = 0 can be reached), K_N = {0}; the forward pass starts at x_0 = 0 and takes the largest
/// u_i that keeps x_{i+1} in K_{i+1}. The paper's guarantees: when 0 ∈ K_0 the forward pass
/// never fails, and its x_i are the largest of any feasible profile at every grid point, which
/// makes the duration the least on the grid. Between grid points the limits hold up to the
/// discretization error O(Δ²) (docs/trajectory.md has the measured figures).

#include <Eigen/Core>
#include <array>

#include "mjarm/fields.hpp"
#include "mjarm/trajectory/path/joint_path.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

/// How the path is discretized.
struct ToppOptions {
  int grid_intervals = 100;  ///< N: equal steps of the path parameter
};

constexpr auto declared_fields(const ToppOptions*) {
  using S = ToppOptions;
  return declare<S>("time-optimal path",
                    field("grid_intervals", &S::grid_intervals, "", Range::closed(2.0, 1e6),
                          "equal steps N of the path parameter"));
}

/// The outcome of a parameterization.
enum class ToppStatus {
  solved,      ///< 0 ∈ K_0: the forward pass ran to the end
  infeasible,  ///< no profile on the grid starts at rest (K_0 empty or without 0)
};

constexpr auto declared_names(const ToppStatus*) {
  using S = ToppStatus;
  return std::array{EnumName{S::solved, "solved", "the forward pass ran to the end"},
                    EnumName{S::infeasible, "infeasible", "no profile on the grid starts at rest"}};
}

/// A `JointPath` timed as fast as the limits allow (see the file): rest to rest, a
/// `TrajectoryProfile`. Construction allocates and computes; sampling allocates nothing.
class TimeOptimalPath {
 public:
  /// Times @p path under @p max_velocity [u/s] and @p max_acceleration [u/s²] (n each).
  /// @throws Error when a limit is not positive and finite or its size is not n (the joint is
  ///         named), or an option is out of its declared range.
  TimeOptimalPath(const JointPath& path, const Eigen::VectorXd& max_velocity,
                  const Eigen::VectorXd& max_acceleration, const ToppOptions& options = {});

  ToppStatus status() const noexcept { return status_; }
  bool solved() const noexcept { return status_ == ToppStatus::solved; }
  /// The duration T [s] (0 unless solved).
  double duration() const noexcept { return times_[times_.size() - 1]; }
  /// The number of joints n.
  Eigen::Index dofs() const noexcept { return path_.dofs(); }
  const JointPath& path() const noexcept { return path_; }
  const Eigen::VectorXd& max_velocity() const noexcept { return max_velocity_; }
  const Eigen::VectorXd& max_acceleration() const noexcept { return max_acceleration_; }

  /// The grid s_0 … s_N.
  const Eigen::VectorXd& grid() const noexcept { return grid_; }
  /// x_i = ṡ² at each grid point (N + 1; all 0 unless solved).
  const Eigen::VectorXd& squared_speeds() const noexcept { return x_; }
  /// u_i = s̈ on each step (N).
  const Eigen::VectorXd& path_accelerations() const noexcept { return u_; }
  /// The time t_i of each grid point (N + 1; t_0 = 0, t_N = T).
  const Eigen::VectorXd& grid_times() const noexcept { return times_; }
  /// The controllable sets K_i: row 0 the lower ends, row 1 the upper ends (2 × (N + 1)).
  const Eigen::Matrix2Xd& controllable_sets() const noexcept { return controllable_; }

  /// s, ṡ and s̈ at @p t [s], clamped to [0, T] (NaN gives the start).
  struct PathState {
    double s = 0.0, ds = 0.0, dds = 0.0;
  };
  PathState path_state(double t) const noexcept;
  /// q, q̇, q̈ and q⃛ at @p t [s] (clamped as path_state) into @p sample (resized to n when it
  /// is not; no allocation once it is).
  void at(double t, TrajectorySample& sample) const;

 private:
  void parameterize();

  JointPath path_;
  Eigen::VectorXd max_velocity_, max_acceleration_;
  ToppStatus status_ = ToppStatus::infeasible;
  Eigen::VectorXd grid_, x_, u_, times_;
  Eigen::Matrix2Xd controllable_;
};

/// `TimeOptimalPath(path, max_velocity, max_acceleration, options)`.
/// @throws Error as the constructor.
TimeOptimalPath parameterize(const JointPath& path, const Eigen::VectorXd& max_velocity,
                             const Eigen::VectorXd& max_acceleration,
                             const ToppOptions& options = {});

}  // namespace mjarm
