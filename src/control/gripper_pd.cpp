#include "mjarm/control/gripper_pd.hpp"

#include <algorithm>
#include <cmath>

#include "control_checks.hpp"

namespace mjarm {
namespace {

const GripperPdOptions& gripper_checked(const GripperPdOptions& options) {
  check_fields(options, "gripper-pd");
  return options;
}

}  // namespace

GripperPdController::GripperPdController(const Chain& fingers, const GripperPdOptions& options)
    : gains_(gripper_checked(options).gains.expanded(fingers.size(), "gripper-pd")),
      max_force_(options.max_force),
      gravity_(options.gravity_compensation),
      dynamics_(fingers),
      open_(detail::finger_stroke_end(fingers, options.open, true, "gripper-pd", "open")),
      closed_(detail::finger_stroke_end(fingers, options.closed, false, "gripper-pd", "closed")) {}

void GripperPdController::compute(const mjData& data, const Reference& reference,
                                  JointCommand& command) noexcept {
  const Chain& chain = dynamics_.chain();
  const int n = chain.size();
  if (command.value.size() != n) return;
  command.kind = CommandKind::torque;
  if (!std::isnan(reference.gripper)) fraction_ = std::clamp(reference.gripper, 0.0, 1.0);
  if (gravity_) dynamics_.update(data);
  double e2 = 0.0;
  int saturated = 0;
  for (int i = 0; i < n; ++i) {
    const double target = open_[i] + fraction_ * (closed_[i] - open_[i]);
    const double e = target - data.qpos[chain.qpos_address(i)];
    const double tau = gains_.kp[i] * e - gains_.kd[i] * data.qvel[chain.dof_address(i)] +
                       (gravity_ ? dynamics_.gravity()[i] : 0.0);
    command.value[i] = std::clamp(tau, -max_force_, max_force_);
    saturated += std::abs(tau) > max_force_ ? 1 : 0;
    e2 += e * e;
  }
  values_ = {fraction_, std::sqrt(e2), static_cast<double>(saturated)};
}

}  // namespace mjarm
