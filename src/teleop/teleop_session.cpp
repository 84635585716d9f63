#include "mjarm/teleop/teleop_session.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "mjarm/control/computed_torque.hpp"
#include "mjarm/error.hpp"
#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/ik/multi_target_ik.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/teleop/hand_finger_force.hpp"
#include "mjarm/teleop/viewer_controllers.hpp"
#include "mjarm/trajectory/ramped_command.hpp"
#include "teleop_model.hpp"

namespace mjarm {

namespace {

// body id of a site or body frame
int frame_body(const mjModel& m, const std::string& frame) {
  const int site = mj_name2id(&m, mjOBJ_SITE, frame.c_str());
  if (site >= 0) return m.site_bodyid[site];
  const int body = mj_name2id(&m, mjOBJ_BODY, frame.c_str());
  if (body >= 0) return body;
  throw Error("teleop: frame '" + frame + "' is neither a site nor a body of the model");
}

bool is_ancestor(const mjModel& m, int ancestor, int body) {
  for (int b = body; b > 0; b = m.body_parentid[b]) {
    if (b == ancestor) return true;
  }
  return false;
}

// the hinge/slide joints that move any hand frame, except the lift and the fingers, in id order
std::vector<std::string> teleop_arm_joints(const Robot& robot, const std::vector<TeleopHand>& hands,
                                           const std::string& lift) {
  const mjModel& m = robot.model();
  std::vector<std::string> names;
  for (int j = 0; j < m.njnt; ++j) {
    if (m.jnt_type[j] != mjJNT_HINGE && m.jnt_type[j] != mjJNT_SLIDE) continue;
    const char* name = mj_id2name(&m, mjOBJ_JOINT, j);
    if (name == nullptr || name == lift) continue;
    bool moves = false, finger = false;
    for (const auto& h : hands) {
      moves = moves || is_ancestor(m, m.jnt_bodyid[j], frame_body(m, h.frame));
      finger = finger || std::find(h.fingers.begin(), h.fingers.end(), name) != h.fingers.end();
    }
    if (moves && !finger) names.emplace_back(name);
  }
  if (names.empty()) throw Error("teleop: no joint of the model moves the hand frames");
  return names;
}

}  // namespace

std::vector<TeleopHand> find_teleop_hands(const Robot& robot) {
  std::vector<TeleopHand> hands;
  const std::string suffix = "_tcp";
  std::string sites;
  for (const auto& site : robot.site_names()) {
    if (site.empty()) continue;
    sites += (sites.empty() ? "" : ", ") + site;
    std::string name;
    if (site == "tcp") {
      name = "hand";
    } else if (site.size() > suffix.size() &&
               site.compare(site.size() - suffix.size(), suffix.size(), suffix) == 0) {
      name = site.substr(0, site.size() - suffix.size());
    } else {
      continue;
    }
    TeleopHand hand{name, site, {}};
    hand.fingers = detail::gripper_joints(Chain(robot, site));
    hands.push_back(std::move(hand));
  }
  if (hands.empty()) {
    throw Error("teleop: model '" + robot.name() +
                "' has no hand frame (a site called 'tcp' or '<name>_tcp'); sites: " +
                (sites.empty() ? std::string("none") : sites));
  }
  std::sort(hands.begin(), hands.end(),
            [](const TeleopHand& a, const TeleopHand& b) { return a.name < b.name; });
  return hands;
}

// the smoothed references, shared by the rigs (a mode switch restarts them)
struct TeleopSession::Smoothing {
  std::vector<TargetFilter> poses;
  std::vector<RampedCommand> grippers;
  RampedCommand lift;
  Smoothing(const TeleopOptions& o, std::size_t hands, std::array<double, 2> lift_range)
      : lift(o.lift_travel_time, lift_range[0], std::max(lift_range[1], lift_range[0] + 1e-9),
             SmoothRamp::Kind::smootherstep) {
    poses.reserve(hands);
    grippers.reserve(hands);
    for (std::size_t i = 0; i < hands; ++i) {
      poses.emplace_back(o.reference_limits);
      grippers.emplace_back(o.gripper_travel_time, 0.0, 1.0, SmoothRamp::Kind::smootherstep);
    }
  }
};

struct TeleopSession::Rig {
  Robot robot;
  SimulationMode mode;
  double period = 0.0;
  Chain arms;                                 // the joints the IK moves (frame: first hand)
  std::vector<Chain> frames;                  // per hand: arms with that hand's frame
  std::vector<std::optional<Chain>> fingers;  // per hand
  std::vector<std::unique_ptr<GripperTargetController>> finger_map;  // command → finger q
  std::optional<Chain> all;  // position: lift + arms + fingers; motor: lift + arms
  int lift_qpos = -1;
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<MultiTargetIk> ik;
  std::unique_ptr<DiffIk> dik;
  std::unique_ptr<JointTargetController> servo;
  std::unique_ptr<ComputedTorqueController> ct;
  std::vector<std::unique_ptr<HandFingerForce>> finger_pd;
  std::vector<int> hand_watch, finger_watch;
  std::vector<std::vector<int>> hand_actuators;
  Reference reference;
  IkResult ik_result;
  Eigen::VectorXd q, q_cmd, q_finger, qfull;
  std::vector<double> qpos;
  std::int64_t ticks = 0;

