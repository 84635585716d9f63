#include "mjarm/trajectory/smooth_ramp_trajectory.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

void require_ramp_axes(const Eigen::VectorXd& start, const Eigen::VectorXd& goal) {
  if (start.size() == 0 || goal.size() != start.size())
    throw Error("smooth ramp trajectory: start and goal need the same number of axes (≥ 1), got " +
                std::to_string(start.size()) + " and " + std::to_string(goal.size()));
  for (Eigen::Index i = 0; i < start.size(); ++i)
    if (!std::isfinite(start[i]) || !std::isfinite(goal[i]))
      throw Error("smooth ramp trajectory: axis " + std::to_string(i) +
                  ": start and goal must be finite, got " + number_text(start[i]) + " and " +
                  number_text(goal[i]));
}

}  // namespace

SmoothRampTrajectory::SmoothRampTrajectory(SmoothRamp::Kind kind, const Eigen::VectorXd& start,
                                           const Eigen::VectorXd& goal, double duration)
    : kind_(kind), start_(start), duration_(duration) {
  require_ramp_axes(start, goal);
  delta_ = goal - start;
  const bool moves = (delta_.array() != 0.0).any();
  if (!std::isfinite(duration) || duration < 0.0 || (duration == 0.0 && moves))
    throw Error("smooth ramp trajectory: the duration must be " +
                std::string(moves ? "positive" : "≥ 0") + " and finite, got " +
                number_text(duration) + " s");
}

SmoothRampTrajectory SmoothRampTrajectory::within_limits(SmoothRamp::Kind kind,
                                                         const Eigen::VectorXd& start,
                                                         const Eigen::VectorXd& goal,
                                                         const Eigen::VectorXd& max_velocity,
                                                         const Eigen::VectorXd& max_acceleration) {
  require_ramp_axes(start, goal);
  const Eigen::Index n = start.size();
  if (max_velocity.size() != n || max_acceleration.size() != n)
    throw Error("smooth ramp trajectory: the limits need " + std::to_string(n) +
                " entries (one per axis), got " + std::to_string(max_velocity.size()) + " and " +
                std::to_string(max_acceleration.size()));
  // the slowest axis sets the duration; the first of equals keeps it
  double T = 0.0;
  Eigen::Index limiting = -1;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (const double limit : {max_velocity[i], max_acceleration[i]})
      if (!(limit > 0.0) || !std::isfinite(limit))
        throw Error("smooth ramp trajectory: axis " + std::to_string(i) +
                    ": the limits must be positive and finite, got max velocity " +
                    number_text(max_velocity[i]) + " and max acceleration " +
                    number_text(max_acceleration[i]));
    const double Ti = SmoothRamp::duration_for(kind, std::abs(goal[i] - start[i]), max_velocity[i],
                                               max_acceleration[i]);
    if (Ti > T) {
      T = Ti;
      limiting = i;
    }
  }
  SmoothRampTrajectory ramp(kind, start, goal, T);
  ramp.limiting_axis_ = limiting;
  return ramp;
}

void SmoothRampTrajectory::at(double t, TrajectorySample& sample) const {
  sample.resize(dofs());
  if (duration_ == 0.0) {  // nothing moves
    sample.position = start_;
    sample.velocity.setZero();
    sample.acceleration.setZero();
    sample.jerk.setZero();
    return;
  }
  const RampSample s = SmoothRamp(kind_, duration_).at(t);
  sample.position = start_ + s.s * delta_;
  sample.velocity = s.ds * delta_;
  sample.acceleration = s.dds * delta_;
  sample.jerk = s.ddds * delta_;
}

Eigen::VectorXd SmoothRampTrajectory::peak_velocity() const {
  if (duration_ == 0.0) return Eigen::VectorXd::Zero(dofs());
  return SmoothRamp::peak_slope(kind_) / duration_ * delta_.cwiseAbs();
}

Eigen::VectorXd SmoothRampTrajectory::peak_acceleration() const {
  if (duration_ == 0.0) return Eigen::VectorXd::Zero(dofs());
  return SmoothRamp::peak_curvature(kind_) / (duration_ * duration_) * delta_.cwiseAbs();
}

Eigen::VectorXd SmoothRampTrajectory::peak_jerk() const {
  if (duration_ == 0.0) return Eigen::VectorXd::Zero(dofs());
  const double T = duration_;
  return SmoothRamp::peak_jerk(kind_) / (T * T * T) * delta_.cwiseAbs();
}

}  // namespace mjarm
