#pragma once

#include <Eigen/Core>

#include "mjarm/fields.hpp"

namespace mjarm {

/// What a controller's output means to the simulation.
enum class CommandKind {
  torque,   ///< generalized forces on the chain's dofs [N·m or N]; sent to motors as τ ÷ gear
  position  ///< position targets for the chain's joints [rad or m]; sent to position servos
};

constexpr auto declared_names(const CommandKind*) {
  return std::array{EnumName{CommandKind::torque, "torque", "generalized forces on the dofs"},
                    EnumName{CommandKind::position, "position", "position targets of the joints"}};
}

/// A controller's output for one control tick: one value per joint of the controller's `Chain`,
/// in chain order. The simulation turns it into actuator inputs (clipped to ctrlrange, with the
/// saturation reported).
struct JointCommand {
  CommandKind kind = CommandKind::torque;
  Eigen::VectorXd value;  ///< size chain.size()
};

}  // namespace mjarm
