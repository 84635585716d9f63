#include "mjarm/ik/local_ik_workspace.hpp"

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

}  // namespace mjarm
