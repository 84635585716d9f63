#include "mjarm/ik/local_ik_workspace.hpp"

#include <Eigen/Cholesky>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

LocalIkWorkspace::LocalIkWorkspace(const Chain& chain, const LocalIkSettings& settings)
    : chain_(chain),
      limits_(settings.limits),
      posture_gain_(settings.posture.gain),
      eps_sq_(settings.null_space_damping * settings.null_space_damping),
      max_step_(settings.max_step),
      secondary_ratio_(settings.secondary_ratio),
      max_backtracks_(settings.max_backtracks),
      has_secondary_(settings.limits.centre_gain > 0.0 || settings.limits.repulsion_gain > 0.0 ||
                     settings.posture.gain > 0.0) {
  q_pref_ = resolve_posture(chain_, settings.posture);
  if (!settings.collision.empty()) {
    guard_ = std::make_unique<CollisionGuard>(chain_, settings.collision);
  }
  const int n = chain_.size();
  for (Eigen::VectorXd* v :
       {&q_, &q_best_, &q_try_, &dq_, &bias_, &projected_, &locked_, &dq_locked_}) {
    v->setZero(n);
  }
}

void LocalIkWorkspace::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  if (guard_) guard_->set_fixed_qpos(qpos);
}

void LocalIkWorkspace::start(const Eigen::Ref<const Eigen::VectorXd>& q_seed, std::string_view what,
                             IkResult& result) {
  chain_.check(q_seed, what);
  q_ = q_seed;
  clamp_to_limits(chain_, q_);
  if (guard_ && guard_->in_contact(q_)) {
    throw Error(std::string(what) + " is in contact: " + guard_->describe_contacts(q_));
  }
  if (result.q.size() != chain_.size()) result.q.resize(chain_.size());
}

void LocalIkWorkspace::update_secondary() noexcept {
  if (!has_secondary_) return;
  bias_.setZero();
  add_limit_bias(chain_, limits_, q_, bias_);
  add_posture_pull(q_pref_, posture_gain_, q_, bias_);
}

template <int Rows>
bool LocalIkWorkspace::damped_task_step(
    const Eigen::Matrix<double, Rows, Eigen::Dynamic>& J,
    const Eigen::Matrix<double, Rows, 1>& target, double lambda_sq,
    Eigen::Matrix<double, Rows, Eigen::Dynamic>& J_free) noexcept {
  using Square = Eigen::Matrix<double, Rows, Rows>;
  using Column = Eigen::Matrix<double, Rows, 1>;
  return limited_step(
      [&](const Eigen::VectorXd& locked, const Eigen::VectorXd& dq_locked, Eigen::VectorXd& dq) {
        J_free = J;
        for (int i = 0; i < chain_.size(); ++i) {
          if (locked[i] != 0.0) J_free.col(i).setZero();
        }
        const Column r = target - J * dq_locked;
        Square A = J_free * J_free.transpose();
        A.diagonal().array() += lambda_sq;
        dq.noalias() = J_free.transpose() * A.llt().solve(r);
        if (has_secondary_) {
          projected_ = bias_.cwiseProduct((1.0 - locked.array()).matrix());
          Square N = J_free * J_free.transpose();
          N.diagonal().array() += eps_sq_;
          const Column z = N.ldlt().solve(J_free * projected_);
          projected_.noalias() -= J_free.transpose() * z;
          dq += secondary_scale(dq.norm(), projected_.norm(), secondary_ratio_) * projected_;
        }
        dq += dq_locked;
      });
}

// the task sizes of PositionIk (3) and PoseIk (6)
template bool LocalIkWorkspace::damped_task_step<3>(
    const Eigen::Matrix<double, 3, Eigen::Dynamic>&, const Eigen::Matrix<double, 3, 1>&, double,
    Eigen::Matrix<double, 3, Eigen::Dynamic>&) noexcept;
template bool LocalIkWorkspace::damped_task_step<6>(
    const Eigen::Matrix<double, 6, Eigen::Dynamic>&, const Eigen::Matrix<double, 6, 1>&, double,
    Eigen::Matrix<double, 6, Eigen::Dynamic>&) noexcept;

}  // namespace mjarm
