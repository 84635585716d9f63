#include "mjarm/control/acceleration_control.hpp"

#include <Eigen/Cholesky>

#include "control_checks.hpp"

namespace mjarm {

struct AccelerationController::Factor {
  Eigen::LLT<Small> llt;
};

AccelerationController::AccelerationController(const Chain& chain,
                                               const AccelerationControlOptions& options)
    : options_(options),
      rows_(task_rows(options.mode)),
      dynamics_(chain),
      llt_(make_workspace<Factor>()) {
  using O = AccelerationControlOptions;
  check_fields(detail::ignored_rows_cleared(options, rows_, &O::stiffness, &O::damping), "accel");
  const int n = dynamics_.size();
  const int k = std::min(rows_, n);  // size of the Gram matrix
  J_.setZero(rows_, n);
  gram_.setZero(k, k);
  small_.setZero(6);
  qdd_.setZero(n);
  qdd0_.setZero(n);
  task_.setZero(rows_);
  back_.setZero(n);
  passive_.setZero(n);
}

AccelerationController::~AccelerationController() = default;
AccelerationController::AccelerationController(const AccelerationController& other) = default;
AccelerationController& AccelerationController::operator=(const AccelerationController& other) =
    default;
AccelerationController::AccelerationController(AccelerationController&& other) noexcept = default;
AccelerationController& AccelerationController::operator=(AccelerationController&& other) noexcept =
    default;

void AccelerationController::apply_pinv(const Eigen::Ref<const Eigen::VectorXd>& y,
                                        Eigen::Ref<Eigen::VectorXd> x) noexcept {
  if (rows_ <= J_.cols()) {
    // J⁺·y = Jᵀ·(J·Jᵀ + λ²I)⁻¹·y
    small_.head(rows_) = llt_->llt.solve(y);
    x.noalias() = J_.transpose() * small_.head(rows_);
  } else {
    // J⁺·y = (Jᵀ·J + λ²I)⁻¹·Jᵀ·y
    const auto n = J_.cols();
    small_.head(n).noalias() = J_.transpose() * y;
    x = llt_->llt.solve(small_.head(n));
  }
}

void AccelerationController::compute(const mjData& data, const Reference& reference,
                                     JointCommand& command) noexcept {
  command.kind = CommandKind::torque;
  const int n = dynamics_.size();
  if (command.value.size() != n) return;
  dynamics_.update(data);
  const auto& qd = dynamics_.qd();

  // desired task acceleration, minus the part the current velocity already produces
  const TaskReference& task = reference.task;
  const Vector6d e = task_error(dynamics_.pose(), task.X_WE);
  const Vector6d e_dot = task.V_WE - dynamics_.velocity();
  xdd_ = task.A_WE + options_.stiffness.cwiseProduct(e) + options_.damping.cwiseProduct(e_dot);
  task_ = xdd_.head(rows_) - dynamics_.bias_acceleration().head(rows_);

  // damped least-squares inverse: Gram matrix, manipulability from its Cholesky factor
  J_ = dynamics_.jacobian().topRows(rows_);
  if (rows_ <= n) {
    gram_.noalias() = J_ * J_.transpose();
  } else {
    gram_.noalias() = J_.transpose() * J_;
  }
  llt_->llt.compute(gram_);
  double w = 0.0;
  if (llt_->llt.info() == Eigen::Success) w = llt_->llt.matrixLLT().diagonal().prod();
  const double w0 = options_.manipulability_threshold;
  double lambda = w < w0 ? options_.max_damping * (1.0 - w / w0) : 0.0;
  if (lambda > 0.0 || llt_->llt.info() != Eigen::Success) {
    // a singular Gram matrix with no damping allowed still gets a tiny regularization
    const double lambda2 = lambda > 0.0 ? lambda * lambda : 1e-12;
    gram_.diagonal().array() += lambda2;
    llt_->llt.compute(gram_);
    lambda = std::sqrt(lambda2);
  }
  apply_pinv(task_, qdd_);

  // null-space motion: damping (and posture) filtered through I − J⁺J
  qdd0_ = -options_.nullspace_damping * qd;
  const auto& q_ref = reference.joint.q;
  if (options_.nullspace_stiffness > 0.0 && q_ref.size() == n) {
    qdd0_ += options_.nullspace_stiffness * (q_ref - dynamics_.q());
  }
  task_.noalias() = J_ * qdd0_;
  apply_pinv(task_, back_);
  qdd_ += qdd0_ - back_;

  // inverse dynamics
  auto tau = command.value.head(n);
  dynamics_.inverse_dynamics(data, qdd_, tau);
  if (options_.compensate_passive) {
    detail::read_passive(dynamics_.chain(), data, passive_);
    tau -= passive_;
  }

  values_[0] = e.head<3>().norm();
  values_[1] = rows_ == 6 ? e.tail<3>().norm() : 0.0;
  values_[2] = w;
  values_[3] = lambda;
}

}  // namespace mjarm
