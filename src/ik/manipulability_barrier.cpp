#include "mjarm/ik/manipulability_barrier.hpp"

namespace mjarm {

ManipulabilityBarrier::ManipulabilityBarrier(const Chain& chain,
                                             const ManipulabilityBarrierOptions& options)
    : options_((check_fields(options), options)),
      manip_(chain, ManipulabilityOptions{.block = options.block}),
      gradient_(Eigen::VectorXd::Zero(chain.size())) {}

int ManipulabilityBarrier::rows(const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                                Eigen::Ref<Eigen::MatrixXd> C,
                                Eigen::Ref<Eigen::VectorXd> b) noexcept {
  const ManipulabilityResult& r = manip_.evaluate(q, gradient_);  // q checked by the caller
  if (r.status == SingularityStatus::singular) return 0;          // no gradient to hold on to
  C.row(0) = gradient_.transpose();
  b[0] = -options_.gain / dt * (r.manipulability - options_.min_manipulability);
  return 1;
}

void ManipulabilityBarrier::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  manip_.kinematics().set_fixed_qpos(qpos);
}

}  // namespace mjarm
