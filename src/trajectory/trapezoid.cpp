#include "mjarm/trajectory/trapezoid.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

// the message is built only on failure: a valid profile is made without heap allocation
void require_trapezoid_limit(double value, const char* what, Eigen::Index axis = -1) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(std::string(axis < 0 ? "trapezoid profile: " : "synced trapezoid: axis ") +
                (axis < 0 ? "" : std::to_string(axis) + " ") + what +
                " must be positive and finite, got " + number_text(value));
}

}  // namespace

TrapezoidProfile::TrapezoidProfile(double distance, double max_velocity, double max_acceleration)
    : distance_(distance), acceleration_(max_acceleration) {
  if (!(distance >= 0.0) || !std::isfinite(distance))
    throw Error("trapezoid profile: distance must be ≥ 0 and finite, got " +
                number_text(distance) + " (SyncedTrapezoid takes signed moves)");
  require_trapezoid_limit(max_velocity, "max velocity");
  require_trapezoid_limit(max_acceleration, "max acceleration");
  if (distance == 0.0) return;
  const double d_acc = max_velocity * max_velocity / (2.0 * max_acceleration);
  triangular_ = 2.0 * d_acc > distance;
  if (triangular_) {
    accel_time_ = std::sqrt(distance / max_acceleration);
    peak_velocity_ = max_acceleration * accel_time_;
  } else {
    accel_time_ = max_velocity / max_acceleration;
    cruise_time_ = (distance - 2.0 * d_acc) / max_velocity;
    peak_velocity_ = max_velocity;
  }
  duration_ = 2.0 * accel_time_ + cruise_time_;
  if (!std::isfinite(duration_) || !std::isfinite(peak_velocity_))
    throw Error("trapezoid profile: " + number_text(distance) + " at max velocity " +
                number_text(max_velocity) + " and max acceleration " +
                number_text(max_acceleration) + " takes longer than a double can hold");
}

TrapezoidProfile::Sample TrapezoidProfile::at(double t) const noexcept {
  Sample out;
  if (t >= duration_) {
    out.position = distance_;
    out.fraction = 1.0;
    return out;
  }
  if (!(t > 0.0)) return out;  // also NaN
  const double a = acceleration_;
  if (t < accel_time_) {
    out.position = 0.5 * a * t * t;
    out.velocity = a * t;
    out.acceleration = a;
  } else if (t < accel_time_ + cruise_time_) {
    out.position = 0.5 * a * accel_time_ * accel_time_ + peak_velocity_ * (t - accel_time_);
    out.velocity = peak_velocity_;
  } else {
    // deceleration, measured back from the end
    const double left = duration_ - t;
    out.position = distance_ - 0.5 * a * left * left;
    out.velocity = a * left;
    out.acceleration = -a;
  }
  out.fraction = out.position / distance_;
  return out;
}

TrapezoidProfile trap_profile(double distance, double max_velocity, double max_acceleration) {
  return TrapezoidProfile(distance, max_velocity, max_acceleration);
}

double trap_frac(const TrapezoidProfile& profile, double t) noexcept { return profile.fraction(t); }

SyncedTrapezoid::SyncedTrapezoid(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                                 double max_velocity, double max_acceleration)
    : SyncedTrapezoid(start, goal, Eigen::VectorXd::Constant(start.size(), max_velocity),
                      Eigen::VectorXd::Constant(start.size(), max_acceleration)) {}

SyncedTrapezoid::SyncedTrapezoid(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                                 const Eigen::VectorXd& max_velocity,
                                 const Eigen::VectorXd& max_acceleration)
    : start_(start), direction_(Eigen::VectorXd::Zero(start.size())) {
  const Eigen::Index n = start.size();
  if (n == 0) throw Error("synced trapezoid: no axes (start is empty)");
  if (goal.size() != n || max_velocity.size() != n || max_acceleration.size() != n)
    throw Error(
        "synced trapezoid: start, goal, max velocity and max acceleration must have the "
        "same size, got " +
        std::to_string(n) + ", " + std::to_string(goal.size()) + ", " +
        std::to_string(max_velocity.size()) + ", " + std::to_string(max_acceleration.size()));
  axes_.reserve(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(start[i]) || !std::isfinite(goal[i]))
      throw Error("synced trapezoid: axis " + std::to_string(i) +
                  " start and goal must be finite, got " + number_text(start[i]) + " and " +
                  number_text(goal[i]));
    require_trapezoid_limit(max_velocity[i], "max velocity", i);
    require_trapezoid_limit(max_acceleration[i], "max acceleration", i);
    const double move = goal[i] - start[i];
    direction_[i] = move > 0.0 ? 1.0 : (move < 0.0 ? -1.0 : 0.0);
    axes_.emplace_back(std::abs(move), max_velocity[i], max_acceleration[i]);
    if (axes_.back().duration() > duration_) {
      duration_ = axes_.back().duration();
      limiting_axis_ = static_cast<std::size_t>(i);
    }
  }
  scale_.reserve(axes_.size());
  for (const TrapezoidProfile& profile : axes_)
    scale_.push_back(duration_ > 0.0 ? profile.duration() / duration_ : 1.0);
}

void SyncedTrapezoid::at(double t, Eigen::Ref<Eigen::VectorXd> position,
                         Eigen::Ref<Eigen::VectorXd> velocity,
                         Eigen::Ref<Eigen::VectorXd> acceleration) const {
  const Eigen::Index n = start_.size();
  if (position.size() != n || velocity.size() != n || acceleration.size() != n)
    throw Error("synced trapezoid: outputs must have " + std::to_string(n) + " entries, got " +
                std::to_string(position.size()) + ", " + std::to_string(velocity.size()) + ", " +
                std::to_string(acceleration.size()));
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double lambda = scale_[k];
    // the axis's own profile run λ times slower; at t ≥ T every axis is at its goal
    const TrapezoidProfile::Sample s =
        t >= duration_ ? axes_[k].at(axes_[k].duration()) : axes_[k].at(lambda * t);
    position[i] = start_[i] + direction_[i] * s.position;
    velocity[i] = direction_[i] * lambda * s.velocity;
    acceleration[i] = direction_[i] * lambda * lambda * s.acceleration;
  }
}

double SyncedTrapezoid::fraction(double t) const noexcept {
  if (t >= duration_) return 1.0;
  return axes_[limiting_axis_].fraction(scale_[limiting_axis_] * t);
}

void TrapezoidProfile::at(double t, TrajectorySample& sample) const {
  sample.resize(1);
  const Sample s = at(t);
  sample.position[0] = s.position;
  sample.velocity[0] = s.velocity;
  sample.acceleration[0] = s.acceleration;
  sample.jerk[0] = 0.0;
}

void SyncedTrapezoid::at(double t, TrajectorySample& sample) const {
  sample.resize(dofs());
  at(t, sample.position, sample.velocity, sample.acceleration);
  sample.jerk.setZero();
}

}  // namespace mjarm
