// `mjarm view` in a real window: a scripted session under an Xvfb of the test's own, with
// synthetic slider clicks, mouse drags and key presses, checked through its screenshots and its
// --json report; and the message when there is no display at all.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "executable_on_path.hpp"
#include "mjarm/address_sanitizer.hpp"
#include "mjarm/render/png.hpp"
#include "mjarm/teleop/session_log.hpp"
#include "mjarm/teleop/viewer_session.hpp"
#include "support/files.hpp"
#include "support/virtual_display.hpp"
#include "teleop/teleop_ui.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out;
  std::string err;
};

// runs a shell command, capturing stdout and stderr
Outcome run_command(const std::string& command, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  Outcome r;
  FILE* pipe = popen((command + " 2>'" + err.string() + "'").c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer{};
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    r.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  r.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return r;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("mjarm_viewer_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The environment prefix that gives a command the display: the X server of this test process,
// started on first use and stopped at exit (nullopt, and a failure, when it could not start).
std::optional<std::string> display_prefix() {
  static const test::VirtualDisplay server;
  if (server.display().empty()) {
    ADD_FAILURE() << server.error();
    return std::nullopt;
  }
  std::string prefix = "DISPLAY=" + server.display() + " ";
#if defined(MJARM_ADDRESS_SANITIZER)
  prefix += "ASAN_OPTIONS=detect_leaks=0 ";  // Mesa and X11 keep allocations until exit
#endif
  // a viewer that hangs fails the test instead of hanging it
  return prefix + "timeout -k 10 300 ";
}

/// Mean and standard deviation of every channel value (0…255) of an image.
struct ChannelStats {
  double mean = 0.0;
  double stddev = 0.0;
};

ChannelStats channel_stats(const Image& image) {
  double sum = 0.0, sum2 = 0.0;
  for (const std::uint8_t v : image.rgb) {
    sum += v;
    sum2 += static_cast<double>(v) * v;
  }
  const double n = static_cast<double>(image.rgb.size());
  ChannelStats s;
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
  return s;
}

// mean absolute difference per channel over the 3-D view (right of the panel, x ≥ x0)
double difference(const Image& a, const Image& b, int x0) {
  double sum = 0.0;
  std::size_t n = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = x0; x < a.width; ++x) {
      for (int c = 0; c < 3; ++c) sum += std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
      n += 3;
    }
  }
  return sum / static_cast<double>(n);
}

Eigen::Vector3d vec(const nlohmann::json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

TEST(ViewerWindow, ScriptedSessionMovesTheArmAndTakesScreenshots) {
  const auto prefix = display_prefix();
  if (!prefix) return;
  const fs::path dir = fresh_dir("script");
  {
    std::ofstream script(dir / "session.txt");
    // at --render-hz 10 a frame is 100 ms of simulated time (fewer frames to draw in software)
    script << "wait 2\n"
              "screenshot "
           << (dir / "a.png").string()
           << "\n"
              "slider x 0.8          # a synthetic click at 80 % of the x slider\n"
              "set z 0.45\n"
              "wait 15               # 1.5 s of simulated time\n"
              "screenshot "
           << (dir / "b.png").string()
           << "\n"
              "drag left 150 0       # orbit the camera\n"
              "scroll 2\n"
              "key space             # pause\n"
              "wait 3\n"
              "key right             # one control tick\n"
              "screenshot "
           << (dir / "c.png").string()
           << "\n"
              "key backspace         # reset (still paused)\n"
              "wait 2\n"
              "screenshot "
           << (dir / "d.png").string()
           << "\n"
              "key space\n"
              "set mode torque\n"
              "wait 5\n"
              "screenshot "
           << (dir / "e.png").string() << "\n";
  }
  const Outcome r = run_command(
      *prefix + "'" MJARM_CLI "' view panda --size 640x480 --render-hz 10 --json --script '" +
          (dir / "session.txt").string() + "'",
      dir);
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  const auto report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["ended_by"], "end of script");
  const auto& shots = report["screenshots"];
  ASSERT_EQ(shots.size(), 5u) << r.out;

  // every screenshot is a real picture of the window
  std::vector<Image> images;
  for (const auto& shot : shots) {
    images.push_back(read_png(shot["path"].get<std::string>()));
    const Image& image = images.back();
    ASSERT_EQ(image.width, 640);
    ASSERT_EQ(image.height, 480);
    const ChannelStats s = channel_stats(image);
    EXPECT_GT(s.stddev, 20.0) << shot["path"] << " looks blank";
    EXPECT_GT(s.mean, 20.0);
    EXPECT_LT(s.mean, 235.0);
  }

  // the slider click went through the panel: x at 80 % of its range (one division = 0.5 %)
  const ViewerSession session(Robot::bundled("panda"));
  const PanelRanges& ranges = session.ranges();
  const double expected_x = ranges.lower[0] + 0.8 * (ranges.upper[0] - ranges.lower[0]);
  const Eigen::Vector3d a_target = vec(shots[0]["target"]), b_target = vec(shots[1]["target"]);
  EXPECT_NEAR(b_target.x(), expected_x, 0.01 * (ranges.upper[0] - ranges.lower[0]));
  EXPECT_NEAR(b_target.z(), 0.45, 1e-12);
  EXPECT_NEAR(b_target.y(), a_target.y(), 1e-12);

  // the arm followed: it moved by more than 10 cm and sits on the target
  const Eigen::Vector3d a_ee = vec(shots[0]["end_effector"]), b_ee = vec(shots[1]["end_effector"]);
  EXPECT_GT((b_ee - a_ee).norm(), 0.1);
  EXPECT_LT((b_ee - b_target).norm(), 2e-3);
  const int panel_width = 250;  // the 3-D view starts right of the panel (≈ 270 px)
  EXPECT_GT(difference(images[0], images[1], panel_width + 20), 1.0) << "the arm moved on screen";

  // paused, then one step: the arm holds still while the camera drag changed the picture
  const double period = 0.01;  // kinematic mode
  EXPECT_NEAR(shots[2]["sim_time"].get<double>(), shots[1]["sim_time"].get<double>() + period,
              1e-9);
  EXPECT_LT((vec(shots[2]["end_effector"]) - b_ee).norm(), 1e-3);
  EXPECT_GT(difference(images[1], images[2], panel_width + 20), 1.0) << "the camera moved";

  // backspace reset: home again at time 0 (paused), the target back on the end effector
  EXPECT_DOUBLE_EQ(shots[3]["sim_time"].get<double>(), 0.0);
  EXPECT_LT((vec(shots[3]["end_effector"]) - a_ee).norm(), 1e-6);
  EXPECT_LT((vec(shots[3]["target"]) - a_target).norm(), 1e-9);

  // torque mode on panda_torque holds the home pose
  EXPECT_EQ(shots[4]["mode"], "torque");
  EXPECT_NEAR(shots[4]["sim_time"].get<double>(), 0.5, 0.11);  // ± a frame
  EXPECT_LT((vec(shots[4]["end_effector"]) - a_ee).norm(), 5e-3);
  EXPECT_EQ(report["mode"], "torque");
  EXPECT_TRUE(report["fault"].is_null());
  fs::remove_all(dir);
}

TEST(ViewerWindow, ScriptErrorsNameTheLine) {
  const auto prefix = display_prefix();
  if (!prefix) return;
  const fs::path dir = fresh_dir("bad");
  {
    std::ofstream script(dir / "bad.txt");
    script << "wait 1\nset x 99\n";
  }
  const Outcome r = run_command(*prefix + "'" MJARM_CLI "' view panda --size 640x480 --script '" +
                                    (dir / "bad.txt").string() + "'",
                                dir);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("line 2 (set)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("outside its slider range"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(ViewerWindow, FramesAreCountedExactlyWhateverTheRates) {
  // --frames 3 draws 3 frames even with 240 frames per input poll (the script used to resume
  // only at the next poll: 240 frames here, 50 at --render-hz 1000 with the default 20 Hz input)
  const auto prefix = display_prefix();
  if (!prefix) return;
  const fs::path dir = fresh_dir("frames");
  const Outcome r = run_command(*prefix + "'" MJARM_CLI
                                          "' view panda --size 320x240 --render-hz 240 "
                                          "--input-hz 1 --frames 3 --json",
                                dir);
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(nlohmann::json::accept(r.out)) << r.out;
  const auto report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["frames"], 3);
  EXPECT_EQ(report["ended_by"], "end of script");
  fs::remove_all(dir);
}

// The bimanual viewer on dual_arm: a slider click through mjui, key nudges of the selected hand,
// named edits (priority, mode, lift), a camera drag the camera section follows, a reset — all
// recorded; the session file replays headless to the window's final state bit for bit.
TEST(ViewerWindow, BimanualPanelEditsAndNudgesAreRecordedAndReplayExactly) {
  const auto prefix = display_prefix();
  if (!prefix) return;
  const fs::path dir = fresh_dir("bimanual");
  const fs::path session_file = dir / "run.session";
  {
    std::ofstream script(dir / "session.txt");
    script << "wait 2\n"
              "slider left.z 0.75         # a click at 75 % of the left hand's z slider\n"
              "key tab                    # the keys move the right hand\n"
              "key r\n"
              "key r                      # +2 cm in z\n"
              "key shift+a                # +0.087 rad roll\n"
              "key g                      # close its gripper\n"
              "set priority right-over-left\n"
              "wait 4\n"
              "set mode torque\n"
              "set lift 0.25\n"
              "wait 3\n"
              "drag left 120 0            # orbit: the camera section follows\n"
              "screenshot "
           << (dir / "a.png").string()
           << "\n"
              "key backspace              # reset: the hands' targets back where they started\n"
              "wait 2\n";
  }
  const Outcome r = run_command(*prefix +
                                    "'" MJARM_CLI
                                    "' view dual_arm --size 640x480 --render-hz 10 --json "
                                    "--script '" +
                                    (dir / "session.txt").string() + "' --record-session '" +
                                    session_file.string() + "'",
                                dir);
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  const auto report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["ended_by"], "end of script");
  EXPECT_EQ(report["mode"], "torque");
  EXPECT_EQ(report["priority"], "right-over-left");
  EXPECT_EQ(report["selected_hand"], "right");
  EXPECT_TRUE(report["fault"].is_null()) << report["fault"];

  // the edits reached the session as the panel shows them
  const Robot robot = Robot::bundled("dual_arm");
  const TeleopSession reference(robot);
  const std::vector<PanelRanges> ranges = teleop_ranges(reference);
  const Eigen::Vector3d left0 = reference.initial_targets().hands[0].X_WT.p;
  const Eigen::Vector3d right0 = reference.initial_targets().hands[1].X_WT.p;
  ASSERT_EQ(report["screenshots"].size(), 1u);
  const auto& shot = report["screenshots"][0];
  const auto& hands = shot["hands"];
  ASSERT_EQ(hands.size(), 2u);
  EXPECT_EQ(hands[0]["name"], "left");
  const double z_range = ranges[0].upper[2] - ranges[0].lower[2];
  EXPECT_NEAR(vec(hands[0]["target"]).z(), ranges[0].lower[2] + 0.75 * z_range, 0.01 * z_range);
  EXPECT_NEAR(vec(hands[0]["target"]).x(), left0.x(), 1e-12);
  EXPECT_NEAR(vec(hands[1]["target"]).z(), right0.z() + 0.02, 1e-12);
  EXPECT_NEAR(vec(hands[1]["target"]).y(), right0.y(), 1e-12);
  EXPECT_NEAR(shot["lift"].get<double>(), 0.25, 0.02);  // ramped towards 0.25 over 0.3 s
  EXPECT_GT(hands[1]["gripper"].get<double>(), 0.5);    // closing (0.5 s for a full stroke)
  EXPECT_NEAR(hands[0]["gripper"].get<double>(), 0.0, 1e-12);
  // the right hand is where it was asked (motor mode, 0.3 s after the switch)
  EXPECT_LT((vec(hands[1]["position"]) - vec(hands[1]["target"])).norm(), 0.01);
  const Image image = read_png(shot["path"].get<std::string>());
  const ChannelStats s = channel_stats(image);
  EXPECT_GT(s.stddev, 20.0) << "the screenshot looks blank";
  // the mouse moved the camera, and the camera section with it (front preset: azimuth 155°)
  EXPECT_GT(std::abs(report["camera"]["azimuth"].get<double>() - 155.0), 1.0);
  // after the reset the targets are the initial ones again
  EXPECT_LT((vec(report["hands"][1]["target"]["position"]) - right0).norm(), 1e-12);

  // the recorded session: every kind of event, and a headless replay to the same state
  ASSERT_TRUE(fs::exists(session_file));
  const SessionLog log = read_session_log(session_file);
  EXPECT_EQ(log.model, "dual_arm");
  EXPECT_EQ(log.ticks, report["control_ticks"].get<std::int64_t>());
  EXPECT_EQ(log.digest, report["session"]["digest"].get<std::string>());
  int kinds[4] = {0, 0, 0, 0};
  for (const SessionEvent& e : log.events) ++kinds[static_cast<int>(e.kind)];
  EXPECT_GE(kinds[0],
            5);  // the initial targets, the slider, two nudges, roll, gripper, lift, reset
  EXPECT_EQ(kinds[1], 1);  // kinematic → torque
  EXPECT_EQ(kinds[2], 1);  // the left hand's task (position at priority 1); the right one kept
  EXPECT_EQ(kinds[3], 1);  // the reset
  const ReplayResult replay = replay_session(robot, log);
  EXPECT_TRUE(replay.matches) << replay.digest << " vs " << log.digest;
  for (std::size_t i = 0; i < 2; ++i) {
    const Eigen::Vector3d p = vec(report["hands"][i]["hand"]["position"]);
    EXPECT_EQ(replay.stats.hands[i].X_WE.p, p) << "hand " << i;
  }
  // the CLI's replay agrees
  const Outcome cli =
      run_command("'" MJARM_CLI "' replay '" + session_file.string() + "' --json", dir);
  ASSERT_EQ(cli.status, 0) << cli.err;
  EXPECT_TRUE(nlohmann::json::parse(cli.out)["deterministic"].get<bool>());
  fs::remove_all(dir);
}

