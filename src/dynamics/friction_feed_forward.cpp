#include "mjarm/dynamics/friction_feed_forward.hpp"

#include <cmath>

namespace mjarm {
FrictionFeedForwardOptions friction_options_for(bool controller_cancels_passive,
                                                FrictionMode mode) noexcept {
  FrictionFeedForwardOptions options;
  options.mode = mode;
  options.damping = controller_cancels_passive ? DampingCompensation::by_controller
                                               : DampingCompensation::feed_forward;
  return options;
}

FrictionFeedForward::FrictionFeedForward(const Chain& chain, FrictionFeedForwardOptions options)
    : options_(options) {
  check_fields(options_);
  const mjModel& m = chain.robot().model();
  const int n = chain.size();
  friction_.resize(n);
  damping_.resize(n);
  for (int i = 0; i < n; ++i) {
    friction_[i] = m.dof_frictionloss[chain.dof_address(i)];
    damping_[i] = m.dof_damping[chain.dof_address(i)];
  }
}

bool FrictionFeedForward::active() const noexcept {
  const bool damp =
      options_.damping == DampingCompensation::feed_forward && (damping_.array() != 0.0).any();
  return damp || (friction_.array() != 0.0).any();
}

void FrictionFeedForward::apply(const Eigen::Ref<const Eigen::VectorXd>& qd,
                                Eigen::Ref<Eigen::VectorXd> tau) const noexcept {
  const bool add_damping = options_.damping == DampingCompensation::feed_forward;
  const bool torque_mode = options_.mode == FrictionMode::torque;
  for (Eigen::Index i = 0; i < friction_.size(); ++i) {
    const double f = friction_[i];
    // every term is skipped, not added as zero, so a frictionless dof stays bit-identical
    double extra = 0.0;
    bool touched = false;
    if (f != 0.0) {
      extra = torque_mode ? f * std::tanh(options_.torque_sharpness * tau[i] / f)
                          : f * std::tanh(qd[i] / options_.velocity_scale);
      touched = true;
    }
    if (add_damping && damping_[i] != 0.0) {
      extra += damping_[i] * qd[i];
      touched = true;
    }
    if (touched) tau[i] += extra;
  }
}

void FrictionFeedForward::model_force(const Eigen::Ref<const Eigen::VectorXd>& qd,
                                      Eigen::Ref<Eigen::VectorXd> out) const noexcept {
  for (Eigen::Index i = 0; i < friction_.size(); ++i) {
    const double f = friction_[i];
    out[i] = -damping_[i] * qd[i];
    if (f != 0.0) out[i] -= f * std::tanh(qd[i] / options_.velocity_scale);
  }
}

}  // namespace mjarm
