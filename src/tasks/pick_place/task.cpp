#include "mjarm/tasks/pick_place/task.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/sim/weld_grasp.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {

GraspKind grasp_kind(std::string_view name) {
  if (name == "weld") return GraspKind::weld;
  if (name == "friction") return GraspKind::friction;
  throw Error("unknown grasp '" + std::string(name) +
              "'; choices: weld (a weld switched on where the object is), friction (finger "
              "contact forces only)");
}

void check(const PickPlaceMotion& m) {
  check_fields(m);  // the limits too, as "pick and place: limits.max_velocity …"
  if (m.approach_height < m.descend_height)
    throw Error("pick and place: approach_height must be ≥ descend_height");
}

namespace {

constexpr int kStates = 14;

int index(PickPlaceState s) noexcept { return static_cast<int>(s); }

const PickPlaceGoal& checked_goal(const PickPlaceGoal& goal, const PickPlaceMotion& motion,
                                  const Chain& arm) {
  check(motion);
  if (!goal.object.allFinite() || !goal.target.allFinite() || !goal.R_grasp.allFinite() ||
      !goal.X_WS.p.allFinite() || !goal.X_WS.R.allFinite())
    throw Error("pick and place: the goal's points and poses must be finite");
  if (goal.posture.size() != 0 && goal.posture.size() != arm.size())
    throw Error("pick and place: the posture needs " + std::to_string(arm.size()) +
                " joint values (the arm chain), got " + std::to_string(goal.posture.size()));
  if (!(std::isfinite(goal.velocity_lag) && goal.velocity_lag >= 0.0))
    throw Error("pick and place: velocity_lag must be finite and ≥ 0 [s]");
  return goal;
}

Pose at(const Eigen::Vector3d& point, double height, const Eigen::Matrix3d& R) {
  Pose X;
  X.R = R;
  X.p = point + Eigen::Vector3d(0.0, 0.0, height);
  return X;
}

std::array<CartesianTrapezoid, 5> segments_of(const PickPlaceGoal& g, const PickPlaceMotion& m) {
  const Pose above = at(g.object, m.approach_height, g.R_grasp);
  const Pose grasp = at(g.object, m.descend_height, g.R_grasp);
  const Pose lifted = at(g.object, m.lift_height, g.R_grasp);
  const Pose over = at(g.target, m.move_height, g.R_grasp);
  const Pose release = at(g.target, m.place_height, g.R_grasp);
  return {CartesianTrapezoid(g.X_WS, above, m.limits), CartesianTrapezoid(above, grasp, m.limits),
          CartesianTrapezoid(grasp, lifted, m.limits), CartesianTrapezoid(lifted, over, m.limits),
          CartesianTrapezoid(over, release, m.limits)};
}

// the segment a moving state samples (−1: none), and the one whose goal a resting state holds
int segment_of(PickPlaceState s) noexcept {
  switch (s) {
    case PickPlaceState::approach:
      return 0;
    case PickPlaceState::descend:
      return 1;
    case PickPlaceState::lift:
      return 2;
    case PickPlaceState::move:
      return 3;
    case PickPlaceState::place:
      return 4;
    default:
      return -1;
  }
}

int held_segment(PickPlaceState s) noexcept {
  switch (s) {
    case PickPlaceState::dwell_a:
      return 0;
    case PickPlaceState::dwell_b:
    case PickPlaceState::grasp:
    case PickPlaceState::dwell_c:
      return 1;
    case PickPlaceState::dwell_d:
      return 2;
    case PickPlaceState::dwell_e:
      return 3;
    default:
      return 4;  // DWELL_F, RELEASE, DONE
  }
}

bool transporting(PickPlaceState s) noexcept {
  return index(s) >= index(PickPlaceState::lift) && index(s) <= index(PickPlaceState::dwell_f);
}

}  // namespace

