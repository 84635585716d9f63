#include "mjarm/sim/actuator_binding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const char* command_words(CommandKind kind) {
  return kind == CommandKind::torque ? "torques" : "position targets";
}

ActuatorKind needed_kind(CommandKind kind) {
  return kind == CommandKind::torque ? ActuatorKind::motor : ActuatorKind::position;
}

}  // namespace

ActuatorBinding::ActuatorBinding(const Chain& chain, CommandKind kind, std::string_view owner)
    : kind_(kind) {
  const Robot& robot = chain.robot();
  const mjModel& m = robot.model();
  const std::vector<ActuatorInfo> infos = robot.actuators();
  const std::string who = "controller '" + std::string(owner) + "'";
  for (int i = 0; i < chain.size(); ++i) {
    const std::string& joint = chain.joint_names()[i];
    const std::optional<int> actuator = chain.actuator(i);
    if (!actuator) {
      throw Error(who + " writes " + command_words(kind) + ", but joint '" + joint + "' of model '" +
                  robot.name() + "' has no actuator");
    }
    const ActuatorInfo& info = infos[*actuator];
    if (info.kind != needed_kind(kind)) {
      throw Error(who + " writes " + command_words(kind) + ", which need a " +
                  to_string(needed_kind(kind)) + " actuator on joint '" + joint + "', but model '" +
                  robot.name() + "' drives it with actuator '" + info.name + "' of kind " +
                  to_string(info.kind) +
                  (kind == CommandKind::torque ? " (load the model's _torque flavour)"
                                               : " (load the model's position flavour)"));
    }
    const double gain = m.actuator_gainprm[*actuator * mjNGAIN];
    if (info.gear == 0.0 || gain == 0.0) {
      throw Error(who + ": actuator '" + info.name + "' on joint '" + joint +
                  "' has zero gear or gain, so it cannot move the joint");
    }
    double lower = info.ctrl_limited ? info.ctrl_lower : -kInf;
    double upper = info.ctrl_limited ? info.ctrl_upper : kInf;
    double scale = info.gear;  // position servo: ctrl is the actuator length gear·q
    if (kind == CommandKind::torque) {
      // joint torque = gear · actuator force = gear · gain · ctrl; the force limit applies to
      // gain · ctrl, so it bounds ctrl as well
      scale = 1.0 / (info.gear * gain);
      if (info.force_limited) {
        const double a = info.force_lower / gain;
        const double b = info.force_upper / gain;
        lower = std::max(lower, std::min(a, b));
        upper = std::min(upper, std::max(a, b));
      }
    }
    actuators_.push_back(*actuator);
    joint_names_.push_back(joint);
    scale_.push_back(scale);
    lower_.push_back(lower);
    upper_.push_back(upper);
  }
}

ApplyResult ActuatorBinding::apply(const JointCommand& command, double* ctrl,
                                   std::uint8_t* saturated) const noexcept {
  ApplyResult result;
  const int n = size();
  if (command.kind != kind_ || command.value.size() != n) {
    result.bad_index = -2;
    return result;
  }
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(command.value[i])) {
      result.bad_index = i;
      return result;
    }
  }
  for (int i = 0; i < n; ++i) {
    const double wanted = scale_[i] * command.value[i];
    const double clipped = std::clamp(wanted, lower_[i], upper_[i]);
    const int a = actuators_[i];
    ctrl[a] = clipped;
    saturated[a] = clipped != wanted ? 1 : 0;
    result.saturated += saturated[a];
  }
  return result;
}

}  // namespace mjarm
