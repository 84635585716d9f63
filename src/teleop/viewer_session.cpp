#include "mjarm/teleop/viewer_session.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "mjarm/control/gripper_pd.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/teleop/viewer_controllers.hpp"
#include "teleop_model.hpp"

namespace mjarm {

using detail::gripper_joints;

namespace {

double rotation_angle(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b) noexcept {
  return so3::angle(R_b * R_a.transpose());
}

}  // namespace

std::string default_viewer_site(const Robot& robot) {
  std::vector<std::string> named;
  for (const auto& name : robot.site_names()) {
    if (name == "tcp") return name;
    if (!name.empty()) named.push_back(name);
  }
  if (named.size() == 1) return named.front();
  std::string list;
  for (const auto& n : named) list += (list.empty() ? "" : ", ") + n;
  throw Error("viewer: model '" + robot.name() + "' has " +
              (named.empty() ? std::string("no named site")
                             : std::to_string(named.size()) + " sites (" + list + ")") +
              "; choose the end-effector frame with --site");
}

struct ViewerSession::Rig {
  Robot robot;
  SimulationMode mode;
  Chain arm;
  std::optional<Chain> gripper;
  double period = 0.0;
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<PoseIk> ik;
  std::unique_ptr<JointTargetController> joints;
  std::unique_ptr<OperationalSpaceController> osc;
  std::unique_ptr<GripperTargetController> grip;  // kinematic and position modes
  std::unique_ptr<GripperPdController> grip_pd;   // torque mode
  Reference reference;
  IkResult ik_result;
  Eigen::VectorXd q, q_cmd, q_grip, q_home;
  std::vector<double> qpos;
  int watch = -1;

  Rig(const Robot& r, SimulationMode m, const std::string& site, const ViewerSessionOptions& o)
      : robot(r), mode(m), arm(robot, site) {
    const auto fingers = gripper_joints(arm);
    if (!fingers.empty()) gripper.emplace(robot, fingers, site);
    sim = detail::rig_simulation(robot, m, o.kinematic_period, o.control_period, GeomSet(), period);
    if (gripper && m != SimulationMode::torque)
      grip = std::make_unique<GripperTargetController>(*gripper);
    if (m != SimulationMode::kinematic) {
      if (m == SimulationMode::position) {
        joints = std::make_unique<JointTargetController>(arm);
        sim->add_controller(*joints);
      } else {
        OperationalSpaceOptions osc_options;
        osc_options.nullspace_stiffness = 10.0;  // hold the initial posture in the null space
        osc = std::make_unique<OperationalSpaceController>(arm, osc_options);
        sim->add_controller(*osc);
      }
      if (grip) sim->add_controller(*grip);
      if (gripper && m == SimulationMode::torque) {
        grip_pd = std::make_unique<GripperPdController>(*gripper);
        sim->add_controller(*grip_pd);
      }
    }
    if (m != SimulationMode::torque) {
      PoseIkOptions ik_options;
      ik_options.max_iterations = std::max(1, o.ik_iterations);
      ik = std::make_unique<PoseIk>(arm, ik_options);
    }
    const std::string root = detail::root_body(robot.model(), arm.joint_ids().front());
    if (!root.empty()) watch = sim->watch_contacts(GeomSet::of_bodies(robot, {root}), GeomSet());
    const int n = arm.size();
    q.setZero(n);
    q_cmd.setZero(n);
    q_home.setZero(n);
    q_grip.setZero(gripper ? gripper->size() : 0);
    ik_result.q.setZero(n);
    reference.joint.q.setZero(n);
    reference.joint.qd.setZero(n);
    reference.joint.qdd.setZero(n);
    qpos.assign(static_cast<std::size_t>(robot.nq()), 0.0);
  }

