#pragma once
/// @file
/// The controllers of the pick and place: inverse kinematics every control tick into servo
/// targets (position mode, as the classic teaching code does), operational-space impedance
/// (torque mode), and the fingers.

#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "mjarm/control/controller.hpp"
#include "mjarm/control/finger_force.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/sim/simulation_options.hpp"

namespace mjarm {

struct PickPlaceScene;

/// Position mode: every tick, pose IK of the chain's frame to reference.task.X_WE, seeded with
/// the previous tick's solution (the current joints on the first tick after `reset`), and the
/// solution sent as the servos' targets. A few damped-least-squares iterations per tick: the
/// reference moves a fraction of a millimetre between ticks.
///
/// Internals: position_error [m], orientation_error [rad] (of the IK solution to the reference),
/// iterations.
class IkServoController final : public Controller {
 public:
  /// @throws Error for invalid IK options.
  explicit IkServoController(const Chain& arm, const PoseIkOptions& options = default_options());

  /// 20 iterations at most, tolerances 1e-7 m and 1e-6 rad, no backtracking beyond 2 halvings.
  static PoseIkOptions default_options();

  std::string_view name() const noexcept override { return "ik-servo"; }
  CommandKind command_kind() const noexcept override { return CommandKind::position; }
  const Chain& chain() const noexcept override { return ik_.chain(); }
  /// One tick. A reference pose that is not finite keeps the previous targets.
  void compute(const mjData& data, const Reference& reference,
               JointCommand& command) noexcept override;
  void reset() noexcept override { seeded_ = false; }

  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  PoseIk ik_;
  IkResult result_;
  Eigen::VectorXd seed_;
  bool seeded_ = false;
  std::array<std::string, 3> names_{"position_error", "orientation_error", "iterations"};
  std::array<double, 3> values_{};
};

/// The arm controller of a mode: `IkServoController` (position) or an
/// `OperationalSpaceController` in pose mode with the gains the figures in docs/pick_place.md
/// were measured with (torque).
std::unique_ptr<Controller> make_pick_place_arm_controller(const Chain& arm, SimulationMode mode);

/// The finger controller of a scene: `FingerForceController` with the fingers' and the object's
/// geoms, writing torques or servo targets as the mode needs, squeezing with @p grasp_force [N].
std::unique_ptr<FingerForceController> make_pick_place_fingers(const PickPlaceScene& scene,
                                                               SimulationMode mode,
                                                               double grasp_force);

}  // namespace mjarm
