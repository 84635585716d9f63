#pragma once
/// @file
/// The mode switch of the teleoperation sessions (`ViewerSession`, `TeleopSession`), written
/// once: one rig per `SimulationMode`, built on the model's own flavour (kinematic) or on its
/// position-servo / torque-motor variant; a mode whose rig cannot be built is unavailable, with
/// the reason kept; a switch carries the state over. What a rig holds is the session's own (its
/// `Rig` has at least `Robot robot`, `double period` and `std::unique_ptr<Simulation> sim`).

#include <array>
#include <functional>
#include <memory>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm::detail {

/// Calls @p build(model, mode) for each mode, kinematic first, with @p robot (kinematic) or its
/// variant of that flavour; a missing variant, or an `Error` from @p build, makes the mode's entry
/// of @p reasons say why (an error in kinematic mode is rethrown: the frame itself is wrong).
void build_mode_rigs(const Robot& robot, std::array<std::string, 3>& reasons,
                     const std::function<void(const Robot&, SimulationMode)>& build);

/// A mode switch: @p to takes @p from's state (qpos, qvel, time) when the models have the same
/// sizes (else it is reset), and its controllers are reset.
void carry_state(const Simulation& from, Simulation& to);

/// The rigs of a session, one per mode, and the mode in force.
template <class Rig>
class ModeRigs {
 public:
  /// Builds the rigs with @p make(model, mode) → `std::unique_ptr<Rig>` and selects @p initial.
  /// @throws Error "@p who: reason" when @p initial is unavailable, or what @p make throws in
  ///         kinematic mode.
  template <class Make>
  void build(const Robot& robot, SimulationMode initial, const char* who, Make&& make) {
    build_mode_rigs(robot, reasons_, [&](const Robot& model, SimulationMode mode) {
      rigs_[static_cast<int>(mode)] = make(model, mode);
    });
    require(initial, who);
    mode_ = initial;
  }

  SimulationMode mode() const noexcept { return mode_; }
  bool available(SimulationMode mode) const noexcept {
    const int m = static_cast<int>(mode);
    return m >= 0 && m < 3 && rigs_[m] != nullptr;
  }
  const std::string& unavailable_reason(SimulationMode mode) const noexcept {
    static const std::string none;
    const int m = static_cast<int>(mode);
    return m >= 0 && m < 3 ? reasons_[m] : none;
  }
  /// @throws Error "@p who: reason" when @p mode is unavailable.
  void require(SimulationMode mode, const char* who) const {
    if (!available(mode)) throw Error(std::string(who) + ": " + unavailable_reason(mode));
  }

  /// The rig of an available @p mode.
  const Rig& rig(SimulationMode mode) const noexcept { return *rigs_[static_cast<int>(mode)]; }
  Rig& current() noexcept { return *rigs_[static_cast<int>(mode_)]; }
  const Rig& current() const noexcept { return *rigs_[static_cast<int>(mode_)]; }

  /// Makes each available rig current in turn and calls @p f(rig) (e.g. to put every rig in the
  /// initial state, so that a switch before any motion is seamless); the mode in force is kept.
  template <class F>
  void for_each(F&& f) {
    const SimulationMode kept = mode_;
    for (int m = 0; m < 3; ++m) {
      if (rigs_[m] == nullptr) continue;
      mode_ = static_cast<SimulationMode>(m);
      f(*rigs_[m]);
    }
    mode_ = kept;
  }

  /// Switches to @p mode carrying the state over (`carry_state`).
  /// @return false when @p mode already is the one in force (nothing happens)
  /// @throws Error "@p who: reason" when @p mode is unavailable.
  bool switch_to(SimulationMode mode, const char* who) {
    if (mode == mode_) return false;
    require(mode, who);
    carry_state(*current().sim, *rigs_[static_cast<int>(mode)]->sim);
    mode_ = mode;
    return true;
  }

 private:
  std::array<std::unique_ptr<Rig>, 3> rigs_;
  std::array<std::string, 3> reasons_;
  SimulationMode mode_ = SimulationMode::kinematic;
};

}  // namespace mjarm::detail
