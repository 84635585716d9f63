#include "mjarm/trajectory/path/jerk_waypoints.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

// ṡ at path parameter s of a solved parameterization: x is linear in s on each grid step
double jerk_waypoint_speed(const TimeOptimalPath& topp, double s) {
  const Eigen::VectorXd& grid = topp.grid();
  const Eigen::VectorXd& x = topp.squared_speeds();
  const Eigen::Index N = grid.size() - 1;
  const double* begin = grid.data();
  const Eigen::Index i = std::clamp<Eigen::Index>(
      static_cast<Eigen::Index>(std::upper_bound(begin, begin + N + 1, s) - begin) - 1, 0, N - 1);
  const double xs = x[i] + 2.0 * topp.path_accelerations()[i] * (s - grid[i]);
  return std::sqrt(std::max(xs, 0.0));
}

}  // namespace

JerkWaypointTrajectory::JerkWaypointTrajectory(const TimeOptimalPath& topp,
                                               const Eigen::VectorXd& max_jerk,
                                               const JerkWaypointOptions& options) {
  check_fields(options);
  if (!topp.solved()) throw Error("jerk waypoints: the time-optimal path is not solved");
  const JointPath& path = topp.path();
  const Eigen::Index n = path.dofs();
  if (max_jerk.size() != n)
    throw Error("jerk waypoints: max_jerk has " + std::to_string(max_jerk.size()) +
                " entries, the path has " + std::to_string(n) + " joints");
  std::vector<JerkLimits> limits(static_cast<std::size_t>(n));
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!(max_jerk[j] > 0.0) || !std::isfinite(max_jerk[j]))
      throw Error("jerk waypoints: max_jerk[" + std::to_string(j) +
                  "] must be positive and finite, got " + number_text(max_jerk[j]));
    limits[static_cast<std::size_t>(j)] = {topp.max_velocity()[j], topp.max_acceleration()[j],
                                           max_jerk[j]};
  }
  const int count = path.waypoint_count();
  // the time-optimal path's velocity at each waypoint, within the limits
  velocities_.assign(static_cast<std::size_t>(count), Eigen::VectorXd::Zero(n));
  Eigen::VectorXd q(n), d1(n), d2(n);
  for (int k = 1; k + 1 < count; ++k) {
    const double s = path.knots()[k];
    path.evaluate(s, q, d1, d2);
    velocities_[static_cast<std::size_t>(k)] =
        (options.velocity_share * jerk_waypoint_speed(topp, s) * d1)
            .cwiseMax(-topp.max_velocity())
            .cwiseMin(topp.max_velocity());
  }
  std::vector<KinematicState> from(static_cast<std::size_t>(n)), to(static_cast<std::size_t>(n));
  // segment k from waypoint k to k + 1 at the waypoints' current velocities
  const auto join = [&](int k, JerkLimitedGenerator& generator) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      from[jj] = {path.waypoints()(j, k), velocities_[static_cast<std::size_t>(k)][j], 0.0};
      to[jj] = {path.waypoints()(j, k + 1), velocities_[static_cast<std::size_t>(k + 1)][j], 0.0};
    }
    const OtgResult result = generator.calculate(from, to);
    return result.status == OtgStatus::working || result.status == OtgStatus::finished;
  };
  for (int k = 0; k + 1 < count; ++k) {
    JerkLimitedGenerator generator(limits);
    Eigen::VectorXd& v_next = velocities_[static_cast<std::size_t>(k + 1)];
    for (int attempt = 0; !join(k, generator); ++attempt) {
      if (v_next.isZero())
        throw Error("jerk waypoints: segment " + std::to_string(k) + " failed (" +
                    to_string(generator.result().status) + ") even with a stop at waypoint " +
                    std::to_string(k + 1));
      if (attempt == 0) ++reduced_;
      v_next = attempt < options.retries ? Eigen::VectorXd(0.5 * v_next) : Eigen::VectorXd::Zero(n);
    }
    segments_.push_back(std::move(generator));
  }
  // a synchronized segment between two moving states can take longer than one through a stop:
  // an interior waypoint whose two segments are shorter with a stop there gets the stop (each
  // change shortens the whole, left to right, neighbours as they stand)
  for (int k = 1; k + 1 < count; ++k) {
    Eigen::VectorXd& v = velocities_[static_cast<std::size_t>(k)];
    if (v.isZero()) continue;
    const Eigen::VectorXd moving = v;
    v.setZero();
    JerkLimitedGenerator before(limits), after(limits);
    const auto kk = static_cast<std::size_t>(k);
    if (join(k - 1, before) && join(k, after) &&
        before.duration() + after.duration() <
            segments_[kk - 1].duration() + segments_[kk].duration()) {
      segments_[kk - 1] = std::move(before);
      segments_[kk] = std::move(after);
      ++stopped_;
    } else {
      v = moving;
    }
  }
  starts_.assign(1, 0.0);
  for (const JerkLimitedGenerator& segment : segments_)
    starts_.push_back(starts_.back() + segment.duration());
}

void JerkWaypointTrajectory::at(double t, TrajectorySample& sample) const {
  if (!(t > 0.0)) t = 0.0;  // also NaN
  t = std::min(t, duration());
  const auto it = std::upper_bound(starts_.begin() + 1, starts_.end() - 1, t);
  const auto k = static_cast<std::size_t>(it - starts_.begin()) - 1;
  segments_[k].at(t - starts_[k], sample);
}

}  // namespace mjarm
