#include "mjarm/control/gravity_compensation.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

ServoBiasCompensation::ServoBiasCompensation(const Chain& chain, BiasTerm term)
    : term_(term), dynamics_(chain) {
  const Robot& robot = chain.robot();
  const mjModel& m = robot.model();
  const int n = chain.size();
  stiffness_.resize(n);
  for (int i = 0; i < n; ++i) {
    const std::string& joint = chain.joint_names()[i];
    const std::optional<int> actuator = chain.actuator(i);
    if (!actuator) {
      throw Error("ServoBiasCompensation: joint '" + joint + "' of model '" + robot.name() +
                  "' has no actuator (a position servo is expected)");
    }
    const ActuatorInfo info = robot.actuators().at(static_cast<std::size_t>(*actuator));
    const double kp = m.actuator_gainprm[*actuator * mjNGAIN];
    if (info.kind != ActuatorKind::position || !(kp > 0.0) || !std::isfinite(kp)) {
      throw Error("ServoBiasCompensation: actuator '" + info.name + "' of joint '" + joint +
                  "' is a " + to_string(info.kind) +
                  " actuator; a position servo with kp > 0 is expected (use a torque controller "
                  "such as GravityHoldController on motors)");
    }
    stiffness_[i] = info.gear * info.gear * kp;
  }
  bias_ = Eigen::VectorXd::Zero(n);
  offset_ = Eigen::VectorXd::Zero(n);
}

void ServoBiasCompensation::update(const mjData& data) noexcept {
  dynamics_.update(data);
  bias_ = term_ == BiasTerm::gravity ? dynamics_.gravity() : dynamics_.bias();
  offset_ = bias_.cwiseQuotient(stiffness_);
}

GravityCompensationController::GravityCompensationController(const Chain& chain, BiasTerm term)
    : compensation_(chain, term), hold_(Eigen::VectorXd::Zero(chain.size())) {}

void GravityCompensationController::compute(const mjData& data, const Reference& reference,
                                            JointCommand& command) noexcept {
  const Chain& chain = compensation_.chain();
  const int n = chain.size();
  if (command.value.size() != n) return;
  command.kind = CommandKind::position;
  if (!latched_) {
    for (int i = 0; i < n; ++i) hold_[i] = data.qpos[chain.qpos_address(i)];
    latched_ = true;
  }
  compensation_.update(data);
  command.value = reference.joint.q.size() == n ? reference.joint.q : hold_;
  compensation_.apply(command.value);
  values_ = {compensation_.bias().norm(), compensation_.offset().cwiseAbs().maxCoeff()};
}

GravityHoldController::GravityHoldController(const Chain& chain, BiasTerm term)
    : term_(term), dynamics_(chain) {}

void GravityHoldController::compute(const mjData& data, const Reference& /*reference*/,
                                    JointCommand& command) noexcept {
  if (command.value.size() != dynamics_.size()) return;
  command.kind = CommandKind::torque;
  dynamics_.update(data);
  command.value = term_ == BiasTerm::gravity ? dynamics_.gravity() : dynamics_.bias();
  values_[0] = command.value.norm();
}

}  // namespace mjarm
