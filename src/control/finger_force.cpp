#include "mjarm/control/finger_force.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "control_checks.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

constexpr int kMaxFingers = 8;

const FingerForceOptions& fingers_checked(const FingerForceOptions& options) {
  check_fields(options, "fingers");
  if (options.max_force < options.grasp_force) {
    throw Error("fingers: max_force (" + number_text(options.max_force) +
                " N) must be ≥ grasp_force (" + number_text(options.grasp_force) + " N)");
  }
  return options;
}

}  // namespace

FingerForceController::FingerForceController(const Chain& fingers,
                                             const FingerForceOptions& options)
    : options_(fingers_checked(options)),
      dynamics_(fingers),
      open_(detail::finger_stroke_end(fingers, options.open, true, "fingers", "open")),
      closed_(detail::finger_stroke_end(fingers, options.closed, false, "fingers", "closed")) {
  const int n = fingers.size();
  if (n > kMaxFingers) {
    throw Error("fingers: at most " + std::to_string(kMaxFingers) + " finger joints, got " +
                std::to_string(n));
  }
  const mjModel& m = fingers.robot().model();
  finger_of_geom_.assign(static_cast<std::size_t>(m.ngeom), 0);
  object_geom_.assign(static_cast<std::size_t>(m.ngeom), 0);
  const auto check_geom = [&](int g, const char* what) {
    if (g < 0 || g >= m.ngeom) {
      throw Error(std::string("fingers: ") + what + " geom id " + std::to_string(g) +
                  " out of range [0, " + std::to_string(m.ngeom) + ")");
    }
  };
  if (!options.object_geoms.empty() && static_cast<int>(options.finger_geoms.size()) != n) {
    throw Error("fingers: finger_geoms needs one list per finger joint (" + std::to_string(n) +
                "), got " + std::to_string(options.finger_geoms.size()));
  }
  for (std::size_t i = 0; i < options.finger_geoms.size(); ++i) {
    for (int g : options.finger_geoms[i]) {
      check_geom(g, "finger");
      finger_of_geom_[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(i + 1);
    }
  }
  for (int g : options.object_geoms) {
    check_geom(g, "object");
    object_geom_[static_cast<std::size_t>(g)] = 1;
  }
  if (options.command == CommandKind::position) {
    servo_kp_.resize(n);
    servo_kv_.resize(n);
    ctrl_lower_.resize(n);
    ctrl_upper_.resize(n);
    for (int i = 0; i < n; ++i) {
      const std::optional<int> a = fingers.actuator(i);
      const bool servo =
          a && m.actuator_gaintype[*a] == mjGAIN_FIXED &&
          m.actuator_biastype[*a] == mjBIAS_AFFINE && m.actuator_gainprm[*a * mjNGAIN] > 0.0 &&
          m.actuator_biasprm[*a * mjNBIAS + 1] == -m.actuator_gainprm[*a * mjNGAIN] &&
          m.actuator_trntype[*a] == mjTRN_JOINT && m.actuator_gear[6 * *a] == 1.0;
      if (!servo) {
        throw Error(
            "fingers: position mode needs a position servo (gain kp, bias "
            "−kp·q − kv·q̇, gear 1) on finger joint '" +
            fingers.joint_names()[i] + "'");
      }
      servo_kp_[i] = m.actuator_gainprm[*a * mjNGAIN];
      servo_kv_[i] = -m.actuator_biasprm[*a * mjNBIAS + 2];
      const bool limited = m.actuator_ctrllimited[*a] != 0;
      ctrl_lower_[i] = limited ? m.actuator_ctrlrange[2 * *a] : -mjMAXVAL;
      ctrl_upper_[i] = limited ? m.actuator_ctrlrange[2 * *a + 1] : mjMAXVAL;
    }
  }
  forces_ = Eigen::VectorXd::Zero(n);
}

void FingerForceController::reset() noexcept {
  fraction_ = 0.0;
  forces_.setZero();
  touching_.fill(false);
}

int FingerForceController::touching_count() const noexcept {
  int count = 0;
  for (int i = 0; i < chain().size(); ++i) count += touching_[i] ? 1 : 0;
  return count;
}

void FingerForceController::compute(const mjData& data, const Reference& reference,
                                    JointCommand& command) noexcept {
  const Chain& chain = dynamics_.chain();
  const int n = chain.size();
  if (command.value.size() != n) return;
  command.kind = options_.command;
  if (!std::isnan(reference.gripper)) fraction_ = std::clamp(reference.gripper, 0.0, 1.0);

  // which fingers touch the object: MuJoCo's contact list of this state
  touching_.fill(false);
  for (int c = 0; c < data.ncon; ++c) {
    const mjContact& contact = data.contact[c];
    if (contact.exclude != 0) continue;
    const int g1 = contact.geom1, g2 = contact.geom2;
    int finger = 0;
    if (object_geom_[static_cast<std::size_t>(g2)] != 0)
      finger = finger_of_geom_[static_cast<std::size_t>(g1)];
    if (finger == 0 && object_geom_[static_cast<std::size_t>(g1)] != 0)
      finger = finger_of_geom_[static_cast<std::size_t>(g2)];
    if (finger > 0) touching_[static_cast<std::size_t>(finger - 1)] = true;
  }

  const bool torque = options_.command == CommandKind::torque;
  if (torque && options_.gravity_compensation) dynamics_.update(data);
  // the fingers' mean opening (a finger on the object is pulled towards it: centring) and the
  // mean opening asked for; while the reference asks for less, the fingers on the object squeeze
  // — all of them switch together, so that one finger never pushes the object alone
  double mean_opening = 0.0, mean_target = 0.0;
  for (int i = 0; i < n; ++i) {
    const double closing = closed_[i] < open_[i] ? -1.0 : 1.0;
    mean_opening -= closing * (data.qpos[chain.qpos_address(i)] - closed_[i]) / n;
    mean_target += (1.0 - fraction_) * std::abs(open_[i] - closed_[i]) / n;
  }
  const bool squeezing = mean_target < mean_opening;
  double squeeze = 0.0;
  int touching = 0;
  for (int i = 0; i < n; ++i) {
    const double q = data.qpos[chain.qpos_address(i)];
    const double v = data.qvel[chain.dof_address(i)];
    const double e = open_[i] + fraction_ * (closed_[i] - open_[i]) - q;
    // on the object and still asked to close: push with the grasp force (closing direction)
    const double closing = closed_[i] < open_[i] ? -1.0 : 1.0;
    const bool contact = touching_[static_cast<std::size_t>(i)] && squeezing;
    double lower = -options_.max_force, upper = options_.max_force;
    if (!torque) {
      // what the servo can push from here without its target leaving ctrlrange
      const double from_q = servo_kv_[i] * v;
      lower = std::max(lower, servo_kp_[i] * (ctrl_lower_[i] - q) - from_q);
      upper = std::min(upper, servo_kp_[i] * (ctrl_upper_[i] - q) - from_q);
      if (lower > upper) lower = upper = 0.5 * (lower + upper);
    }
    const double opening = -closing * (q - closed_[i]);
    const double f =
        std::clamp(contact ? closing * (options_.grasp_force +
                                        options_.centering_stiffness * (opening - mean_opening)) -
                                 options_.contact_damping * v
                           : options_.free_stiffness * e - options_.free_damping * v,
                   lower, upper);
    forces_[i] = f;
    if (contact) {
      squeeze += std::abs(f);
      ++touching;
    }
    if (torque) {
      command.value[i] = f + (options_.gravity_compensation ? dynamics_.gravity()[i] : 0.0);
    } else {
      command.value[i] =
          std::clamp(q + (f + servo_kv_[i] * v) / servo_kp_[i], ctrl_lower_[i], ctrl_upper_[i]);
    }
  }
  values_ = {fraction_, static_cast<double>(touching), touching > 0 ? squeeze / touching : 0.0};
}

}  // namespace mjarm
