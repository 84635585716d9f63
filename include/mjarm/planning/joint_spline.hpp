#pragma once
/// @file
/// `JointSpline`: quintic segments through joint-space knots, with non-zero velocities at the
/// interior knots so that the arm does not stop at each, timed by the joint limits.

#include <Eigen/Core>
#include <vector>

#include "mjarm/trajectory/quintic.hpp"

namespace mjarm {

/// A C² joint trajectory: K quintic segments through K + 1 knots q_0 … q_K, each segment
/// starting where the previous one ends with the same q, q̇ and q̈ (q̈ = 0 at every knot, q̇ = 0
/// at both ends). Evaluating allocates nothing.
class JointSpline {
 public:
  /// An empty spline (no segment, duration 0).
  JointSpline() = default;

  /// Knots @p q (K + 1 vectors of n entries), knot velocities @p qd (K + 1) and segment
  /// durations @p durations (K, each > 0).
  /// @throws Error when sizes differ, a value is not finite, a duration is not positive, or
  ///         there are fewer than 2 knots.
  JointSpline(const std::vector<Eigen::VectorXd>& q, const std::vector<Eigen::VectorXd>& qd,
              const std::vector<double>& durations);

  /// The knot velocities by the slope heuristic: at an interior knot k, per joint,
  /// v = ½(s_{k−1} + s_k) with the segment slopes s_j = (q_{j+1} − q_j)/T_j when both have the
  /// same sign (0 otherwise, and at knots with @p blend[k] = 0), then clipped to ±max_velocity.
  /// Both ends get 0.
  static std::vector<Eigen::VectorXd> blend_velocities(const std::vector<Eigen::VectorXd>& q,
                                                       const std::vector<double>& durations,
                                                       const std::vector<char>& blend,
                                                       const Eigen::VectorXd& max_velocity);

  /// The timed spline through @p q: first each segment's rest-to-rest shortest duration
  /// (`shortest_quintic_duration`, at least @p floors[k]), then the blended knot velocities from
  /// those durations, then each segment's shortest duration with its boundary velocities (at
  /// least floors[k]). A segment with no feasible duration gets zero velocity at both ends.
  /// @param blend one flag per knot (K + 1): 0 forces a stop there
  /// @throws Error for sizes that differ, non-finite values or non-positive limits.
  static JointSpline timed(const std::vector<Eigen::VectorXd>& q,
                           const Eigen::VectorXd& max_velocity,
                           const Eigen::VectorXd& max_acceleration,
                           const std::vector<double>& floors, const std::vector<char>& blend);

  bool empty() const noexcept { return segments_.empty(); }
  /// Number of joints n (0 when empty).
  Eigen::Index size() const noexcept { return empty() ? 0 : segments_.front().size(); }
  /// Number of segments K.
  int segments() const noexcept { return static_cast<int>(segments_.size()); }
  /// Segment k.
  const QuinticTrajectory& segment(int k) const { return segments_.at(k); }
  /// Start time of segment k (k = K gives the total duration) [s].
  double knot_time(int k) const { return starts_.at(k); }
  /// The knots and their velocities (K + 1 each).
  const std::vector<Eigen::VectorXd>& knots() const noexcept { return q_; }
  const std::vector<Eigen::VectorXd>& knot_velocities() const noexcept { return qd_; }
  /// Total duration [s].
  double duration() const noexcept { return starts_.empty() ? 0.0 : starts_.back(); }

  /// q, q̇, q̈ at @p t [s], clamped to [0, duration]. Allocates nothing.
  /// @throws Error when the spline is empty or an output does not have n entries.
  void at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
          Eigen::Ref<Eigen::VectorXd> qdd) const;

  /// q, q̇, q̈ and the jerk q⃛ (that of the segment holding @p t) at @p t [s],
  /// clamped as above. Allocates nothing.
  /// @throws Error as above.
  void at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
          Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::VectorXd> qddd) const;

 private:
  /// The segment holding @p t, after clamping @p t to [0, duration] (NaN → 0).
  std::size_t segment_at(double& t) const;

  std::vector<Eigen::VectorXd> q_, qd_;
  std::vector<QuinticTrajectory> segments_;
  std::vector<double> starts_;  // K + 1 entries: start of each segment, then the end
};

}  // namespace mjarm