// What was recorded is written whatever ends the viewer: a script error, Ctrl-C.
TEST(ViewerWindow, BimanualRecordingIsKeptOnAnErrorAndOnCtrlC) {
  const auto prefix = display_prefix();
  if (!prefix) return;
  const fs::path dir = fresh_dir("bimanual_end");
  {
    std::ofstream script(dir / "bad.txt");
    script << "wait 3\nkey r\nwait 2\nset left.x 99\n";
  }
  const fs::path broken = dir / "error.session";
  const Outcome r = run_command(
      *prefix + "'" MJARM_CLI "' view dual_arm --size 320x240 --render-hz 10 --script '" +
          (dir / "bad.txt").string() + "' --record-session '" + broken.string() + "'",
      dir);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("line 4 (set)"), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(broken)) << "the session recorded before the error is lost";
  const Robot robot = Robot::bundled("dual_arm");
  const SessionLog log = read_session_log(broken);
  ASSERT_EQ(log.events.size(), 2u);  // the initial targets and the nudge, after 3 frames
  EXPECT_GT(log.events[1].tick, 0);
  EXPECT_GT(log.ticks, log.events[1].tick);  // and the ticks of the 2 frames after it
  EXPECT_TRUE(replay_session(robot, log).matches);

  // an interactive session stopped by SIGINT (Ctrl-C) once its session file is being written:
  // its temporary file (FileWriter's ".NAME.partial-…") is opened inside the viewer, after the
  // Ctrl-C handler is installed; the command line's check of the path creates and removes the
  // file itself earlier, before the handler, so that name alone is no sign of readiness. The
  // signal goes as soon as the file is there (the loop's 60 s only guard against a hang): the
  // session may have run no tick yet or many, the verdict is the same — a second's sleep here
  // guessed how long a window takes to open, and on a slow machine it was still being built
  const fs::path sub = dir / "interactive";
  fs::create_directories(sub);
  const fs::path stopped = sub / "ctrl_c.session";
  std::string display = prefix->substr(0, prefix->find(' '));
  // --foreground: timeout passes the SIGINT to mjarm alone; by default it sends it to mjarm and
  // again to its whole process group, and the second one ends mjarm at once (the guard is
  // one-shot: a second Ctrl-C ends the process)
  // (in braces: the stderr redirection run_command adds covers mjarm too)
  const std::string command =
      "{ " + display +
      " timeout --foreground -k 10 120 '" MJARM_CLI "' view dual_arm --size 320x240 --json " +
      "--record-session '" + stopped.string() + "' & pid=$!; i=0; " + "while ! ls -A '" +
      sub.string() + "' | grep -q '^\\.ctrl_c\\.session\\.partial-' && [ $i -lt 600 ]; do " +
      "sleep 0.1; i=$((i+1)); done; kill -INT $pid; wait $pid; }";
  const Outcome c = run_command(command, dir);
  // issue 29: the viewer exited 0 after Ctrl-C; it prints its report and exits 130 as every
  // command stopped by a signal does
  EXPECT_EQ(c.status, 130) << c.err;
  EXPECT_NE(c.err.find("view: interrupted after "), std::string::npos) << c.err;
  ASSERT_TRUE(nlohmann::json::accept(c.out)) << c.out << c.err;
  EXPECT_EQ(nlohmann::json::parse(c.out)["ended_by"], "interrupted");
  ASSERT_TRUE(fs::exists(stopped)) << c.err;
  EXPECT_TRUE(replay_session(robot, read_session_log(stopped)).matches);
  fs::remove_all(dir);
}