PickPlaceTask::PickPlaceTask(Simulation& simulation, const Chain& arm, const PickPlaceGoal& goal,
                             const PickPlaceMotion& motion, GraspMonitor& monitor, WeldGrasp* weld,
                             int table_watch, Recorder* recorder)
    : simulation_(&simulation),
      arm_(arm),
      goal_(checked_goal(goal, motion, arm)),
      motion_(motion),
      monitor_(&monitor),
      weld_(weld),
      table_watch_(table_watch),
      recorder_(recorder),
      segments_(segments_of(goal, motion)) {
  if (goal.grasp == GraspKind::weld && weld == nullptr)
    throw Error("pick and place: the weld grasp needs a WeldGrasp");
  try {
    (void)simulation.contacts(table_watch);
  } catch (const std::out_of_range&) {
    throw Error("pick and place: contact watch " + std::to_string(table_watch) +
                " is not one of this simulation's (Simulation::watch_contacts)");
  }
  const double durations[kStates] = {
      segments_[0].duration(), motion.dwell_time, segments_[1].duration(), motion.dwell_time,
      motion.grip_time,        motion.dwell_time, segments_[2].duration(), motion.dwell_time,
      segments_[3].duration(), motion.dwell_time, segments_[4].duration(), motion.dwell_time,
      motion.release_time,     motion.settle_time};
  schedule_[0] = 0.0;
  for (int s = 0; s < kStates; ++s) schedule_[s + 1] = schedule_[s] + durations[s];
  saturation_run_.assign(static_cast<std::size_t>(simulation.model().nu), 0);
}

void PickPlaceTask::grasp_event(double t, const char* what) noexcept {
  if (recorder_ != nullptr) recorder_->event(trace_.start_time + t, "grasp", what);
}

void PickPlaceTask::enter(PickPlaceState state, double t) noexcept {
  trace_.state = state;
  if (recorder_ != nullptr) recorder_->event(trace_.start_time + t, "phase", to_string(state));
  const GraspReading& r = monitor_->reading();
  switch (state) {
    case PickPlaceState::dwell_c: {
      // the fingers have closed: the grasp is made where the object is now
      trace_.closed = r.finger1_contacts > 0 && r.finger2_contacts > 0;
      trace_.closing_force = r.force;
      monitor_->close();
      if (trace_.closed)
        std::snprintf(message_.data(), message_.size(),
                      "closed: both fingers touch, grasp force %.3f N", r.force);
      else
        std::snprintf(message_.data(), message_.size(),
                      "not closed: finger contacts %d and %d, grasp force %.3f N",
                      r.finger1_contacts, r.finger2_contacts, r.force);
      grasp_event(t, message_.data());
      if (goal_.grasp == GraspKind::weld && weld_ != nullptr) {
        trace_.welded = weld_->activate();
        trace_.weld_jump = trace_.weld_settle = 0.0;
        const mjData& d = simulation_->data();
        p_weld_ = Eigen::Map<const Eigen::Vector3d>(d.xpos + 3 * weld_->body2());
        mjtNum velocity[6];  // [ω; v] at the body frame's origin, world axes
        mj_objectVelocity(&simulation_->model(), &d, mjOBJ_XBODY, weld_->body2(), velocity, 0);
        v_weld_ = Eigen::Vector3d(velocity[3], velocity[4], velocity[5]);
        const Eigen::Vector3d& p = weld_->relative_pose().p;
        if (trace_.welded)
          std::snprintf(message_.data(), message_.size(),
                        "welded: object at (%.4f, %.4f, %.4f) m in the gripper frame", p.x(), p.y(),
                        p.z());
        grasp_event(
            t, trace_.welded ? message_.data() : "weld not switched on: the state is not finite");
      }
      break;
    }
    case PickPlaceState::release: {
      if (weld_ != nullptr) weld_->release();
      monitor_->open();
      std::snprintf(message_.data(), message_.size(),
                    "released: %sfingers opening, largest slip %.3f mm",
                    goal_.grasp == GraspKind::weld ? "weld off, " : "", trace_.max_slip * 1e3);
      grasp_event(t, message_.data());
      break;
    }
    case PickPlaceState::done:
      trace_.done_time = t;
      break;
    default:
      break;
  }
}

