#include "mjarm/teleop/viewer_controllers.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

JointTargetController::JointTargetController(const Chain& chain) : chain_(chain) {}

void JointTargetController::compute(const mjData&, const Reference& reference,
                                    JointCommand& command) noexcept {
  if (command.value.size() != chain_.size() || reference.joint.q.size() != chain_.size()) return;
  command.kind = CommandKind::position;
  command.value = reference.joint.q;
}

GripperTargetController::GripperTargetController(const Chain& chain) : chain_(chain) {
  for (int i = 0; i < chain_.size(); ++i) {
    if (!std::isfinite(chain_.lower()[i]) || !std::isfinite(chain_.upper()[i])) {
      throw Error("gripper: joint '" + chain_.joint_names()[static_cast<std::size_t>(i)] +
                  "' has no range; the gripper maps 0…1 onto each joint's range");
    }
  }
}

void GripperTargetController::targets(double closed, Eigen::Ref<Eigen::VectorXd> q) const noexcept {
  const double g = std::isfinite(closed) ? std::clamp(closed, 0.0, 1.0) : 0.0;
  for (int i = 0; i < chain_.size(); ++i) {
    q[i] = chain_.upper()[i] + g * (chain_.lower()[i] - chain_.upper()[i]);
  }
}

void GripperTargetController::compute(const mjData&, const Reference& reference,
                                      JointCommand& command) noexcept {
  if (command.value.size() != chain_.size()) return;
  command.kind = CommandKind::position;
  targets(reference.gripper, command.value);
}

}  // namespace mjarm