TEST(ViewerWindow, BimanualRecordPathIsCheckedBeforeTheWindowOpens) {
  // no display at all: the unwritable session file is what is reported, so it was checked
  // before anything needed a window
  const fs::path dir = fresh_dir("bimanual_bad");
  const Outcome r = run_command("env -u DISPLAY '" MJARM_CLI "' view dual_arm --record-session '" +
                                    (dir / "missing" / "x.session").string() + "'",
                                dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--record-session"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("no display"), std::string::npos) << r.err;
  // one end effector: nothing to record
  const Outcome one = run_command("env -u DISPLAY '" MJARM_CLI "' view panda --record-session '" +
                                      (dir / "x.session").string() + "'",
                                  dir);
  EXPECT_EQ(one.status, 2) << one.err;
  EXPECT_NE(one.err.find("records sessions of several hands"), std::string::npos) << one.err;
  EXPECT_FALSE(fs::exists(dir / "x.session"));
  fs::remove_all(dir);
}

TEST(ViewerWindow, NoDisplayIsAClearError) {
  const fs::path dir = fresh_dir("nodisplay");
  const Outcome r =
      run_command("env -u DISPLAY -u WAYLAND_DISPLAY '" MJARM_CLI "' view panda --frames 1", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no display: set DISPLAY or run under xvfb-run; for headless images use "
                       "`mjarm render`"),
            std::string::npos)
      << r.err;
  // a bad command line is still reported as such (exit 2), display or not
  const Outcome bad = run_command("env -u DISPLAY '" MJARM_CLI "' view panda --mode fast", dir);
  EXPECT_EQ(bad.status, 2) << bad.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mjarm
