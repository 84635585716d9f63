#pragma once
/// @file
/// `JointPath`: a geometric path through joint-space waypoints, without timing: a natural cubic
/// spline q(s) per joint in the path parameter s, the cumulative chord length of the waypoints
/// (s_0 = 0, s_k = s_{k−1} + ‖q_k − q_{k−1}‖). It is C² (q, q′, q″ continuous; q‴ steps at
/// the interior waypoints), passes every waypoint, and has q″ = 0 at both ends. The time-optimal
/// parameterization (time_optimal_path.hpp) gives it a timing s(t).

#include <Eigen/Core>
#include <vector>

namespace mjarm {

/// A C² cubic spline through n-joint waypoints, parameterized by chord length (see the file).
/// Construction allocates; evaluation allocates nothing.
class JointPath {
 public:
  /// The spline through @p waypoints (K + 1 ≥ 2 vectors of n ≥ 1 entries each) [rad or m].
  /// @throws Error naming the waypoint (and joint) when there are fewer than 2 waypoints, their
  ///         sizes differ, n is 0, a value is not finite, or two consecutive waypoints are equal
  ///         (a zero-length piece has no direction).
  explicit JointPath(const std::vector<Eigen::VectorXd>& waypoints);

  /// The number of joints n.
  Eigen::Index dofs() const noexcept { return waypoints_.rows(); }
  /// The number of waypoints K + 1.
  int waypoint_count() const noexcept { return static_cast<int>(waypoints_.cols()); }
  /// The waypoints, one per column (n × (K + 1)).
  const Eigen::MatrixXd& waypoints() const noexcept { return waypoints_; }
  /// The path parameter s_k of each waypoint (K + 1; s_0 = 0, the last is length()).
  const Eigen::VectorXd& knots() const noexcept { return knots_; }
  /// The path length L: the sum of the chord lengths.
  double length() const noexcept { return knots_[knots_.size() - 1]; }

  /// q(s), q′(s) = dq/ds and q″(s) at @p s, clamped to [0, L] (NaN gives s = 0). Allocates
  /// nothing.
  /// @throws Error when an output does not have n entries.
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const;
  /// The same and q‴(s) (that of the piece holding s: it steps at interior waypoints).
  /// @throws Error as above.
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq, Eigen::Ref<Eigen::VectorXd> dddq) const;

  /// The index k of the piece [s_k, s_{k+1}] holding @p s (clamped as evaluate).
  int piece_at(double s) const noexcept;

 private:
  Eigen::MatrixXd waypoints_;  // n × (K + 1)
  Eigen::VectorXd knots_;      // K + 1
  // piece k: q(s_k + τ) = c0 + c1·τ + c2·τ² + c3·τ³, one column per piece (n × K each)
  Eigen::MatrixXd c0_, c1_, c2_, c3_;
};

}  // namespace mjarm
