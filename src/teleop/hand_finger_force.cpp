#include "mjarm/teleop/hand_finger_force.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

// the finger geoms (one list per finger joint) and every geom outside the gripper: the body the
// first finger hangs from and its subtree
FingerForceOptions with_hand_geoms(const Chain& fingers, FingerForceOptions o) {
  if (o.command != CommandKind::torque)
    throw Error("HandFingerForce: the fingers take torques (options.command must be torque)");
  if (!o.finger_geoms.empty() || !o.object_geoms.empty())
    throw Error(
        "HandFingerForce: finger and object geoms are found on the model; leave "
        "options.finger_geoms and options.object_geoms empty");
  if (fingers.size() == 0) throw Error("HandFingerForce: no finger joint");
  const mjModel& m = fingers.robot().model();
  const int hand = m.body_parentid[m.jnt_bodyid[fingers.joint_ids().front()]];
  o.finger_geoms.resize(static_cast<std::size_t>(fingers.size()));
  for (int g = 0; g < m.ngeom; ++g) {
    const int body = m.geom_bodyid[g];
    bool own = false;
    for (int b = body; b > 0 && !own; b = m.body_parentid[b]) own = b == hand;
    for (int i = 0; i < fingers.size(); ++i) {
      if (m.jnt_bodyid[fingers.joint_ids()[static_cast<std::size_t>(i)]] == body)
        o.finger_geoms[static_cast<std::size_t>(i)].push_back(g);
    }
    if (!own) o.object_geoms.push_back(g);
  }
  return o;
}

}  // namespace

FingerForceOptions hand_finger_force_defaults() {
  FingerForceOptions o;
  o.command = CommandKind::torque;
  o.free_stiffness = 1000.0;
  o.free_damping = 5.0;
  o.contact_damping = 20.0;
  o.centering_stiffness = 2000.0;
  o.grasp_force = 20.0;
  o.max_force = 30.0;
  o.gravity_compensation = true;
  return o;
}

HandFingerForce::HandFingerForce(const Chain& fingers, const FingerForceOptions& options)
    : fingers_(fingers, with_hand_geoms(fingers, options)) {
  own_.gripper = 0.0;
}

void HandFingerForce::compute(const mjData& data, const Reference&,
                              JointCommand& command) noexcept {
  fingers_.compute(data, own_, command);
}

void HandFingerForce::reset() noexcept {
  fingers_.reset();
  own_.gripper = 0.0;
}

void HandFingerForce::set_command(double closed) noexcept {
  if (!std::isnan(closed)) own_.gripper = std::clamp(closed, 0.0, 1.0);
}

}  // namespace mjarm
