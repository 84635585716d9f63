#include "mjarm/teleop/session_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "session_format.hpp"
#include "teleop_model.hpp"

namespace mjarm {

namespace {

std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::string hex(std::uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

std::string exact_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

const char* mode_name(SimulationMode m) { return to_string(m); }

std::string task_text(const HandTask& t) {
  return std::string(to_string(t.kind)) + ":" + std::to_string(t.priority);
}

}  // namespace

std::string model_fingerprint(const Robot& robot) {
  const mjModel& m = robot.model();
  std::uint64_t h = fnv1a("", 0);
  for (int j = 0; j < m.njnt; ++j) {
    const char* n = mj_id2name(&m, mjOBJ_JOINT, j);
    if (n != nullptr) h = fnv1a(n, std::strlen(n) + 1, h);
  }
  for (int a = 0; a < m.nu; ++a) {
    const char* n = mj_id2name(&m, mjOBJ_ACTUATOR, a);
    if (n != nullptr) h = fnv1a(n, std::strlen(n) + 1, h);
  }
  return std::to_string(m.nq) + " " + std::to_string(m.nv) + " " + std::to_string(m.nu) + " " +
         hex(h);
}

std::string state_digest(const TeleopSession& session) {
  const mjData& d = session.simulation().data();
  const mjModel& m = session.robot().model();
  std::uint64_t h = fnv1a(d.qpos, sizeof(double) * static_cast<std::size_t>(m.nq));
  h = fnv1a(d.qvel, sizeof(double) * static_cast<std::size_t>(m.nv), h);
  return hex(h);
}

void write_session_log(const SessionLog& log, const std::filesystem::path& path) {
  FileWriter out(path, FileWriter::Mode::replace, "teleop session");
  write_session_log(log, out);
}

void write_session_log(const SessionLog& log, FileWriter& out) {
  std::string text;
  const TeleopOptions& o = log.options;
  text += std::string(kSessionFileMagic) + " 1\nmodel " + log.model + "\nfingerprint " + log.fingerprint +
          "\nhands";
  for (const auto& h : o.hands) text += " " + h.name + ":" + h.frame;
  text += "\nlift " + (o.lift.empty() ? std::string("-") : o.lift) + " " +
          (o.lift_in_ik ? "1" : "0") + "\nkeyframe " +
          (o.keyframe.empty() ? std::string("-") : o.keyframe) + "\nmode " + mode_name(o.mode) +
          "\nperiods " + exact_text(o.kinematic_period) + " " + exact_text(o.control_period) +
          "\ntasks";
  for (const auto& t : o.tasks) text += " " + task_text(t);
  text += "\nevents " + std::to_string(log.events.size()) + "\n";
  for (const auto& e : log.events) {
    text += std::to_string(e.tick);
    switch (e.kind) {
      case SessionEvent::Kind::targets:
        text += " targets " + exact_text(e.targets.lift);
        for (const auto& h : e.targets.hands) {
          for (int k = 0; k < 3; ++k) text += " " + exact_text(h.X_WT.p[k]);
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) text += " " + exact_text(h.X_WT.R(r, c));
          text += " " + exact_text(h.gripper);
        }
        break;
      case SessionEvent::Kind::mode:
        text += std::string(" mode ") + mode_name(e.mode);
        break;
      case SessionEvent::Kind::task:
        text += " task " + std::to_string(e.hand) + " " + task_text(e.task);
        break;
      case SessionEvent::Kind::reset:
        text += " reset";
        break;
    }
    text += "\n";
  }
  text += "end " + std::to_string(log.ticks) + " " + log.digest + "\n";
  out.write(text);
  out.commit();
}

SessionRecorder::SessionRecorder(TeleopSession& session) : session_(session) {
  log_.model = session.robot().name();
  log_.fingerprint = model_fingerprint(session.robot());
  log_.options = session.options();
  log_.options.hands = session.hands();
  log_.options.mode = session.mode();
  log_.options.tasks = session.tasks();
  // the model name of the flavour the file names (the position one when recording in torque)
  const std::string& name = session.robot().name();
  const std::string suffix = "_torque";
  if (session.mode() == SimulationMode::torque && name.size() > suffix.size() &&
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
    log_.model = name.substr(0, name.size() - suffix.size());
  }
  SessionEvent e;
  e.targets = session.targets();
  log_.events.push_back(e);
}

void SessionRecorder::set_targets(const TeleopTargets& targets) {
  session_.set_targets(targets);
  SessionEvent e;
  e.tick = ticks_;
  e.targets = session_.targets();
  log_.events.push_back(e);
}

void SessionRecorder::set_mode(SimulationMode mode) {
  session_.set_mode(mode);
  SessionEvent e;
  e.tick = ticks_;
  e.kind = SessionEvent::Kind::mode;
  e.mode = mode;
  log_.events.push_back(e);
}

void SessionRecorder::set_task(int hand, const HandTask& task) {
  session_.set_task(hand, task);
  SessionEvent e;
  e.tick = ticks_;
  e.kind = SessionEvent::Kind::task;
  e.hand = hand;
  e.task = task;
  log_.events.push_back(e);
}

void SessionRecorder::reset() {
  session_.reset();
  SessionEvent e;
  e.tick = ticks_;
  e.kind = SessionEvent::Kind::reset;
  log_.events.push_back(e);
}

int SessionRecorder::step(int ticks) noexcept {
  const int done = session_.step(ticks);
  ticks_ += done;
  return done;
}

SessionLog SessionRecorder::log() const {
  SessionLog log = log_;
  log.ticks = ticks_;
  log.digest = state_digest(session_);
  return log;
}

SessionReplay::SessionReplay(const Robot& robot, const SessionLog& log) : log_(log) {
  const std::string fingerprint = model_fingerprint(robot);
  if (fingerprint != log.fingerprint) {
    throw Error("the session was recorded on model '" + log.model + "' (fingerprint " +
                log.fingerprint + "), not on '" + robot.name() + "' (fingerprint " + fingerprint +
                "): replay it with the model it was recorded on");
  }
  // a file names the hands' frames only: their fingers are found again on the model
  TeleopOptions options = log.options;
  for (auto& h : options.hands) {
    if (h.fingers.empty()) h.fingers = detail::gripper_joints(Chain(robot, h.frame));
  }
  session_ = std::make_unique<TeleopSession>(robot, options);
  apply_due();
}

void SessionReplay::apply_due() {
  for (; next_ < log_.events.size() && log_.events[next_].tick == tick_; ++next_) {
    const SessionEvent& e = log_.events[next_];
    switch (e.kind) {
      case SessionEvent::Kind::targets:
        session_->set_targets(e.targets);
        break;
      case SessionEvent::Kind::mode:
        session_->set_mode(e.mode);
        break;
      case SessionEvent::Kind::task:
        session_->set_task(e.hand, e.task);
        break;
      case SessionEvent::Kind::reset:
        session_->reset();
        break;
    }
  }
}

bool SessionReplay::step() {
  if (stopped_ || tick_ >= log_.ticks) return false;
  if (session_->step(1) != 1) {
    stopped_ = true;
    return false;
  }
  ++tick_;
  apply_due();
  return true;
}

ReplayResult SessionReplay::result() const {
  ReplayResult r;
  r.ticks = tick_;
  r.digest = state_digest(*session_);
  r.matches = r.digest == log_.digest && r.ticks == log_.ticks;
  r.stats = session_->stats();
  return r;
}

ReplayResult replay_session(const Robot& robot, const SessionLog& log) {
  SessionReplay replay(robot, log);
  while (replay.step()) {
  }
  return replay.result();
}

}  // namespace mjarm