bool PickPlaceTask::update(const mjData& data, Reference& reference) noexcept {
  if (!started_) {
    started_ = true;
    trace_.start_time = data.time;
    enter(PickPlaceState::approach, 0.0);
  }
  if (observer_ != nullptr) observer_->on_tick(data);
  const double t = data.time - trace_.start_time;
  // the state changes due by now (a long control period may pass several)
  while (index(trace_.state) < kStates - 1 && t >= schedule_[index(trace_.state) + 1]) {
    const int next = index(trace_.state) + 1;
    enter(static_cast<PickPlaceState>(next), schedule_[next]);
  }
  if (trace_.state == PickPlaceState::done && t >= schedule_[kStates]) return false;
  const PickPlaceState state = trace_.state;
  const double since = t - schedule_[index(state)];

  // the grasp: slip, drop and force
  const GraspEvent event = monitor_->update();
  const GraspReading& r = monitor_->reading();
  if (r.closed) trace_.max_slip = std::max(trace_.max_slip, r.slip);
  if (event != GraspEvent::none) {
    if (event == GraspEvent::dropped) {
      trace_.dropped = true;
      trace_.dropped_time = t;
    }
    trace_.slipped = true;
    std::snprintf(message_.data(), message_.size(),
                  "%s: the object moved %.3f mm from its grasped pose (%.2f mm/s relative to the "
                  "gripper) in %s",
                  to_string(event), r.slip * 1e3, r.slip_speed * 1e3, to_string(state));
    grasp_event(t, message_.data());
  }
  if (transporting(state)) {
    force_sum_ += r.force;
    ++force_samples_;
    trace_.transport_force_mean = force_sum_ / static_cast<double>(force_samples_);
    trace_.transport_force_max = std::isnan(trace_.transport_force_max)
                                     ? r.force
                                     : std::max(trace_.transport_force_max, r.force);
  }
  if (state == PickPlaceState::dwell_c && trace_.welded) {
    trace_.weld_settle = std::max(trace_.weld_settle, weld_->deviation());
    if (since <= kWeldJumpWindow) {
      const Eigen::Map<const Eigen::Vector3d> p(data.xpos + 3 * weld_->body2());
      trace_.weld_jump = std::max(trace_.weld_jump, (p - p_weld_ - since * v_weld_).norm());
    }
  }

  // the criteria the whole run is held to: the table, the actuators
  if (!trace_.table_contact && simulation_->contacts(table_watch_).contacts > 0) {
    trace_.table_contact = true;
    trace_.table_contact_time = t;
    const ContactSummary& c = simulation_->contacts(table_watch_);
    const char* geom = mj_id2name(&simulation_->model(), mjOBJ_GEOM, c.first_geom_a);
    std::snprintf(message_.data(), message_.size(), "robot geom '%s' touched the table in %s",
                  geom != nullptr ? geom : "?", to_string(state));
    if (recorder_ != nullptr) recorder_->event(data.time, "table_contact", message_.data());
  }
  const std::span<const std::uint8_t> saturated = simulation_->saturated();
  for (std::size_t a = 0; a < saturation_run_.size() && a < saturated.size(); ++a) {
    saturation_run_[a] = saturated[a] != 0 ? saturation_run_[a] + 1 : 0;
    if (saturation_run_[a] > trace_.longest_saturation) {
      trace_.longest_saturation = saturation_run_[a];
      trace_.saturated_actuator = static_cast<int>(a);
    }
  }

  // the reference
  const int moving = segment_of(state);
  TaskReference& task = reference.task;
  if (moving >= 0) {
    const CartesianTrapezoid& segment = segments_[static_cast<std::size_t>(moving)];
    task.X_WE = segment.at(since).X_WE;
    const CartesianTrapezoid::Sample lagged = segment.at(since - goal_.velocity_lag);
    task.V_WE = lagged.V_WE;
    task.A_WE = lagged.A_WE;
  } else {
    task.X_WE = segments_[static_cast<std::size_t>(held_segment(state))].goal();
    task.V_WE.setZero();
    task.A_WE.setZero();
  }
  task.F_ext.setZero();
  if (index(state) < index(PickPlaceState::grasp)) {
    reference.gripper = 0.0;
  } else if (state == PickPlaceState::grasp) {
    reference.gripper = smoothstep(since / motion_.grip_time).s;
  } else if (state == PickPlaceState::release) {
    reference.gripper = 1.0 - smoothstep(since / motion_.release_time).s;
  } else if (state == PickPlaceState::done) {
    reference.gripper = 0.0;
  } else {
    reference.gripper = 1.0;
  }
  if (goal_.posture.size() == arm_.size()) reference.joint.q = goal_.posture;
  return true;
}

}  // namespace mjarm
