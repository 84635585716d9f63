// Simulation::add_controller refuses a controller that compensates the bias forces itself when
// the position-mode simulation adds them too (they would count twice).

#include <gtest/gtest.h>

#include <string>

#include "mjarm/control/gravity_compensation.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/error.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {
namespace {

// Position targets straight from reference.joint.q; no compensation of its own.
class PlainTargets final : public Controller {
 public:
  explicit PlainTargets(const Chain& chain) : chain_(chain) {}
  std::string_view name() const noexcept override { return "plain-targets"; }
  CommandKind command_kind() const noexcept override { return CommandKind::position; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData&, const Reference& reference, JointCommand& command) noexcept override {
    command.kind = CommandKind::position;
    if (reference.joint.q.size() == command.value.size()) command.value = reference.joint.q;
  }

 private:
  Chain chain_;
};

SimulationOptions position_mode(bool gravity_compensation) {
  SimulationOptions options;
  options.mode = SimulationMode::position;
  options.gravity_compensation = gravity_compensation;
  return options;
}

TEST(BiasGuard, WhoCompensatesTheBias) {
  const Robot servo = Robot::bundled("panda");
  const Robot torque = Robot::bundled("panda_torque");
  EXPECT_TRUE(GravityCompensationController(Chain(servo, "attachment_site")).compensates_bias());
  EXPECT_FALSE(OperationalSpaceController(Chain(torque, "attachment_site")).compensates_bias());
  EXPECT_FALSE(PlainTargets(Chain(servo, "attachment_site")).compensates_bias());
}

TEST(BiasGuard, PositionModeWithGravityCompensationRefusesTheServoCompensation) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  Simulation sim(robot, position_mode(true));
  GravityCompensationController hold(chain);
  try {
    sim.add_controller(hold);
    FAIL() << "expected mjarm::Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("gravity-servo"), std::string::npos) << message;
    EXPECT_NE(message.find("gravity_compensation"), std::string::npos) << message;
  }
  // the refusal left the actuators free: a controller without compensation takes them
  PlainTargets plain(chain);
  EXPECT_NO_THROW(sim.add_controller(plain));
}

TEST(BiasGuard, AcceptedWithTheSimulationCompensationOff) {
  // that it then holds the arm on target: Simulation.PositionModeWithTheServoTargetCompensation…
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  Simulation sim(robot, position_mode(false));
  GravityCompensationController hold(chain);
  EXPECT_NO_THROW(sim.add_controller(hold));
  // and a plain position controller is accepted with the simulation's compensation on
  Simulation compensated(robot, position_mode(true));
  PlainTargets plain(chain);
  EXPECT_NO_THROW(compensated.add_controller(plain));
}

}  // namespace
}  // namespace mjarm