  Rig(const Robot& r, SimulationMode m, const std::vector<TeleopHand>& hands,
      const std::vector<std::string>& arm_joints, const std::string& lift, const TeleopOptions& o)
      : robot(r), mode(m), arms(robot, arm_joints, hands.front().frame) {
    const mjModel& model = robot.model();
    for (const auto& h : hands) {
      frames.emplace_back(robot, arm_joints, h.frame);
      if (h.fingers.empty()) {
        fingers.emplace_back();
        finger_map.emplace_back();
      } else {
        fingers.emplace_back(Chain(robot, h.fingers, h.frame));
        finger_map.push_back(std::make_unique<GripperTargetController>(*fingers.back()));
      }
    }
    if (!lift.empty()) lift_qpos = model.jnt_qposadr[robot.joint(lift)];
    // kinematic mode: a move that makes the robot touch anything is rolled back
    const std::string root = detail::root_body(model, arms.joint_ids().front());
    sim = detail::rig_simulation(robot, m, o.kinematic_period, o.control_period,
                                 m == SimulationMode::kinematic && !root.empty()
                                     ? GeomSet::of_bodies(robot, {root})
                                     : GeomSet(),
                                 period);
    std::vector<std::string> driven;
    if (!lift.empty()) driven.push_back(lift);
    driven.insert(driven.end(), arm_joints.begin(), arm_joints.end());
    if (m == SimulationMode::position) {
      for (const auto& hd : hands)
        driven.insert(driven.end(), hd.fingers.begin(), hd.fingers.end());
      all.emplace(robot, driven, hands.front().frame);
      servo = std::make_unique<JointTargetController>(*all);
      sim->add_controller(*servo);
    } else if (m == SimulationMode::torque) {
      all.emplace(robot, driven, hands.front().frame);
      ComputedTorqueOptions cto;
      cto.gains = JointPdGains::critically_damped(o.motor_omega);
      ct = std::make_unique<ComputedTorqueController>(*all, cto);
      sim->add_controller(*ct);
      for (auto& f : fingers) {
        if (!f) {
          finger_pd.emplace_back();
          continue;
        }
        finger_pd.push_back(std::make_unique<HandFingerForce>(*f));
        sim->add_controller(*finger_pd.back());
      }
    }
    // per hand: contacts of the gripper subtree and of the fingers with everything else, and the
    // actuators of its arm joints and fingers
    for (std::size_t i = 0; i < hands.size(); ++i) {
      const int body = frame_body(model, hands[i].frame);
      int gripper = body;
      std::vector<std::string> finger_bodies;
      if (fingers[i]) {
        const int first = model.jnt_bodyid[fingers[i]->joint_ids().front()];
        gripper = model.body_parentid[first];
        for (const int j : fingers[i]->joint_ids())
          finger_bodies.emplace_back(mj_id2name(&model, mjOBJ_BODY, model.jnt_bodyid[j]));
      }
      const char* gname = mj_id2name(&model, mjOBJ_BODY, gripper);
      const GeomSet hand_set = GeomSet::of_bodies(robot, {gname != nullptr ? gname : ""});
      hand_watch.push_back(sim->watch_contacts(hand_set, GeomSet()));
      finger_watch.push_back(finger_bodies.empty()
                                 ? -1
                                 : sim->watch_contacts(GeomSet::of_bodies(robot, finger_bodies),
                                                       hand_set.complement(robot)));
      std::vector<int> acts;
      for (int a = 0; a < model.nu; ++a) {
        if (model.actuator_trntype[a] != mjTRN_JOINT) continue;
        const int j = model.actuator_trnid[2 * a];
        const bool on_arm = is_ancestor(model, model.jnt_bodyid[j], body) &&
                            (lift.empty() || j != robot.joint(lift));
        const bool finger =
            fingers[i] && std::find(fingers[i]->joint_ids().begin(), fingers[i]->joint_ids().end(),
                                    j) != fingers[i]->joint_ids().end();
        if (on_arm || finger) acts.push_back(a);
      }
      hand_actuators.push_back(std::move(acts));
    }
    const int n = arms.size();
    q.setZero(n);
    q_cmd.setZero(n);
    ik_result.q.setZero(n);
    int most_fingers = 0;
    for (const auto& f : fingers) most_fingers = std::max(most_fingers, f ? f->size() : 0);
    q_finger.setZero(most_fingers);
    qfull.setZero(robot.nq());
    qpos.assign(static_cast<std::size_t>(robot.nq()), 0.0);
    const int na = all ? all->size() : 0;
    reference.joint.q.setZero(na);
    reference.joint.qd.setZero(na);
    reference.joint.qdd.setZero(na);
  }

