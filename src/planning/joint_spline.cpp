#include "mjarm/planning/joint_spline.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

void check_knots(const std::vector<Eigen::VectorXd>& q, const char* what, Eigen::Index n) {
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (q[k].size() != n)
      throw Error(std::string("joint spline: ") + what + " " + std::to_string(k) + " has " +
                  std::to_string(q[k].size()) + " entries, expected " + std::to_string(n));
    if (!q[k].allFinite())
      throw Error(std::string("joint spline: ") + what + " " + std::to_string(k) +
                  " holds NaN or infinity");
  }
}

QuinticTrajectory::State knot_state(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  return {q, qd, Eigen::VectorXd::Zero(q.size())};
}

}  // namespace

JointSpline::JointSpline(const std::vector<Eigen::VectorXd>& q,
                         const std::vector<Eigen::VectorXd>& qd,
                         const std::vector<double>& durations)
    : q_(q), qd_(qd) {
  if (q.size() < 2)
    throw Error("joint spline: needs at least 2 knots, got " + std::to_string(q.size()));
  if (qd.size() != q.size() || durations.size() + 1 != q.size())
    throw Error("joint spline: " + std::to_string(q.size()) +
                " knots need as many velocities (got " + std::to_string(qd.size()) +
                ") and one duration fewer (got " + std::to_string(durations.size()) + ")");
  const Eigen::Index n = q.front().size();
  if (n == 0) throw Error("joint spline: knots have no joints");
  check_knots(q, "knot", n);
  check_knots(qd, "knot velocity", n);
  starts_.push_back(0.0);
  for (std::size_t k = 0; k < durations.size(); ++k) {
    if (!(durations[k] > 0.0) || !std::isfinite(durations[k]))
      throw Error("joint spline: duration of segment " + std::to_string(k) +
                  " must be positive and finite, got " + number_text(durations[k]));
    segments_.emplace_back(knot_state(q[k], qd[k]), knot_state(q[k + 1], qd[k + 1]), durations[k]);
    starts_.push_back(starts_.back() + durations[k]);
  }
}

std::vector<Eigen::VectorXd> JointSpline::blend_velocities(const std::vector<Eigen::VectorXd>& q,
                                                           const std::vector<double>& durations,
                                                           const std::vector<char>& blend,
                                                           const Eigen::VectorXd& max_velocity) {
  if (q.empty() || durations.size() + 1 != q.size() || blend.size() != q.size())
    throw Error("joint spline: blend_velocities needs K + 1 knots, K durations and K + 1 flags");
  const Eigen::Index n = q.front().size();
  if (max_velocity.size() != n)
    throw Error("joint spline: max_velocity has " + std::to_string(max_velocity.size()) +
                " entries, expected " + std::to_string(n));
  std::vector<Eigen::VectorXd> v(q.size(), Eigen::VectorXd::Zero(n));
  for (std::size_t k = 1; k + 1 < q.size(); ++k) {
    if (!blend[k] || !(durations[k - 1] > 0.0) || !(durations[k] > 0.0)) continue;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double before = (q[k][i] - q[k - 1][i]) / durations[k - 1];
      const double after = (q[k + 1][i] - q[k][i]) / durations[k];
      if (before * after <= 0.0) continue;
      v[k][i] = std::clamp(0.5 * (before + after), -max_velocity[i], max_velocity[i]);
    }
  }
  return v;
}

JointSpline JointSpline::timed(const std::vector<Eigen::VectorXd>& q,
                               const Eigen::VectorXd& max_velocity,
                               const Eigen::VectorXd& max_acceleration,
                               const std::vector<double>& floors, const std::vector<char>& blend) {
  if (q.size() < 2 || floors.size() + 1 != q.size() || blend.size() != q.size())
    throw Error("joint spline: timed needs K + 1 >= 2 knots, K floors and K + 1 blend flags");
  const Eigen::Index n = q.front().size();
  check_knots(q, "knot", n);
  const std::size_t K = floors.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  // rest-to-rest durations give the slopes of the heuristic
  std::vector<double> durations(K);
  for (std::size_t k = 0; k < K; ++k) {
    const QuinticDuration d =
        shortest_quintic_duration(knot_state(q[k], zero), knot_state(q[k + 1], zero), max_velocity,
                                  max_acceleration, floors[k]);
    if (d.status != QuinticDurationStatus::ok)
      throw Error("joint spline: segment " + std::to_string(k) + " has no rest-to-rest duration (" +
                  to_string(d.status) + ")");
    durations[k] = d.duration;
  }
  std::vector<char> flags = blend;
  std::vector<Eigen::VectorXd> v = blend_velocities(q, durations, flags, max_velocity);
  // each segment with its boundary velocities; an infeasible one stops at both ends (a
  // rest-to-rest segment always has a duration), which may change its neighbours: repeat
  for (std::size_t pass = 0; pass <= K + 1; ++pass) {
    bool changed = false;
    for (std::size_t k = 0; k < K; ++k) {
      const QuinticDuration d =
          shortest_quintic_duration(knot_state(q[k], v[k]), knot_state(q[k + 1], v[k + 1]),
                                    max_velocity, max_acceleration, floors[k]);
      if (d.status == QuinticDurationStatus::ok) {
        durations[k] = d.duration;
        continue;
      }
      v[k].setZero();
      v[k + 1].setZero();
      changed = true;
    }
    if (!changed) break;
  }
  return JointSpline(q, v, durations);
}

std::size_t JointSpline::segment_at(double& t) const {
  if (empty()) throw Error("joint spline: evaluated while empty");
  if (std::isnan(t)) t = 0.0;
  t = std::clamp(t, 0.0, duration());
  // the segment whose [start, end) holds t (the last one holds the end)
  const auto it = std::upper_bound(starts_.begin(), starts_.end(), t);
  std::size_t k = static_cast<std::size_t>(it - starts_.begin());
  k = k == 0 ? 0 : k - 1;
  return std::min(k, segments_.size() - 1);
}

void JointSpline::at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
                     Eigen::Ref<Eigen::VectorXd> qdd) const {
  const std::size_t k = segment_at(t);
  segments_[k].at(t - starts_[k], q, qd, qdd);
}

void JointSpline::at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
                     Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::VectorXd> qddd) const {
  const std::size_t k = segment_at(t);
  segments_[k].at(t - starts_[k], q, qd, qdd, qddd);
}

}  // namespace mjarm
