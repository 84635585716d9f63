#include "mjarm/teleop/session_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "teleop_model.hpp"

namespace mjarm {

namespace {

constexpr const char* kMagic = "mjarm-teleop-session";

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

SimulationMode parse_mode(const std::string& text, const std::string& where) {
  for (int k = 0; k < 3; ++k) {
    if (text == to_string(static_cast<SimulationMode>(k))) return static_cast<SimulationMode>(k);
  }
  throw Error(where + ": " +
              unknown_name_message("mode", text, {"kinematic", "position", "torque"}));
}

std::string task_text(const HandTask& t) {
  return std::string(t.kind == TargetKind::pose ? "pose" : "position") + ":" +
         std::to_string(t.priority);
}

HandTask parse_task(const std::string& text, const std::string& where) {
  const auto colon = text.find(':');
  HandTask t;
  const std::string kind = text.substr(0, colon);
  if (kind == "pose") {
    t.kind = TargetKind::pose;
  } else if (kind == "position") {
    t.kind = TargetKind::position;
  } else {
    throw Error(where + ": a hand task must be pose:<priority> or position:<priority>, got '" +
                text + "'");
  }
  try {
    t.priority = colon == std::string::npos ? -1 : std::stoi(text.substr(colon + 1));
  } catch (const std::exception&) {
    t.priority = -1;
  }
  if (t.priority < 0) throw Error(where + ": bad priority in '" + text + "'");
  return t;
}

// a reader of whitespace-separated fields that names the file and line in its errors
struct LineReader {
  std::string file;
  int line = 0;
  std::istringstream fields;

