#include "mjarm/teleop/touch_finger_pd.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm {

TouchFingerPd::TouchFingerPd(const Chain& fingers, const TouchFingerPdOptions& options)
    : free_(options.free.expanded(fingers.size(), "TouchFingerPd (free gains)")),
      touch_(options.touch.expanded(fingers.size(), "TouchFingerPd (touch gains)")),
      max_force_(options.max_force),
      gravity_(options.gravity_compensation),
      dynamics_(fingers) {
  if (!(max_force_ > 0.0) || !std::isfinite(max_force_)) {
    throw Error("TouchFingerPd: max_force must be finite and > 0, got " +
                std::to_string(max_force_));
  }
  const mjModel& m = fingers.robot().model();
  for (int i = 0; i < fingers.size(); ++i) {
    if (!std::isfinite(fingers.lower()[i]) || !std::isfinite(fingers.upper()[i])) {
      throw Error("TouchFingerPd: finger joint '" + fingers.joint_names()[i] +
                  "' has no finite range");
    }
  }
  // the gripper: the parent body of the first finger, and everything below it
  finger_body_.assign(static_cast<std::size_t>(m.nbody), 0);
  own_body_.assign(static_cast<std::size_t>(m.nbody), 0);
  for (const int j : fingers.joint_ids()) finger_body_[m.jnt_bodyid[j]] = 1;
  const int hand = m.body_parentid[m.jnt_bodyid[fingers.joint_ids().front()]];
  for (int b = 1; b < m.nbody; ++b) {
    int a = b;
    while (a > 0 && a != hand) a = m.body_parentid[a];
    own_body_[b] = a == hand ? 1 : 0;
  }
}

void TouchFingerPd::reset() noexcept {
  fraction_ = 0.0;
  touching_ = false;
}

void TouchFingerPd::set_command(double closed) noexcept {
  if (!std::isnan(closed)) fraction_ = std::clamp(closed, 0.0, 1.0);
}

bool TouchFingerPd::touches(const mjData& data) const noexcept {
  const mjModel& m = dynamics_.chain().robot().model();
  for (int c = 0; c < data.ncon; ++c) {
    const mjContact& k = data.contact[c];
    const int b1 = m.geom_bodyid[k.geom1], b2 = m.geom_bodyid[k.geom2];
    if ((finger_body_[b1] && !own_body_[b2]) || (finger_body_[b2] && !own_body_[b1])) return true;
  }
  return false;
}

void TouchFingerPd::compute(const mjData& data, const Reference&, JointCommand& command) noexcept {
  const Chain& chain = dynamics_.chain();
  const int n = chain.size();
  if (command.value.size() != n) return;
  command.kind = CommandKind::torque;
  touching_ = touches(data);
  const JointPdGains& gains = touching_ ? touch_ : free_;
  if (gravity_) dynamics_.update(data);
  double squeeze = 0.0;
  for (int i = 0; i < n; ++i) {
    const double target = chain.upper()[i] + fraction_ * (chain.lower()[i] - chain.upper()[i]);
    const double e = target - data.qpos[chain.qpos_address(i)];
    const double tau = gains.kp[i] * e - gains.kd[i] * data.qvel[chain.dof_address(i)] +
                       (gravity_ ? dynamics_.gravity()[i] : 0.0);
    command.value[i] = std::clamp(tau, -max_force_, max_force_);
    squeeze += std::abs(command.value[i]);
  }
  values_ = {fraction_, touching_ ? 1.0 : 0.0, squeeze / n};
}

}  // namespace mjarm
