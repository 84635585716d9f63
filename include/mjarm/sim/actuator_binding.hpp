#pragma once
/// @file
/// `ActuatorBinding`: how one controller's `JointCommand` (chain order) becomes actuator inputs.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/command.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// Outcome of `ActuatorBinding::apply`.
struct ApplyResult {
  /// −1 when the command was applied; otherwise the chain index of the first non-finite value
  /// (nothing is written then). −2 when the command has the wrong size or kind.
  int bad_index = -1;
  int saturated = 0;  ///< how many actuators were clipped this time
  bool ok() const noexcept { return bad_index == -1; }
};

/// Maps a command for a chain onto the actuators of its joints (`Chain::actuator(i)`):
/// - torque: needs a motor on every joint; ctrl = τ ÷ (gear·gain), so the joint receives τ;
/// - position: needs a position servo on every joint; ctrl = gear·q_target.
/// The ctrl value is clipped to ctrlrange (and, for motors, to forcerange ÷ gain) and the
/// clipping is reported per actuator.
class ActuatorBinding {
 public:
  /// @param chain joints commanded, in command order
  /// @param kind what the command holds
  /// @param owner who commands (a controller's name), for error messages
  /// @throws Error naming the joint, its actuator and the actuator's kind when a joint has no
  ///         actuator or one that does not fit @p kind.
  ActuatorBinding(const Chain& chain, CommandKind kind, std::string_view owner);

  CommandKind kind() const noexcept { return kind_; }
  /// Number of joints (= command entries = actuators).
  int size() const noexcept { return static_cast<int>(actuators_.size()); }
  /// Actuator id driven by command entry i.
  const std::vector<int>& actuators() const noexcept { return actuators_; }
  /// Joint names, in command order.
  const std::vector<std::string>& joint_names() const noexcept { return joint_names_; }

  /// Writes ctrl[actuator(i)] for every entry and sets saturated[actuator(i)] to 1 when it was
  /// clipped, 0 otherwise. Writes nothing when a value is NaN/inf or the command does not fit.
  /// @param ctrl the model's ctrl array (nu entries)
  /// @param saturated one flag per actuator (nu entries)
  ApplyResult apply(const JointCommand& command, double* ctrl,
                    std::uint8_t* saturated) const noexcept;

 private:
  CommandKind kind_;
  std::vector<int> actuators_;
  std::vector<std::string> joint_names_;
  std::vector<double> scale_;  // ctrl = scale·value
  std::vector<double> lower_;  // ctrl bounds (∓inf when unlimited)
  std::vector<double> upper_;
};

}  // namespace mjarm