  std::string where() const { return "session file '" + file + "' line " + std::to_string(line); }
  std::string word(const char* what) {
    std::string w;
    if (!(fields >> w)) throw Error(where() + ": missing " + what);
    return w;
  }
  double real(const char* what) {
    const std::string w = word(what);
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0' || !std::isfinite(v))
      throw Error(where() + ": " + what + " must be a finite number, got '" + w + "'");
    return v;
  }
  std::int64_t integer(const char* what) {
    const std::string w = word(what);
    char* end = nullptr;
    const long long v = std::strtoll(w.c_str(), &end, 10);
    if (end == w.c_str() || *end != '\0' || v < 0)
      throw Error(where() + ": " + what + " must be a whole number ≥ 0, got '" + w + "'");
    return v;
  }
  void expect(const std::string& key) {
    const std::string w = word(key.c_str());
    if (w != key) throw Error(where() + ": expected '" + key + "', got '" + w + "'");
  }
  void done() {
    std::string extra;
    if (fields >> extra) throw Error(where() + ": unexpected '" + extra + "'");
  }
};

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
  text += std::string(kMagic) + " 1\nmodel " + log.model + "\nfingerprint " + log.fingerprint +
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

SessionLog read_session_log(const std::filesystem::path& path) {
  const std::string text = read_user_file(path, "teleop session");
  // every record ends with a newline: a file that does not was cut off mid-line
  if (!text.empty() && text.back() != '\n') {
    const auto lines = std::count(text.begin(), text.end(), '\n') + 1;
    throw Error("session file '" + path.string() + "' is truncated: its last line (line " +
                std::to_string(lines) + ") is incomplete");
  }
  std::istringstream lines(text);
  LineReader r;
  r.file = path.string();
  std::string line;
  auto next = [&](const char* what) {
    if (!std::getline(lines, line))
      throw Error("session file '" + r.file + "' is truncated: it ends before " + what);
    ++r.line;
    r.fields = std::istringstream(line);
  };
  SessionLog log;
  next("its header");
  if (r.word("the header") != kMagic)
    throw Error("'" + r.file + "' is not a teleop session file (it should start with '" + kMagic +
                " 1')");
  if (r.word("the version") != "1") throw Error(r.where() + ": unsupported version");
  next("the model");
  r.expect("model");
  log.model = r.word("the model name");
  r.done();
  next("the fingerprint");
  r.expect("fingerprint");
  for (int i = 0; i < 4; ++i) log.fingerprint += (i ? " " : "") + r.word("the fingerprint");
  r.done();
  next("the hands");
  r.expect("hands");
  std::string hand;
  while (r.fields >> hand) {
    const auto colon = hand.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == hand.size())
      throw Error(r.where() + ": a hand must be name:frame, got '" + hand + "'");
    log.options.hands.push_back({hand.substr(0, colon), hand.substr(colon + 1), {}});
  }
  if (log.options.hands.empty()) throw Error(r.where() + ": no hands");
  next("the lift");
  r.expect("lift");
  log.options.lift = r.word("the lift joint");
  if (log.options.lift == "-") log.options.lift.clear();
  log.options.lift_in_ik = r.integer("lift_in_ik") != 0;
  r.done();
  next("the keyframe");
  r.expect("keyframe");
  log.options.keyframe = r.word("the keyframe");
  if (log.options.keyframe == "-") log.options.keyframe.clear();
  r.done();
  next("the mode");
  r.expect("mode");
  log.options.mode = parse_mode(r.word("the mode"), r.where());
  r.done();
  next("the periods");
  r.expect("periods");
  log.options.kinematic_period = r.real("the kinematic period");
  log.options.control_period = r.real("the control period");
  r.done();
  next("the tasks");
  r.expect("tasks");
  std::string task;
  while (r.fields >> task) log.options.tasks.push_back(parse_task(task, r.where()));
  if (log.options.tasks.size() != log.options.hands.size())
    throw Error(r.where() + ": " + std::to_string(log.options.tasks.size()) + " tasks for " +
                std::to_string(log.options.hands.size()) + " hands");
  next("the event count");
  r.expect("events");
  const std::int64_t count = r.integer("the event count");
  r.done();
  for (std::int64_t k = 0; k < count; ++k) {
    next(("event " + std::to_string(k + 1) + " of " + std::to_string(count)).c_str());
    SessionEvent e;
    if (line.rfind("end", 0) == 0)
      throw Error(r.where() + ": the file announces " + std::to_string(count) +
                  " events but ends after " + std::to_string(k));
    e.tick = r.integer("the tick");
    if (!log.events.empty() && e.tick < log.events.back().tick)
      throw Error(r.where() + ": tick " + std::to_string(e.tick) + " comes before the one above");
    const std::string kind = r.word("the event kind");
    if (kind == "targets") {
      e.kind = SessionEvent::Kind::targets;
      e.targets.lift = r.real("the lift");
      for (std::size_t i = 0; i < log.options.hands.size(); ++i) {
        HandTarget h;
        h.X_WT.p.x() = r.real("x");
        h.X_WT.p.y() = r.real("y");
        h.X_WT.p.z() = r.real("z");
        for (int row = 0; row < 3; ++row)
          for (int col = 0; col < 3; ++col) h.X_WT.R(row, col) = r.real("a rotation entry");
        if (!is_valid_pose(h.X_WT))
          throw Error(r.where() + ": the rotation of hand " + std::to_string(i) +
                      " is not a rotation matrix");
        h.gripper = r.real("the gripper command");
        e.targets.hands.push_back(h);
      }
    } else if (kind == "mode") {
      e.kind = SessionEvent::Kind::mode;
      e.mode = parse_mode(r.word("the mode"), r.where());
    } else if (kind == "task") {
      e.kind = SessionEvent::Kind::task;
      e.hand = static_cast<int>(r.integer("the hand"));
      if (e.hand >= static_cast<int>(log.options.hands.size()))
        throw Error(r.where() + ": no hand " + std::to_string(e.hand));
      e.task = parse_task(r.word("the task"), r.where());
    } else if (kind == "reset") {
      e.kind = SessionEvent::Kind::reset;
    } else {
      throw Error(r.where() + ": " +
                  unknown_name_message("event", kind, {"targets", "mode", "task", "reset"}));
    }
    r.done();
    log.events.push_back(std::move(e));
  }
  next("its end line");
  if (r.word("the end line") != "end")
    throw Error(r.where() + ": expected the end line after " + std::to_string(count) + " events");
  log.ticks = r.integer("the tick count");
  if (log.ticks > kMaxSessionTicks)
    throw Error(r.where() + ": the session ends at tick " + std::to_string(log.ticks) +
                ", beyond the " + std::to_string(kMaxSessionTicks) +
                " ticks a session may have (a replay simulates about 20000 a second)" +
                (log.events.empty() ? std::string()
                                    : "; its last event is at tick " +
                                          std::to_string(log.events.back().tick)));
  log.digest = r.word("the final digest");
  r.done();
  if (!log.events.empty() && log.events.back().tick > log.ticks)
    throw Error(r.where() + ": an event comes after the last tick");
  // the end line ends the file: records after it would be dropped without a word
  while (std::getline(lines, line)) {
    ++r.line;
    if (line.find_first_not_of(" \t\r") != std::string::npos)
      throw Error(r.where() + ": '" + line.substr(0, 40) + (line.size() > 40 ? "…" : "") +
                  "' after the end line; the end line is the file's last record");
  }
  return log;
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
