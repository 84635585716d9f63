#include "mjarm/control/joint_limit_avoidance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/dynamics/task_space.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {
namespace {

/// Distance of @p q to its nearer limit and the sign that points away from that limit.
struct LimitSide {
  double distance;
  double away;  // −1: the upper limit is nearer (push down), +1: the lower one
};

LimitSide nearer_limit(double q, double lo, double hi) noexcept {
  const double up = hi - q, down = q - lo;
  return up <= down ? LimitSide{up, -1.0} : LimitSide{down, 1.0};
}

}  // namespace

JointLimitAvoidance::JointLimitAvoidance(const Chain& chain, const JointLimitOptions& options)
    : options_(options), lower_(chain.lower()), upper_(chain.upper()) {
  check_fields(options, "joint limits");
  // the margin must fit each range only when the term runs: off, any model is accepted
  for (int i = 0; i < chain.size() && options.enabled; ++i) {
    const double lo = lower_[i], hi = upper_[i];
    if (!std::isfinite(lo) || !std::isfinite(hi)) continue;
    if (!(2.0 * options.margin < hi - lo)) {
      throw Error("joint limits: margin " + number_text(options.margin) +
                  " must be less than half the range of joint '" + chain.joint_names()[i] + "' [" +
                  number_text(lo) + ", " + number_text(hi) + "]");
    }
  }
  const int n = chain.size();
  torque_.setZero(n);
  weight_.setZero(n);
  share_.setZero(n);
  applied_.setZero(n);
}

double JointLimitAvoidance::potential(const Eigen::Ref<const Eigen::VectorXd>& q) const noexcept {
  const double m = options_.margin, k = options_.gain;
  double u = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (!std::isfinite(lower_[i]) || !std::isfinite(upper_[i])) continue;
    const double d = nearer_limit(q[i], lower_[i], upper_[i]).distance;
    if (d < m) u += 0.5 * k * (m - d) * (m - d);
  }
  return u;
}

void JointLimitAvoidance::update(const Eigen::Ref<const Eigen::VectorXd>& q,
                                 const Eigen::Ref<const Eigen::VectorXd>& qd) noexcept {
  const double m = options_.margin, k = options_.gain, b = options_.damping;
  torque_.setZero();
  weight_.setZero();
  min_distance_ = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (!std::isfinite(lower_[i]) || !std::isfinite(upper_[i])) continue;
    const LimitSide side = nearer_limit(q[i], lower_[i], upper_[i]);
    const double d = side.distance;  // negative past the limit: the push keeps growing
    min_distance_ = std::min(min_distance_, d);
    if (!(d < m)) continue;
    const double s = smoothstep(1.0 - d / m).s;
    double tau = side.away * k * (m - d);
    // damp only the motion towards the limit: leaving it is never slowed
    if (qd[i] * side.away < 0.0) tau -= b * s * qd[i];
    torque_[i] = tau;
    weight_[i] = s;
  }
}

void JointLimitAvoidance::add_to(const TaskSpaceDynamics* task_space,
                                 Eigen::Ref<Eigen::VectorXd> tau) noexcept {
  if (task_space == nullptr) {
    applied_ = torque_;
  } else {
    share_.array() = (1.0 - weight_.array()) * torque_.array();
    task_space->project_torque(share_, applied_);
    applied_ += weight_.cwiseProduct(torque_);
  }
  tau += applied_;
}

}  // namespace mjarm
