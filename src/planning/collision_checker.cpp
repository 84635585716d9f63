#include "mjarm/planning/collision_checker.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {
constexpr double kLimitTolerance = 1e-9;  // round-off of clamped values
}  // namespace

CollisionChecker::CollisionChecker(const Chain& chain, double margin)
    : chain_(chain), contacts_(chain), margin_(margin) {
  if (!(margin >= 0.0) || !std::isfinite(margin))
    throw Error("collision checker: margin must be finite and >= 0 m, got " + number_text(margin));
  install_mujoco_handlers();
  data_ = chain.robot().make_data();
  const mjModel& m = chain.robot().model();
  fixed_qpos_ = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
}

void CollisionChecker::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  chain_.check_qpos(qpos, "fixed qpos");
  fixed_qpos_ = qpos;
}

bool CollisionChecker::valid(const double* q) noexcept {
  ++checks_;
  last_ = RobotContact{};
  limit_joint_ = -1;
  finite_ = true;
  const int n = chain_.size();
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(q[i])) {
      finite_ = false;
      return false;
    }
    if (limit_joint_ < 0 &&
        (q[i] < chain_.lower()[i] - kLimitTolerance || q[i] > chain_.upper()[i] + kLimitTolerance))
      limit_joint_ = i;
  }
  if (limit_joint_ >= 0) return false;
  const mjModel& m = chain_.robot().model();
  mjData& d = *data_;
  std::copy(fixed_qpos_.data(), fixed_qpos_.data() + m.nq, d.qpos);
  chain_.scatter(Eigen::Map<const Eigen::VectorXd>(q, n), d.qpos);
  mj_kinematics(&m, &d);
  mj_collision(&m, &d);
  last_ = contacts_.deepest(d, margin_);
  return !last_.found();
}

std::string CollisionChecker::describe_last() const {
  if (!finite_) return "the configuration holds NaN or infinity";
  if (limit_joint_ >= 0) {
    const int i = limit_joint_;
    return "joint '" + chain_.joint_names()[i] + "' outside its range [" +
           number_text(chain_.lower()[i]) + ", " + number_text(chain_.upper()[i]) + "]";
  }
  if (last_.found())
    return contacts_.geom_name(last_.geom1) + " of the robot touches " +
           contacts_.geom_name(last_.geom2) + " (distance " + number_text(last_.distance) + " m)";
  return "ok";
}

}  // namespace mjarm
