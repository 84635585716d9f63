#include "mjarm/tasks/pick_place/controllers.hpp"

#include <cmath>

#include "mjarm/control/operational_space.hpp"
#include "mjarm/error.hpp"
#include "mjarm/tasks/pick_place/scene.hpp"

namespace mjarm {

PoseIkOptions IkServoController::default_options() {
  PoseIkOptions o;
  o.max_iterations = 20;
  o.max_backtracks = 2;
  o.position_tolerance = 1e-7;
  o.orientation_tolerance = 1e-6;
  o.stall_iterations = 5;
  return o;
}

IkServoController::IkServoController(const Chain& arm, const PoseIkOptions& options)
    : ik_(arm, options), seed_(Eigen::VectorXd::Zero(arm.size())) {
  result_.q = Eigen::VectorXd::Zero(arm.size());
}

void IkServoController::compute(const mjData& data, const Reference& reference,
                                JointCommand& command) noexcept {
  const Chain& chain = ik_.chain();
  const int n = chain.size();
  if (command.value.size() != n) return;
  command.kind = CommandKind::position;
  if (!seeded_) {
    for (int i = 0; i < n; ++i) seed_[i] = data.qpos[chain.qpos_address(i)];
    command.value = seed_;
    seeded_ = true;
  }
  const Pose& X = reference.task.X_WE;
  if (!X.p.allFinite() || !X.R.allFinite()) {
    command.value = seed_;
    return;
  }
  try {
    ik_.solve(X, seed_, result_);
  } catch (...) {  // a reference rotation that is not one: keep the previous targets
    command.value = seed_;
    return;
  }
  if (result_.q.allFinite()) seed_ = result_.q;
  command.value = seed_;
  values_ = {result_.position_error, result_.orientation_error,
             static_cast<double>(result_.iterations)};
}

std::unique_ptr<Controller> make_pick_place_arm_controller(const Chain& arm, SimulationMode mode) {
  if (mode == SimulationMode::position) return std::make_unique<IkServoController>(arm);
  if (mode != SimulationMode::torque)
    throw Error("pick and place: the arm runs in position or torque mode");
  OperationalSpaceOptions o;
  o.mode = TaskMode::pose;
  // per unit of desired inertia: ω_n = √K, critically damped
  o.stiffness = (Vector6d() << 900.0, 900.0, 900.0, 900.0, 900.0, 900.0).finished();
  o.damping = Vector6d::Constant(-1.0);
  o.nullspace_damping = 2.0;
  o.nullspace_stiffness = 10.0;  // the start posture (redundant arms)
  return std::make_unique<OperationalSpaceController>(arm, o);
}

std::unique_ptr<FingerForceController> make_pick_place_fingers(const PickPlaceScene& scene,
                                                               SimulationMode mode,
                                                               double grasp_force) {
  const Robot& robot = scene.model;
  const Chain fingers(robot, {scene.fingers[0], scene.fingers[1]}, scene.tool);
  FingerForceOptions o;
  o.command = mode == SimulationMode::torque ? CommandKind::torque : CommandKind::position;
  o.grasp_force = grasp_force;
  o.max_force = std::max(20.0, grasp_force);
  for (const std::string& finger : scene.fingers) o.finger_geoms.push_back({robot.geom(finger)});
  o.object_geoms = {robot.geom(scene.object + "/geom")};
  return std::make_unique<FingerForceController>(fingers, o);
}

}  // namespace mjarm
