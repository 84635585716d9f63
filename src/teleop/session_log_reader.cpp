// The reader of session files (their writer is session_log.cpp): on its own so that a program
// that only reads them (the fuzz targets, fuzz/) links no simulation.

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/teleop/session_log.hpp"
#include "session_format.hpp"

namespace mjarm {

namespace {

SimulationMode parse_mode(const std::string& text, const std::string& where) {
  if (const auto mode = enum_from_name<SimulationMode>(text)) return *mode;
  throw Error(where + ": " + unknown_name_message("mode", text, enum_names<SimulationMode>()));
}

HandTask parse_task(const std::string& text, const std::string& where) {
  const auto colon = text.find(':');
  HandTask t;
  if (const auto kind = enum_from_name<TargetKind>(text.substr(0, colon))) {
    t.kind = *kind;
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
    const auto v = number_from_text(w);
    if (!v || !std::isfinite(*v))
      throw Error(where() + ": " + what + " must be a finite number, got '" + w + "'");
    return *v;
  }
  std::int64_t integer(const char* what) {
    const std::string w = word(what);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(w.c_str(), &end, 10);
    if (end == w.c_str() || *end != '\0' || v < 0 || errno == ERANGE)
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

SessionLog read_session_log(const std::filesystem::path& path) {
  return parse_session_log(read_user_file(path, "teleop session"), path.string());
}

SessionLog parse_session_log(std::string_view text, const std::string& file) {
  // every record ends with a newline: a file that does not was cut off mid-line
  if (!text.empty() && text.back() != '\n') {
    const auto lines = std::count(text.begin(), text.end(), '\n') + 1;
    throw Error("session file '" + file + "' is truncated: its last line (line " +
                std::to_string(lines) + ") is incomplete");
  }
  std::istringstream lines{std::string(text)};
  LineReader r;
  r.file = file;
  std::string line;
  auto next = [&](const char* what) {
    if (!std::getline(lines, line))
      throw Error("session file '" + r.file + "' is truncated: it ends before " + what);
    ++r.line;
    r.fields = std::istringstream(line);
  };
  SessionLog log;
  next("its header");
  if (r.word("the header") != kSessionFileMagic)
    throw Error("'" + r.file + "' is not a teleop session file (it should start with '" +
                kSessionFileMagic + " 1')");
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
      // compared before the cast: 4294967297 became hand 1
      const std::int64_t hand = r.integer("the hand");
      if (hand >= static_cast<std::int64_t>(log.options.hands.size()))
        throw Error(r.where() + ": no hand " + std::to_string(hand) + " (the session has " +
                    std::to_string(log.options.hands.size()) + ")");
      e.hand = static_cast<int>(hand);
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
                (log.events.empty()
                     ? std::string()
                     : "; its last event is at tick " + std::to_string(log.events.back().tick)));
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

}  // namespace mjarm
