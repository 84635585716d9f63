#include "mjarm/env/action_driver.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/control/joint_pd.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/tasks/approach_timing.hpp"

namespace mjarm {
namespace {

/// Commands the torques it is pointed at: the action of joint_torques, held over the step.
class TorquePassThrough final : public Controller {
 public:
  TorquePassThrough(const Chain& chain, const Eigen::VectorXd& torque)
      : chain_(chain), torque_(torque) {}
  std::string_view name() const noexcept override { return "env-torque"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData&, const Reference&, JointCommand& command) noexcept override {
    command.kind = CommandKind::torque;
    if (command.value.size() == torque_.size()) command.value = torque_;
  }

 private:
  Chain chain_;
  const Eigen::VectorXd& torque_;
};

/// kp_i = ω²·M_ii, kd_i = 2ω·M_ii with M at the `home` keyframe (qpos0 without one).
JointPdGains inertia_scaled_gains(const Chain& chain, double omega) {
  const Robot& robot = chain.robot();
  const mjModel& m = robot.model();
  DataPtr d = robot.make_data();
  const std::vector<std::string> keys = robot.keyframe_names();
  if (std::find(keys.begin(), keys.end(), "home") != keys.end())
    mj_resetDataKeyframe(&m, d.get(), robot.keyframe("home"));
  mj_forward(&m, d.get());
  JointPdGains gains;
  gains.kp.resize(chain.size());
  gains.kd.resize(chain.size());
  for (int i = 0; i < chain.size(); ++i) {
    // the diagonal closes the dof's row of MuJoCo's sparse M (its columns ascend)
    const int row = chain.dof_address(i);
    const double inertia = d->M[m.M_rowadr[row] + m.M_rownnz[row] - 1];
    gains.kp[i] = omega * omega * inertia;
    gains.kd[i] = 2.0 * omega * inertia;
  }
  return gains;
}

ArraySpec symmetric_spec(const Eigen::VectorXd& bound) {
  return ArraySpec::bounded("action", -bound, bound);
}

Eigen::VectorXd pose_bounds(double linear, double angular) {
  Eigen::VectorXd b(6);
  b << linear, linear, linear, angular, angular, angular;
  return b;
}

}  // namespace

ActionDriver::ActionDriver(ActionSpace space, const Chain& chain, const ActionOptions& options,
                           double control_period, bool gripper)
    : space_(space), chain_(chain), options_(options), period_(control_period), gripper_(gripper) {
  options.check();
  if (!(std::isfinite(control_period) && control_period > 0.0))
    throw Error("action driver: the control period must be positive and finite, got " +
                number_text(control_period) + " s");
  const int n = chain_.size();
  q_.setZero(n);
  torque_.setZero(n);
  reference_.joint.q.setZero(n);
  reference_.joint.qd.setZero(n);
  reference_.joint.qdd.setZero(n);
  switch (space) {
    case ActionSpace::joint_torques: {
      Eigen::VectorXd limit(n);
      for (int i = 0; i < n; ++i) limit[i] = joint_torque_limit(chain_, i);
      spec_ = symmetric_spec(limit);
      controller_ = std::make_unique<TorquePassThrough>(chain_, torque_);
      break;
    }
    case ActionSpace::joint_positions:
    case ActionSpace::joint_deltas: {
      spec_ = space == ActionSpace::joint_positions
                  ? ArraySpec::bounded("action", chain_.lower(), chain_.upper())
                  : symmetric_spec(Eigen::VectorXd::Constant(n, options.max_joint_delta));
      JointPdOptions pd;
      pd.gains = inertia_scaled_gains(chain_, options.joint_bandwidth);
      pd.gravity_compensation = true;
      controller_ = std::make_unique<JointPdController>(chain_, pd);
      break;
    }
    case ActionSpace::ee_pose_deltas:
    case ActionSpace::ee_velocities: {
      spec_ =
          symmetric_spec(space == ActionSpace::ee_pose_deltas
                             ? pose_bounds(options.max_translation, options.max_rotation)
                             : pose_bounds(options.max_linear_speed, options.max_angular_speed));
      DiffIkOptions ik;
      ik.dt = control_period;
      ik.velocity_limit = Eigen::VectorXd::Constant(n, options.max_joint_speed);
      ik_ = std::make_unique<DiffIk>(chain_, ik);
      ik_->add_pose_task();
      // anti-windup: the goal may lead the reference by two steps of the largest action
      const double steps = space == ActionSpace::ee_pose_deltas ? 1.0 : control_period;
      max_lead_position_ = 2.0 * std::sqrt(3.0) * steps *
                           (space == ActionSpace::ee_pose_deltas ? options.max_translation
                                                                 : options.max_linear_speed);
      max_lead_rotation_ = 2.0 * std::sqrt(3.0) * steps *
                           (space == ActionSpace::ee_pose_deltas ? options.max_rotation
                                                                 : options.max_angular_speed);
      kinematics_ = std::make_unique<ChainKinematics>(chain_);
      J_ = Matrix6Xd::Zero(6, n);
      controller_ = std::make_unique<OperationalSpaceController>(chain_, options.osc);
      break;
    }
  }
  if (gripper_) {
    // one more entry, last: the gripper command in [0, 1]
    const Eigen::Index k = spec_.minimum.size();
    spec_.minimum.conservativeResize(k + 1);
    spec_.maximum.conservativeResize(k + 1);
    spec_.minimum[k] = 0.0;
    spec_.maximum[k] = 1.0;
    spec_.shape = {static_cast<int>(k + 1)};
  }
}

ActionDriver::~ActionDriver() = default;

const DiffIkStep* ActionDriver::ik_step() const noexcept {
  return ik_ ? &ik_->last_step() : nullptr;
}

ChainKinematics* ActionDriver::measured_kinematics() noexcept {
  return ik_ ? &ik_->task_kinematics(0) : nullptr;
}

void ActionDriver::read_q(const mjData& d) noexcept {
  for (int i = 0; i < chain_.size(); ++i) q_[i] = d.qpos[chain_.qpos_address(i)];
}

void ActionDriver::reset(const mjData& d) {
  read_q(d);
  torque_.setZero();
  reference_.joint.q = q_;
  reference_.joint.qd.setZero();
  reference_.joint.qdd.setZero();
  reference_.task = TaskReference{};
  reference_.gripper = 0.0;  // open
  if (ik_) {
    ik_->reset_warm_start();  // an episode never depends on the ones before it
    X_WR_ = kinematics_->update(q_);
    X_WG_ = X_WR_;
    reference_.task.X_WE = X_WR_;
  }
}

const Reference& ActionDriver::apply(std::span<const double> action, const mjData& d) noexcept {
  const int n = chain_.size();
  read_q(d);
  if (gripper_) reference_.gripper = action[action.size() - 1];
  switch (space_) {
    case ActionSpace::joint_torques:
      for (int i = 0; i < n; ++i) torque_[i] = action[i];
      break;
    case ActionSpace::joint_positions:
      for (int i = 0; i < n; ++i) reference_.joint.q[i] = action[i];
      break;
    case ActionSpace::joint_deltas:
      for (int i = 0; i < n; ++i)
        reference_.joint.q[i] =
            std::clamp(reference_.joint.q[i] + action[i], chain_.lower()[i], chain_.upper()[i]);
      break;
    case ActionSpace::ee_pose_deltas:
    case ActionSpace::ee_velocities: {
      // the goal moves by the action; one feasible QP step from the measured q towards it
      const double scale = space_ == ActionSpace::ee_velocities ? period_ : 1.0;
      const Eigen::Vector3d dp(action[0] * scale, action[1] * scale, action[2] * scale);
      const Eigen::Vector3d r(action[3] * scale, action[4] * scale, action[5] * scale);
      X_WG_.p += dp;
      X_WG_.R = so3::exp(r) * X_WG_.R;
      ik_->set_target(0, X_WG_);  // finite and a rotation: cannot throw
      // from the measured q clamped into the limits: a joint the arm has pushed past its limit
      // (MuJoCo's limits are soft: contact, a blocked tool) never takes the reference out
      for (int i = 0; i < n; ++i) q_[i] = std::clamp(q_[i], chain_.lower()[i], chain_.upper()[i]);
      const DiffIkStep& step = ik_->step(q_);
      X_WR_ = kinematics_->update(step.q_next);
      kinematics_->jacobian(J_);
      reference_.task.X_WE = X_WR_;
      reference_.task.V_WE.noalias() = J_ * step.v;
      reference_.joint.q = step.q_next;
      // anti-windup: a goal the arm cannot follow stays within reach of the reference
      const Eigen::Vector3d lead = X_WG_.p - X_WR_.p;
      if (lead.norm() > max_lead_position_) X_WG_.p = X_WR_.p + lead * (max_lead_position_ / lead.norm());
      const Eigen::Vector3d turn = so3::log(X_WG_.R * X_WR_.R.transpose());
      if (turn.norm() > max_lead_rotation_)
        X_WG_.R = so3::exp(turn * (max_lead_rotation_ / turn.norm())) * X_WR_.R;
      break;
    }
  }
  return reference_;
}

}  // namespace mjarm
