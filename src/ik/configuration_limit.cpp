#include "mjarm/ik/configuration_limit.hpp"

#include <algorithm>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

ConfigurationLimit::ConfigurationLimit(const Chain& chain, const ConfigurationLimitOptions& options)
    : options_(options) {
  check_fields(options_);
  lower_ = chain.lower().array() + options_.margin;
  upper_ = chain.upper().array() - options_.margin;
  for (int i = 0; i < chain.size(); ++i) {
    if (!(lower_[i] < upper_[i])) {
      throw Error("configuration limit: margin " + number_text(options_.margin) +
                  " leaves no range to joint '" + chain.joint_names()[i] + "' [" +
                  number_text(chain.lower()[i]) + ", " + number_text(chain.upper()[i]) + "]");
    }
  }
}

int ConfigurationLimit::rows(const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                             Eigen::Ref<Eigen::MatrixXd> C,
                             Eigen::Ref<Eigen::VectorXd> b) noexcept {
  (void)q;
  (void)dt;
  (void)C;
  (void)b;
  return 0;
}

void ConfigurationLimit::tighten_box(const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                                     Eigen::Ref<Eigen::VectorXd> lo,
                                     Eigen::Ref<Eigen::VectorXd> hi) const noexcept {
  const double rate = options_.gain / dt;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    // inside the hard box [lo, hi], never empty: the hard limits win
    const double new_lo = std::clamp(rate * (lower_[i] - q[i]), lo[i], hi[i]);
    const double new_hi = std::clamp(rate * (upper_[i] - q[i]), new_lo, hi[i]);
    lo[i] = new_lo;
    hi[i] = new_hi;
  }
}

}  // namespace mjarm
