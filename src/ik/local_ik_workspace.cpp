#include "mjarm/ik/local_ik_workspace.hpp"

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

LocalIkWorkspace::LocalIkWorkspace(const Chain& chain, const LimitBias& limits,
                                   const Posture& posture, const CollisionSpec& collision,
                                   double null_space_damping, double max_step,
                                   double secondary_ratio, int max_backtracks)
    : chain_(chain),
      limits_(limits),
      posture_gain_(posture.gain),
      eps_sq_(null_space_damping * null_space_damping),
      max_step_(max_step),
      secondary_ratio_(secondary_ratio),
      max_backtracks_(max_backtracks),
      has_secondary_(limits.centre_gain > 0.0 || limits.repulsion_gain > 0.0 ||
                     posture.gain > 0.0) {
  q_pref_ = resolve_posture(chain_, posture);
  if (!collision.empty()) guard_ = std::make_unique<CollisionGuard>(chain_, collision);
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

void OptionCheck::operator()(bool ok, const char* name, double value, const char* expected) const {
  if (!ok) {
    throw Error(std::string(solver_) + " option " + name + " must be " + expected + ", got " +
                number_text(value));
  }
}

}  // namespace mjarm
