// Session files: a recorded session (targets, a mode switch, a task change, a reset) survives the
// file exactly and replays to the same state bit for bit; a truncated file, a file from another
// model and malformed records are clear errors.
#include "mjarm/teleop/session_log.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "mjarm/error.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

// a short session on dual_arm: the left hand moves, the mode switches to motor, the right hand
// becomes a position target at priority 1, a reset, more motion
SessionLog record_short_session(const Robot& robot) {
  TeleopOptions o;
  o.mode = SimulationMode::position;
  TeleopSession session(robot, o);
  SessionRecorder recorder(session);
  TeleopTargets t = session.initial_targets();
  t.hands[0].X_WT.p.z() -= 0.05;
  t.hands[1].gripper = 0.7;
  t.lift = 0.3;
  recorder.set_targets(t);
  EXPECT_EQ(recorder.step(60), 60);
  recorder.set_mode(SimulationMode::torque);
  recorder.set_task(1, HandTask{TargetKind::position, 1});
  EXPECT_EQ(recorder.step(40), 40);
  recorder.reset();
  t.hands[1].X_WT.p.x() += 0.05;
  recorder.set_targets(t);
  EXPECT_EQ(recorder.step(50), 50);
  return recorder.log();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(SessionLog, FileRoundTripAndReplayAreExact) {
  const Robot robot = Robot::bundled("dual_arm");
  const SessionLog log = record_short_session(robot);
  ASSERT_EQ(log.events.size(), 6u);  // initial targets, targets, mode, task, reset, targets
  EXPECT_EQ(log.ticks, 150);
  const fs::path path = test::scratch() / "short.session";
  write_session_log(log, path);
  const SessionLog back = read_session_log(path);
  EXPECT_EQ(back.model, "dual_arm");
  EXPECT_EQ(back.fingerprint, log.fingerprint);
  EXPECT_EQ(back.ticks, log.ticks);
  EXPECT_EQ(back.digest, log.digest);
  ASSERT_EQ(back.events.size(), log.events.size());
  for (std::size_t k = 0; k < log.events.size(); ++k) {
    EXPECT_EQ(back.events[k].tick, log.events[k].tick) << k;
    EXPECT_EQ(back.events[k].kind, log.events[k].kind) << k;
    if (log.events[k].kind != SessionEvent::Kind::targets) continue;
    for (std::size_t i = 0; i < 2; ++i) {  // bit for bit
      EXPECT_EQ(back.events[k].targets.hands[i].X_WT.p, log.events[k].targets.hands[i].X_WT.p);
      EXPECT_EQ(back.events[k].targets.hands[i].X_WT.R, log.events[k].targets.hands[i].X_WT.R);
      EXPECT_EQ(back.events[k].targets.hands[i].gripper, log.events[k].targets.hands[i].gripper);
    }
  }
  EXPECT_EQ(back.options.tasks.size(), 2u);
  const ReplayResult replay = replay_session(robot, back);
  EXPECT_TRUE(replay.matches) << replay.digest << " vs " << log.digest;
  EXPECT_EQ(replay.stats.mode, SimulationMode::torque);
}

TEST(SessionLog, TruncatedFilesAreRefused) {
  const Robot robot = Robot::bundled("dual_arm");
  const fs::path path = test::scratch() / "whole.session";
  write_session_log(record_short_session(robot), path);
  const std::string text = test::slurp(path);
  // cut after every line but the last, and in the middle of an event line
  std::vector<std::size_t> cuts;
  for (std::size_t p = text.find('\n'); p + 1 < text.size(); p = text.find('\n', p + 1))
    cuts.push_back(p + 1);
  const std::size_t event = text.find(" targets ", text.find("\nevents"));
  cuts.push_back(event + 40);
  ASSERT_GT(cuts.size(), 12u);
  const fs::path cut = test::scratch() / "cut.session";
  for (const std::size_t n : cuts) {
    write_text(cut, text.substr(0, n));
    const std::string message = test::error_of([&] { read_session_log(cut); });
    EXPECT_TRUE(message.find("truncated") != std::string::npos ||
                message.find("missing") != std::string::npos)
        << "cut at " << n << ": " << message;
    EXPECT_NE(message.find("cut.session"), std::string::npos) << message;
  }
  write_text(cut, "");
  EXPECT_NE(test::error_of([&] { read_session_log(cut); }).find("truncated"), std::string::npos);
}

// issue 29, item 11: `end 99999999999` made `replay` tick toward 10¹¹; such a count is refused
// when the file is read, before a model loads or a tick runs
TEST(SessionLog, ATickCountBeyondTheBoundIsRefusedWhenRead) {
  const Robot robot = Robot::bundled("dual_arm");
  const fs::path path = test::scratch() / "long.session";
  write_session_log(record_short_session(robot), path);
  std::string text = test::slurp(path);
  const std::size_t end = text.rfind("end ");
  const std::size_t digest = text.find(' ', end + 4);
  const std::string last_event = text.substr(0, end);
  text = text.substr(0, end) + "end 99999999999" + text.substr(digest);
  write_text(path, text);
  const std::string message = test::error_of([&] { read_session_log(path); });
  EXPECT_NE(message.find("the session ends at tick 99999999999, beyond the 10000000 ticks a "
                         "session may have"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("its last event is at tick"), std::string::npos) << message;
  // at the bound it reads
  text =
      last_event + "end " + std::to_string(kMaxSessionTicks) + text.substr(text.find(' ', end + 4));
  write_text(path, text);
  EXPECT_EQ(read_session_log(path).ticks, kMaxSessionTicks);
}

TEST(SessionLog, AnotherModelIsRefused) {
  const Robot robot = Robot::bundled("dual_arm");
  const SessionLog log = record_short_session(robot);
  const std::string message =
      test::error_of([&] { replay_session(Robot::bundled("dual_arm_box"), log); });
  EXPECT_NE(message.find("recorded on model 'dual_arm'"), std::string::npos) << message;
  EXPECT_NE(message.find("not on 'dual_arm_box'"), std::string::npos) << message;
  EXPECT_THROW(replay_session(Robot::bundled("panda"), log), Error);
}

TEST(SessionLog, MalformedFilesAreClearErrors) {
  const Robot robot = Robot::bundled("dual_arm");
  const fs::path path = test::scratch() / "good.session";
  write_session_log(record_short_session(robot), path);
  const std::string text = test::slurp(path);
  const fs::path bad = test::scratch() / "bad.session";
  auto error_with = [&](const std::string& from, const std::string& to) {
    std::string edited = text;
    const auto at = edited.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    edited.replace(at, from.size(), to);
    write_text(bad, edited);
    return test::error_of([&] { read_session_log(bad); });
  };
  EXPECT_NE(error_with("mjarm-teleop-session", "hello").find("not a teleop session file"),
            std::string::npos);
  EXPECT_NE(error_with("mode position", "mode fast").find("unknown mode 'fast'"),
            std::string::npos);
  EXPECT_NE(error_with("0 targets 0.20", "0 targets nan").find("finite number"), std::string::npos);
  EXPECT_NE(error_with(" reset", " jump").find("unknown event 'jump'"), std::string::npos);
  EXPECT_NE(error_with(" reset", " rest")
                .find("unknown event 'rest'; closest: reset; events: "
                      "targets, mode, task, reset"),
            std::string::npos);
  EXPECT_NE(error_with("tasks pose:0", "tasks grip:0").find("pose:<priority>"), std::string::npos);
  EXPECT_NE(error_with("events 6", "events 7").find("announces 7 events but ends after 6"),
            std::string::npos);
  EXPECT_NE(error_with("events 6", "events 5").find("expected the end line after 5 events"),
            std::string::npos);
  // fuzz finding: a hand number beyond int was cast first (4294967297 became hand 1)
  EXPECT_NE(
      error_with(" task 1 ", " task 4294967297 ").find("no hand 4294967297 (the session has 2)"),
      std::string::npos);
  EXPECT_NE(error_with(" task 1 ", " task 99999999999999999999 ").find("must be a whole number"),
            std::string::npos);
  EXPECT_NE(error_with("fingerprint ", "fingerprint 1 ").find("line 3"), std::string::npos);
  write_text(bad, "mjarm-teleop-session 1\nmodel x\n");
  EXPECT_NE(test::error_of([&] { read_session_log(bad); }).find("ends before the fingerprint"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] { read_session_log(test::scratch() / "absent.session"); }), "");
}

// issue 29, item 1 for sessions: records after the end line were dropped without a word (a
// session appended to another one replayed only the first)
TEST(SessionLog, RecordsAfterTheEndLineAreRefused) {
  const Robot robot = Robot::bundled("dual_arm");
  const fs::path path = test::scratch() / "ended.session";
  write_session_log(record_short_session(robot), path);
  const std::string text = test::slurp(path);
  const auto lines = std::count(text.begin(), text.end(), '\n');
  // blank lines after it hold nothing
  write_text(path, text + "\n  \n");
  EXPECT_EQ(read_session_log(path).ticks, 150);
  write_text(path, text + "\n150 reset\n");
  const std::string message = test::error_of([&] { read_session_log(path); });
  EXPECT_NE(
      message.find("session file '" + path.string() + "' line " + std::to_string(lines + 2) +
                   ": '150 reset' after the end line; the end line is the file's last record"),
      std::string::npos)
      << message;
  write_text(path, text + text);
  EXPECT_NE(test::error_of([&] {
              read_session_log(path);
            }).find("'mjarm-teleop-session 1' after the end line"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