  void read_q() noexcept {
    const double* qpos_now = sim->data().qpos;
    for (int i = 0; i < arms.size(); ++i) q[i] = qpos_now[arms.qpos_address(i)];
  }
};

TeleopSession::TeleopSession(const Robot& robot, const TeleopOptions& options)
    : hands_(options.hands.empty() ? find_teleop_hands(robot) : options.hands), options_(options) {
  check_fields(options);
  const mjModel& m = robot.model();
  std::string lift = options.lift;
  if (!lift.empty() && mj_name2id(&m, mjOBJ_JOINT, lift.c_str()) < 0) {
    if (lift != "lift") robot.joint(lift);  // a named lift that does not exist: an error
    lift.clear();
  }
  options_.lift = lift;
  has_lift_ = !lift.empty();
  if (has_lift_) {
    const int j = robot.joint(lift);
    lift_range_ = {m.jnt_range[2 * j], m.jnt_range[2 * j + 1]};
  }
  options_.keyframe = detail::initial_keyframe(robot, options_.keyframe);
  tasks_ = options.tasks;
  if (tasks_.empty()) tasks_.assign(hands_.size(), HandTask{});
  if (tasks_.size() != hands_.size())
    throw Error("teleop: " + std::to_string(tasks_.size()) + " hand tasks for " +
                std::to_string(hands_.size()) + " hands");
  // the lift moved by its own target, or an IK joint like the arms' (then shared by the hands)
  const std::string direct = options.lift_in_ik ? std::string() : lift;
  if (has_lift_) lift_qpos_ = m.jnt_qposadr[robot.joint(lift)];
  const auto arm_joints = teleop_arm_joints(robot, hands_, direct);
  rigs_.build(robot, options.mode, "teleop", [&](const Robot& model, SimulationMode mode) {
    return std::make_unique<Rig>(model, mode, hands_, arm_joints, direct, options_);
  });
  build_ik();
  smooth_ = std::make_unique<Smoothing>(options_, hands_.size(), lift_range_);
  stats_.hands.resize(hands_.size());
  targets_.hands.resize(hands_.size());
  rigs_.for_each([this](Rig&) { reset(); });
  restart_references();
  initial_.hands.resize(hands_.size());
  for (std::size_t i = 0; i < hands_.size(); ++i) initial_.hands[i] = {stats_.hands[i].X_WE, 0.0};
  initial_.lift = stats_.lift;
  targets_ = initial_;
  refresh_stats();
}

TeleopSession::~TeleopSession() = default;

void TeleopSession::build_ik() {
  rigs_.for_each([this](Rig& rig) {
    const DataPtr d = rig.robot.make_data();
    mj_forward(&rig.robot.model(), d.get());
    if (rig.mode == SimulationMode::torque) {
      DiffIkOptions o;
      o.dt = rig.period;
      o.damping = 1e-4;
      o.velocity_limit = Eigen::VectorXd::Constant(rig.arms.size(), options_.max_joint_speed);
      rig.dik = std::make_unique<DiffIk>(rig.arms, o);
      const double gain = std::min(1.0, options_.motor_gain * rig.period);
      for (std::size_t i = 0; i < hands_.size(); ++i) {
        const double w = std::pow(1e-2, tasks_[i].priority);
        if (tasks_[i].kind == TargetKind::pose) {
          rig.dik->add_pose_task(hands_[i].frame, w, w, gain);
        } else {
          rig.dik->add_position_task(hands_[i].frame, w, gain);
        }
      }
      // a weak pull to the initial posture settles the arms' redundant motion
      const std::vector<double> q0 = options_.keyframe.empty()
                                         ? std::vector<double>(d->qpos, d->qpos + rig.robot.nq())
                                         : rig.robot.keyframe_qpos(options_.keyframe);
      rig.dik->add_posture_task(rig.arms.gather(q0.data()), 1e-4, gain);
      return;
    }
    std::vector<FrameTarget> targets;
    for (std::size_t i = 0; i < hands_.size(); ++i) {
      FrameTarget t;
      t.frame = hands_[i].frame;
      t.kind = tasks_[i].kind;
      t.priority = tasks_[i].priority;
      t.X_WT = frame_pose(rig.robot.model(), *d, rig.frames[i].frame());
      targets.push_back(t);
    }
    MultiTargetIkOptions o;
    o.max_iterations = options_.ik_iterations;
    o.stall_iterations = options_.ik_iterations;
    o.position_tolerance = 1e-4;
    o.orientation_tolerance = 1e-3;
    rig.ik = std::make_unique<MultiTargetIk>(rig.robot, rig.arms.joint_names(), targets, o);
  });
}

void TeleopSession::set_task(int hand, const HandTask& task) {
  if (hand < 0 || hand >= static_cast<int>(hands_.size()))
    throw Error("teleop: no hand " + std::to_string(hand) + " (the session has " +
                std::to_string(hands_.size()) + ")");
  if (task.priority < 0) throw Error("teleop: a task priority must be ≥ 0");
  tasks_[static_cast<std::size_t>(hand)] = task;
  build_ik();
}

const Robot& TeleopSession::robot() const noexcept { return rigs_.current().robot; }
Simulation& TeleopSession::simulation() noexcept { return *rigs_.current().sim; }
const Simulation& TeleopSession::simulation() const noexcept { return *rigs_.current().sim; }
double TeleopSession::control_period() const noexcept { return rigs_.current().period; }

void TeleopSession::set_mode(SimulationMode mode) {
  const std::int64_t ticks = rigs_.current().ticks;
  if (!rigs_.switch_to(mode, "teleop")) return;
  rigs_.current().ticks = ticks;
  restart_references();
}

void TeleopSession::set_targets(const TeleopTargets& targets) {
  if (targets.hands.size() != hands_.size())
    throw Error("teleop: targets for " + std::to_string(targets.hands.size()) + " hands, the " +
                "session has " + std::to_string(hands_.size()));
  for (std::size_t i = 0; i < hands_.size(); ++i) {
    if (is_valid_pose(targets.hands[i].X_WT)) targets_.hands[i].X_WT = targets.hands[i].X_WT;
    if (std::isfinite(targets.hands[i].gripper))
      targets_.hands[i].gripper = std::clamp(targets.hands[i].gripper, 0.0, 1.0);
  }
  if (std::isfinite(targets.lift))
    targets_.lift = std::clamp(targets.lift, lift_range_[0], lift_range_[1]);
  refresh_stats();
}

void TeleopSession::reset() {
  Rig& rig = rigs_.current();
  detail::reset_simulation(*rig.sim, options_.keyframe);
  rig.ticks = 0;
  stats_.rollbacks = 0;
  for (std::size_t i = 0; i < hands_.size(); ++i) smooth_->grippers[i].reset(0.0);
  restart_references();
}

// the references restart where the hands and the lift are
void TeleopSession::restart_references() {
  Rig& rig = rigs_.current();
  rig.read_q();
  rig.q_cmd = rig.q;
  const mjData& d = rig.sim->data();
  for (std::size_t i = 0; i < hands_.size(); ++i) {
    smooth_->poses[i].reset(detail::read_frame(d, rig.frames[i].frame()));
    if (rig.mode == SimulationMode::torque && rig.finger_pd[i])
      rig.finger_pd[i]->set_command(smooth_->grippers[i].value());
  }
  smooth_->lift.reset(lift_qpos_ >= 0 ? d.qpos[lift_qpos_] : 0.0);
  stats_.faulted = false;
  stats_.fault.clear();
  refresh_stats();
}

int TeleopSession::step(int ticks) noexcept {
  Rig& rig = rigs_.current();
  int done = 0;
  for (; done < ticks && !stats_.faulted; ++done) {
    if (!tick(rig)) break;
    ++rig.ticks;
  }
  refresh_stats();
  return done;
}

bool TeleopSession::tick(Rig& rig) noexcept {
  const double dt = rig.period;
  const std::size_t nh = hands_.size();
  const double lift = smooth_->lift.update(targets_.lift, dt);
  for (std::size_t i = 0; i < nh; ++i) {
    smooth_->poses[i].update(targets_.hands[i].X_WT, dt);
    smooth_->grippers[i].update(targets_.hands[i].gripper, dt);
  }
  const mjData& d = rig.sim->data();
  rig.read_q();
  for (int k = 0; k < rig.robot.nq(); ++k) rig.qfull[k] = d.qpos[k];
  try {
    if (rig.mode == SimulationMode::torque) {
      // differential IK on the measured state, the lift where it is
      rig.dik->set_fixed_qpos(rig.qfull);
      for (std::size_t i = 0; i < nh; ++i)
        rig.dik->set_target(static_cast<int>(i), smooth_->poses[i].pose());
      const DiffIkStep& s = rig.dik->step(rig.q);
      const int off = rig.lift_qpos >= 0 ? 1 : 0;
      if (off) {
        rig.reference.joint.q[0] = lift;
        rig.reference.joint.qd[0] = smooth_->lift.rate();
      }
      rig.reference.joint.q.segment(off, rig.arms.size()) = s.q_next;
      rig.reference.joint.qd.segment(off, rig.arms.size()) = s.v;
      for (std::size_t i = 0; i < nh; ++i) {
        if (rig.finger_pd[i]) rig.finger_pd[i]->set_command(smooth_->grippers[i].value());
      }
    } else {
      // multi-target IK from the configuration (kinematic) or the last servo target (position)
      if (rig.lift_qpos >= 0) rig.qfull[rig.lift_qpos] = lift;
      rig.ik->set_fixed_qpos(rig.qfull);
      for (std::size_t i = 0; i < nh; ++i)
        rig.ik->set_target(static_cast<int>(i), smooth_->poses[i].pose());
      const Eigen::VectorXd& seed = rig.mode == SimulationMode::kinematic ? rig.q : rig.q_cmd;
      rig.ik->solve(seed, rig.ik_result);
      const double max_step = options_.max_joint_speed * dt;
      rig.q_cmd = seed + (rig.ik_result.q - seed).cwiseMax(-max_step).cwiseMin(max_step);
    }
  } catch (const std::exception& e) {
    stats_.faulted = true;
    stats_.fault = e.what();
    return false;
  }
  if (rig.mode == SimulationMode::kinematic) {
    rig.arms.scatter(rig.q_cmd, rig.qfull.data());
    for (std::size_t i = 0; i < nh; ++i) {
      if (!rig.fingers[i]) continue;
      const int n = rig.fingers[i]->size();
      rig.finger_map[i]->targets(smooth_->grippers[i].value(), rig.q_finger.head(n));
      rig.fingers[i]->scatter(rig.q_finger.head(n), rig.qfull.data());
    }
    std::copy(rig.qfull.data(), rig.qfull.data() + rig.robot.nq(), rig.qpos.begin());
    try {
      const KinematicStep k = rig.sim->move(rig.qpos, dt);
      if (k.rolled_back) ++stats_.rollbacks;
    } catch (const std::exception& e) {
      stats_.faulted = true;
      stats_.fault = e.what();
      return false;
    }
    return true;
  }
  if (rig.mode == SimulationMode::position) {
    int k = 0;
    if (rig.lift_qpos >= 0) rig.reference.joint.q[k++] = lift;
    rig.reference.joint.q.segment(k, rig.arms.size()) = rig.q_cmd;
    k += rig.arms.size();
    for (std::size_t i = 0; i < nh; ++i) {
      if (!rig.fingers[i]) continue;
      const int n = rig.fingers[i]->size();
      rig.finger_map[i]->targets(smooth_->grippers[i].value(), rig.q_finger.head(n));
      rig.reference.joint.q.segment(k, n) = rig.q_finger.head(n);
      k += n;
    }
  }
  const TickResult result = rig.sim->tick(rig.reference);
  if (!result.ok()) {
    stats_.faulted = true;
    stats_.fault = rig.sim->describe(result.fault);
    return false;
  }
  return true;
}

void TeleopSession::refresh_stats() noexcept {
  Rig& rig = rigs_.current();
  const mjData& d = rig.sim->data();
  stats_.mode = mode();
  stats_.time = d.time;
  stats_.ticks = rig.ticks;
  stats_.lift = lift_qpos_ >= 0 ? d.qpos[lift_qpos_] : 0.0;
  stats_.lift_reference = smooth_->lift.value();
  const auto saturated = rig.sim->saturated();
  for (std::size_t i = 0; i < hands_.size(); ++i) {
    HandStats& h = stats_.hands[i];
    h.X_WE = detail::read_frame(d, rig.frames[i].frame());
    h.X_WR = smooth_->poses[i].pose();
    h.X_WT = targets_.hands[i].X_WT;
    const FrameErrors e = frame_errors(h.X_WE, h.X_WR);
    h.tracking_position = e.position;
    h.tracking_orientation = e.orientation;
    if (rig.ik) {
      const FrameErrors r = rig.ik->target_errors(static_cast<int>(i));
      h.ik_position = r.position;
      h.ik_orientation = r.orientation;
      const bool within = r.position <= rig.ik->options().position_tolerance &&
                          (tasks_[i].kind == TargetKind::position ||
                           r.orientation <= rig.ik->options().orientation_tolerance);
      h.ik_status = within ? IkStatus::converged : IkStatus::not_converged;
    } else if (rig.dik) {
      const Eigen::VectorXd& err = rig.dik->task_error(static_cast<int>(i));
      h.ik_position = err.size() >= 3 ? err.head<3>().norm() : 0.0;
      h.ik_orientation = err.size() == 6 ? err.tail<3>().norm() : 0.0;
      h.ik_status = rig.dik->last_step().qp_status == qp::QpStatus::solved
                        ? IkStatus::converged
                        : IkStatus::not_converged;
    }
    h.saturated = 0;
    for (const int a : rig.hand_actuators[i])
      h.saturated += static_cast<std::size_t>(a) < saturated.size() && saturated[a] ? 1 : 0;
    const ContactSummary& hc = rig.sim->contacts(rig.hand_watch[i]);
    h.contacts = hc.contacts;
    if (rig.finger_watch[i] >= 0) {
      const ContactSummary& fc = rig.sim->contacts(rig.finger_watch[i]);
      h.touching = fc.contacts > 0;
      h.grasp_force = fc.forces_valid ? fc.normal_force : 0.0;
    } else {
      h.touching = false;
      h.grasp_force = 0.0;
    }
    h.gripper = smooth_->grippers[i].value();
  }
}

}  // namespace mjarm