  // arm joint values from the simulation's qpos, without allocating
  void read_q() noexcept {
    const double* qpos_now = sim->data().qpos;
    for (int i = 0; i < arm.size(); ++i) q[i] = qpos_now[arm.qpos_address(i)];
  }
};

ViewerSession::ViewerSession(const Robot& robot, const ViewerSessionOptions& options)
    : site_(options.site.empty() ? default_viewer_site(robot) : options.site),
      options_(options),
      filter_(options.reference_limits),
      gripper_ramp_(options.gripper_travel_time) {
  check_fields(options);
  options_.keyframe = detail::initial_keyframe(robot, options.keyframe);
  rigs_.build(robot, options.mode, "viewer", [&](const Robot& model, SimulationMode mode) {
    return std::make_unique<Rig>(model, mode, site_, options_);
  });
  rigs_.for_each([this](Rig&) { reset(); });
  restart_reference();
  ranges_ =
      panel_ranges(rigs_.rig(SimulationMode::kinematic).arm, stats_.X_WE, options.range_samples);
  initial_panel_ = panel_state(stats_.X_WE, ranges_, 0.0, mode());
  set_target(initial_panel_);
}

ViewerSession::~ViewerSession() = default;

const Robot& ViewerSession::robot() const noexcept { return rigs_.current().robot; }
Simulation& ViewerSession::simulation() noexcept { return *rigs_.current().sim; }
const Simulation& ViewerSession::simulation() const noexcept { return *rigs_.current().sim; }
const Chain& ViewerSession::arm() const noexcept { return rigs_.current().arm; }
bool ViewerSession::has_gripper() const noexcept { return rigs_.current().gripper.has_value(); }
double ViewerSession::control_period() const noexcept { return rigs_.current().period; }

void ViewerSession::set_mode(SimulationMode mode) {
  if (rigs_.switch_to(mode, "viewer")) restart_reference();
}

void ViewerSession::set_target(const PanelState& panel) noexcept {
  X_WT_ = panel_target(panel);
  gripper_ = std::isfinite(panel.gripper) ? std::clamp(panel.gripper, 0.0, 1.0) : 0.0;
  refresh_stats();
}

void ViewerSession::reset() {
  Rig& rig = rigs_.current();
  detail::reset_simulation(*rig.sim, options_.keyframe);
  rig.read_q();
  rig.q_home = rig.q;
  gripper_ramp_.reset(0.0);  // the initial command: open
  restart_reference();
}

// the reference restarts at the end effector, the servo targets at the configuration
void ViewerSession::restart_reference() {
  Rig& rig = rigs_.current();
  rig.read_q();
  rig.q_cmd = rig.q;
  rig.reference.joint.q = rig.q;
  rig.reference.gripper = gripper_ramp_.value();
  rig.reference.task.X_WE = frame_pose(rig.robot.model(), rig.sim->data(), rig.arm.frame());
  filter_.reset(rig.reference.task.X_WE);
  stats_.faulted = false;
  stats_.fault.clear();
  stats_.ik_used = false;
  stats_.saturated = 0;
  refresh_stats();
}

int ViewerSession::step(int ticks) noexcept {
  Rig& rig = rigs_.current();
  int done = 0;
  for (; done < ticks && !stats_.faulted; ++done) {
    if (!tick(rig)) break;
  }
  refresh_stats();
  return done;
}

bool ViewerSession::tick(Rig& rig) noexcept {
  const double dt = rig.period;
  const Pose& X_WR = filter_.update(X_WT_, dt);
  const double gripper = gripper_ramp_.update(gripper_, dt);
  rig.reference.gripper = gripper;
  stats_.ik_used = rig.ik != nullptr;
  if (rig.ik) {
    // IK from the current configuration (kinematic) or the last servo target (position),
    // the step limited to max_joint_speed
    rig.read_q();
    const Eigen::VectorXd& seed = rig.mode == SimulationMode::kinematic ? rig.q : rig.q_cmd;
    rig.ik->solve(X_WR, seed, rig.ik_result);
    stats_.ik_status = rig.ik_result.status;
    const double max_step = options_.max_joint_speed * dt;
    rig.q_cmd = seed + (rig.ik_result.q - seed).cwiseMax(-max_step).cwiseMin(max_step);
  }
  if (rig.mode == SimulationMode::kinematic) {
    const mjData& d = rig.sim->data();
    std::copy(d.qpos, d.qpos + rig.robot.nq(), rig.qpos.begin());
    rig.arm.scatter(rig.q_cmd, rig.qpos.data());
    if (rig.grip) {
      rig.grip->targets(gripper, rig.q_grip);
      rig.gripper->scatter(rig.q_grip, rig.qpos.data());
    }
    try {
      rig.sim->move(rig.qpos, dt);
    } catch (const std::exception& e) {  // only for NaN from a broken model: stop, do not die
      stats_.faulted = true;
      stats_.fault = e.what();
      return false;
    }
    return true;
  }
  if (rig.mode == SimulationMode::position) {
    rig.reference.joint.q = rig.q_cmd;
  } else {
    rig.reference.task.X_WE = X_WR;
    rig.reference.task.V_WE = filter_.velocity();
    rig.reference.task.A_WE = filter_.acceleration();
    rig.reference.joint.q = rig.q_home;  // null-space posture
  }
  const TickResult result = rig.sim->tick(rig.reference);
  stats_.saturated = result.saturated;
  if (!result.ok()) {
    stats_.faulted = true;
    stats_.fault = rig.sim->describe(result.fault);
    return false;
  }
  return true;
}

void ViewerSession::refresh_stats() noexcept {
  Rig& rig = rigs_.current();
  const mjData& d = rig.sim->data();
  stats_.mode = mode();
  stats_.time = d.time;
  stats_.X_WE = detail::read_frame(d, rig.arm.frame());
  stats_.X_WR = filter_.pose();
  stats_.gripper = gripper_ramp_.value();
  stats_.X_WT = X_WT_;
  stats_.tracking_position = (stats_.X_WR.p - stats_.X_WE.p).norm();
  stats_.tracking_orientation = rotation_angle(stats_.X_WE.R, stats_.X_WR.R);
  stats_.target_position = (stats_.X_WT.p - stats_.X_WE.p).norm();
  stats_.target_orientation = rotation_angle(stats_.X_WE.R, stats_.X_WT.R);
  stats_.contacts = rig.watch >= 0 ? rig.sim->contacts(rig.watch) : ContactSummary{};
}

}  // namespace mjarm
