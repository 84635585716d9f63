#include "mjarm/planning/planned_reference.hpp"

#include <cmath>
#include <utility>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

/// The joints of a trajectory (0 when it is empty or not solved).
Eigen::Index planned_joints(const JointSpline& spline) { return spline.size(); }
Eigen::Index planned_joints(const TimeOptimalPath& path) { return path.solved() ? path.dofs() : 0; }

}  // namespace

PlannedReference::PlannedReference(const Chain& chain, TimeOptimalPath trajectory, double hold_time,
                                   double velocity_lag)
    : PlannedReference(chain, JointSpline{}, hold_time, velocity_lag, std::move(trajectory)) {}

PlannedReference::PlannedReference(const Chain& chain, JointSpline trajectory, double hold_time,
                                   double velocity_lag)
    : PlannedReference(chain, std::move(trajectory), hold_time, velocity_lag, std::nullopt) {}

PlannedReference::PlannedReference(const Chain& chain, JointSpline spline, double hold_time,
                                   double velocity_lag, std::optional<TimeOptimalPath> path)
    : chain_(chain),
      trajectory_(std::move(spline)),
      hold_time_(hold_time),
      velocity_lag_(velocity_lag),
      reference_kin_(chain),
      state_kin_(chain) {
  if (path) trajectory_ = std::move(*path);
  const Eigen::Index joints =
      std::visit([](const auto& trajectory) { return planned_joints(trajectory); }, trajectory_);
  if (joints == 0) throw Error("planned reference: the trajectory is empty (or not solved)");
  if (joints != chain.size())
    throw Error("planned reference: the trajectory has " + std::to_string(joints) +
                " joints, the chain " + std::to_string(chain.size()));
  duration_ = std::visit([](const auto& trajectory) { return trajectory.duration(); }, trajectory_);
  sample_.resize(joints);
  if (!(hold_time >= 0.0) || !std::isfinite(hold_time))
    throw Error("planned reference: hold_time must be finite and >= 0 [s], got " +
                number_text(hold_time));
  if (!(velocity_lag >= 0.0) || !std::isfinite(velocity_lag))
    throw Error("planned reference: velocity_lag must be finite and >= 0 [s], got " +
                number_text(velocity_lag));
  const int n = chain.size();
  J_ = Matrix6Xd::Zero(6, n);
  q_ = qd_ = qdd_ = lagged_q_ = lagged_qdd_ = state_q_ = Eigen::VectorXd::Zero(n);
}

void PlannedReference::reset() noexcept {
  started_ = false;
  sum_squares_ = 0.0;
  tracking_ = TrackingError{};
}

void PlannedReference::sample(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd,
                              Eigen::VectorXd& qdd) noexcept {
  if (const JointSpline* spline = std::get_if<JointSpline>(&trajectory_)) {
    spline->at(t, q, qd, qdd);  // sizes fit: never throws
    return;
  }
  std::get<TimeOptimalPath>(trajectory_).at(t, sample_);  // sized: allocates nothing
  q = sample_.position;
  qd = sample_.velocity;
  qdd = sample_.acceleration;
}

void PlannedReference::evaluate(double t, Reference& reference) noexcept {
  const int n = chain_.size();
  sample(t, q_, qd_, qdd_);
  if (velocity_lag_ > 0.0) sample(t - velocity_lag_, lagged_q_, qd_, lagged_qdd_);
  JointReference& joint = reference.joint;
  if (joint.q.size() != n) {  // the first tick sizes the reference
    joint.q.resize(n);
    joint.qd.resize(n);
    joint.qdd.resize(n);
  }
  joint.q = q_;
  joint.qd = qd_;
  joint.qdd = qdd_;
  TaskReference& task = reference.task;
  task.X_WE = reference_kin_.update(q_);
  reference_kin_.jacobian(J_);
  task.V_WE.noalias() = J_ * qd_;
  task.A_WE.noalias() = J_ * qdd_;
  task.A_WE += reference_kin_.bias_acceleration(qd_);
  task.F_ext.setZero();
}

bool PlannedReference::update(const mjData& data, Reference& reference) noexcept {
  if (!started_) {
    started_ = true;
    t0_ = data.time;
  }
  const double t = data.time - t0_;
  evaluate(t, reference);
  // tracking: E in the simulated state against the reference
  for (int i = 0; i < chain_.size(); ++i) state_q_[i] = data.qpos[chain_.qpos_address(i)];
  const Pose& X_WE = state_kin_.update(state_q_);
  const double position = (reference.task.X_WE.p - X_WE.p).norm();
  const double orientation = so3::angle(reference.task.X_WE.R.transpose() * X_WE.R);
  ++tracking_.ticks;
  sum_squares_ += position * position;
  tracking_.max_position = std::max(tracking_.max_position, position);
  tracking_.max_orientation = std::max(tracking_.max_orientation, orientation);
  tracking_.rms_position = std::sqrt(sum_squares_ / static_cast<double>(tracking_.ticks));
  tracking_.final_position = position;
  tracking_.final_orientation = orientation;
  return t <= run_time();
}

}  // namespace mjarm
