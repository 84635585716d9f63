#include "mjarm/control/task_pd.hpp"

#include "control_checks.hpp"

namespace mjarm {

TaskPdController::TaskPdController(const Chain& chain, const TaskPdOptions& options)
    : options_(options), rows_(task_rows(options.mode)), dynamics_(chain) {
  using O = TaskPdOptions;
  check_fields(detail::ignored_rows_cleared(options, rows_, &O::stiffness, &O::damping), "task-pd");
}

void TaskPdController::compute(const mjData& data, const Reference& reference,
                               JointCommand& command) noexcept {
  command.kind = CommandKind::torque;
  const int n = dynamics_.size();
  if (command.value.size() != n) return;
  dynamics_.update(data);

  const TaskReference& task = reference.task;
  const Vector6d e = task_error(dynamics_.pose(), task.X_WE);
  const Vector6d e_dot = task.V_WE - dynamics_.velocity();
  wrench_ = options_.stiffness.cwiseProduct(e) + options_.damping.cwiseProduct(e_dot);

  auto tau = command.value.head(n);
  tau.noalias() = dynamics_.jacobian().topRows(rows_).transpose() * wrench_.head(rows_);
  if (options_.gravity_compensation) tau += dynamics_.gravity();
  if (options_.joint_damping > 0.0) tau -= options_.joint_damping * dynamics_.qd();

  values_[0] = e.head<3>().norm();
  values_[1] = rows_ == 6 ? e.tail<3>().norm() : 0.0;
}

}  // namespace mjarm
