#include "mjarm/sim/recorder.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/version.hpp"
#include "sim/sim_test_support.hpp"
#include "support/file_size_limit.hpp"

namespace mjarm {
namespace {

using test::Csv;
using test::read_csv;

nlohmann::json read_summary(const std::filesystem::path& dir) {
  return nlohmann::json::parse(test::read_text(dir / "summary.json"));
}

// Every file complete: a header, rows of the header's width, a final newline.
void expect_complete(const std::filesystem::path& dir) {
  for (const char* name : {"state.csv", "task.csv", "events.csv"}) {
    const Csv csv = read_csv(dir / name);
    ASSERT_FALSE(csv.header.empty()) << name;
    EXPECT_TRUE(csv.ends_with_newline) << name;
    for (std::size_t r = 0; r < csv.rows.size(); ++r) {
      ASSERT_EQ(csv.rows[r].size(), csv.header.size()) << name << " row " << r;
    }
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "summary.json"));
  EXPECT_EQ(test::partial_folders(dir), 0);
}

struct Planar2Run {
  Robot robot = Robot::bundled("planar2_torque");
  Chain chain{robot, "tip"};
  Simulation sim;
  test::PdTorque pd{chain, 60.0, 6.0};
  Reference reference;

  explicit Planar2Run(double period = 0.01) : sim(robot, options(period)) {
    sim.reset("home");
    sim.add_controller(pd);
    reference.joint.q = Eigen::Vector2d(0.3, -0.6);
    reference.task.X_WE.p = Eigen::Vector3d(0.5, 0.1, 0.7);
    reference.gripper = 0.25;
  }
  static SimulationOptions options(double period) {
    SimulationOptions o;
    o.control_period = period;
    return o;
  }
};

TEST(Recorder, WritesThreeLayersAndASummary) {
  Planar2Run p;
  test::TempDir dir("layers");
  RecorderOptions options;
  options.state_decimation = 2;
  const std::filesystem::path out = dir.path() / "run1";  // created by the recorder
  Recorder recorder(p.sim, out, options);
  EXPECT_EQ(test::partial_folders(out), 1);  // staging while the run goes
  EXPECT_FALSE(std::filesystem::exists(out / "state.csv"));
  ConstantReferenceSource source(p.reference);
  const RunResult run = p.sim.run(source, 0.5, &recorder);
  ASSERT_EQ(run.status, RunStatus::duration_reached);
  recorder.event(p.sim.time(), "phase", "hold, then \"release\"");
  recorder.finalize(run);
  recorder.finalize("twice");  // idempotent
  expect_complete(out);

  const Csv state = read_csv(out / "state.csv");
  for (const char* c : {"t", "q.shoulder", "q.elbow", "v.shoulder", "v.elbow", "ctrl.shoulder",
                        "ctrl.elbow", "force.shoulder", "force.elbow"}) {
    EXPECT_GE(state.column(c), 0) << c;
  }
  EXPECT_EQ(state.header.size(), 11u);  // and contact.count, contact.normal_force
  EXPECT_EQ(state.rows.size(), 125u);   // 250 physics steps, every second one
  // the first row is the start state, the ctrl applied during that step, and its force
  EXPECT_EQ(state.value(0, "t"), 0.0);
  EXPECT_EQ(state.value(0, "q.shoulder"), 0.5);
  EXPECT_EQ(state.value(0, "q.elbow"), -1.0);
  EXPECT_EQ(state.value(0, "ctrl.shoulder"), state.value(0, "force.shoulder"));
  EXPECT_NEAR(state.value(1, "t"), 0.004, 1e-15);

  const Csv task = read_csv(out / "task.csv");
  for (const char* c :
       {"ee.x", "ee.qw", "ref.z", "err.vx", "err.wz", "gripper_ref", "qref.shoulder",
        "cmd.test-pd.elbow", "test-pd.error_norm", "sat.shoulder", "sat.elbow"}) {
    EXPECT_GE(task.column(c), 0) << c;
  }
  EXPECT_EQ(task.rows.size(), 50u);
  EXPECT_EQ(task.value(0, "qref.shoulder"), 0.3);
  EXPECT_EQ(task.value(0, "gripper_ref"), 0.25);
  EXPECT_EQ(task.value(0, "ref.x"), 0.5);
  // the pose of the tip at home, and the error to the reference, world axes
  const Robot& robot = p.robot;
  DataPtr home = robot.make_data();
  mj_resetDataKeyframe(&robot.model(), home.get(), robot.keyframe("home"));
  mj_forward(&robot.model(), home.get());
  const double* tip = home->site_xpos + 3 * robot.site("tip");
  EXPECT_NEAR(task.value(0, "ee.x"), tip[0], 1e-15);
  EXPECT_NEAR(task.value(0, "ee.z"), tip[2], 1e-15);
  EXPECT_NEAR(task.value(0, "err.vx"), 0.5 - tip[0], 1e-15);
  EXPECT_NEAR(task.value(0, "test-pd.error_norm"), std::hypot(0.3 - 0.5, -0.6 + 1.0), 1e-12);

  const Csv events = read_csv(out / "events.csv");
  ASSERT_EQ(events.rows.size(), 1u);
  EXPECT_EQ(events.rows[0][1], "phase");
  EXPECT_EQ(events.rows[0][2], "hold, then \"release\"");

  const nlohmann::json s = read_summary(out);
  EXPECT_EQ(s["model"], "planar2_torque");
  EXPECT_EQ(s["mode"], "torque");
  EXPECT_EQ(s["integrator"], "Euler");
  EXPECT_EQ(s["timestep"], 0.002);
  EXPECT_EQ(s["control_period"], 0.01);
  EXPECT_EQ(s["steps_per_tick"], 5);
  EXPECT_EQ(s["status"], "duration_reached");
  EXPECT_EQ(s["counts"]["state_rows"], 125);
  EXPECT_EQ(s["counts"]["task_rows"], 50);
  EXPECT_EQ(s["counts"]["events"], 1);
  EXPECT_NEAR(s["duration"].get<double>(), 0.5, 1e-9);
  EXPECT_EQ(s["files"]["state"]["file"], "state.csv");
  EXPECT_EQ(s["controllers"][0]["name"], "test-pd");
  EXPECT_EQ(s["controllers"][0]["joints"][1], "elbow");
}

TEST(Recorder, ARunThatThrowsIsFinalizedAsError) {
  Planar2Run p(0.002);
  test::TempDir dir("throw");
  try {
    Recorder recorder(p.sim, dir.path());
    for (int k = 0;; ++k) {
      p.sim.tick(p.reference, &recorder);
      if (k == 19) throw std::runtime_error("controller exploded");
    }
  } catch (const std::runtime_error&) {
  }
  expect_complete(dir.path());
  EXPECT_EQ(read_csv(dir.path() / "state.csv").rows.size(), 20u);
  EXPECT_EQ(read_csv(dir.path() / "task.csv").rows.size(), 20u);
  const nlohmann::json s = read_summary(dir.path());
  EXPECT_EQ(s["status"], "error");
  EXPECT_EQ(s["counts"]["task_rows"], 20);
}

TEST(Recorder, DestroyedWithoutFinalizeIsAborted) {
  Planar2Run p;
  test::TempDir dir("aborted");
  {
    Recorder recorder(p.sim, dir.path());
    for (int k = 0; k < 3; ++k) p.sim.tick(p.reference, &recorder);
  }
  expect_complete(dir.path());
  EXPECT_EQ(read_summary(dir.path())["status"], "aborted");
  EXPECT_EQ(read_csv(dir.path() / "state.csv").rows.size(), 15u);
}

// SIGINT raised in-process while the handler is installed: the loop stops at the next tick and
// the recording is finalized as interrupted with every row so far.
TEST(Recorder, SigintStopsTheRunAndTheRecordingIsKept) {
  Planar2Run p;
  test::TempDir dir("sigint");
  RunResult run;
  {
    InterruptGuard guard;
    EXPECT_THROW(InterruptGuard second, Error);
    Recorder recorder(p.sim, dir.path());
    bool raised = false;
    FunctionReferenceSource source([&](const mjData& d, Reference& r) {
      r = p.reference;
      if (d.time >= 0.1 - 1e-9 && !raised) {
        raised = true;
        std::raise(SIGINT);
      }
      return true;
    });
    run = p.sim.run(source, 10.0, &recorder);
    EXPECT_TRUE(interrupt_requested());
    recorder.finalize(run);
  }
  EXPECT_FALSE(interrupt_requested());  // the guard cleared it
  ASSERT_EQ(run.status, RunStatus::interrupted);
  EXPECT_NEAR(run.end_time, 0.11, 1e-9);  // the tick that saw the signal completed
  expect_complete(dir.path());
  EXPECT_EQ(read_csv(dir.path() / "task.csv").rows.size(), 11u);
  EXPECT_EQ(read_csv(dir.path() / "state.csv").rows.size(), 55u);
  const Csv events = read_csv(dir.path() / "events.csv");
  ASSERT_EQ(events.rows.size(), 1u);
  EXPECT_EQ(events.rows[0][1], "interrupt");
  EXPECT_EQ(read_summary(dir.path())["status"], "interrupted");
}

TEST(Recorder, UnwritableDirectoryFailsBeforeTheRun) {
  Planar2Run p;
  test::TempDir dir("unwritable");
  const std::filesystem::path file = dir.path() / "a_file";
  std::ofstream(file) << "not a directory";
  try {
    Recorder recorder(p.sim, file / "recording");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((file / "recording").string()), std::string::npos)
        << e.what();
  }
  if (geteuid() != 0) {  // root writes anywhere: the permission case only means something for users
    const std::filesystem::path locked = dir.path() / "locked";
    std::filesystem::create_directory(locked);
    std::filesystem::permissions(
        locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    try {
      Recorder recorder(p.sim, locked);
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("not writable"), std::string::npos) << e.what();
    }
    std::filesystem::permissions(locked, std::filesystem::perms::owner_all);
  }
  EXPECT_EQ(p.sim.ticks(), 0);
}

// The staging folder a recorder error names ("… stays in '<folder>'").
std::filesystem::path kept_folder(const std::string& message) {
  const std::string marker = "stays in '";
  const std::size_t begin = message.find(marker);
  if (begin == std::string::npos) return {};
  const std::size_t from = begin + marker.size();
  return message.substr(from, message.find('\'', from) - from);
}

TEST(Recorder, AFullDiskMovesNothingAndNamesTheKeptRows) {
  Planar2Run p;
  test::TempDir dir("full");
  const std::filesystem::path out = dir.path() / "run";
  // headers and the summary fit in 4 KB, the rows of half a second do not
  const test::LimitedRun child = test::with_file_size_limit(4096, [&] {
    Recorder recorder(p.sim, out);
    ConstantReferenceSource source(p.reference);
    recorder.finalize(p.sim.run(source, 0.5, &recorder));
    return std::string("finalized");
  });
  ASSERT_EQ(child.exit_code, 1) << child.out;
  const std::string& message = child.err;
  EXPECT_NE(message.find("state.csv"), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_NE(message.find("nothing was moved into '" + out.string() + "'"), std::string::npos)
      << message;
  // nothing in the directory: no summary pairs with cut rows
  EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
  EXPECT_FALSE(std::filesystem::exists(out / "state.csv"));
  // the rows written so far stay where the message says, described by their summary
  const std::filesystem::path kept = kept_folder(message);
  ASSERT_EQ(kept.parent_path(), out) << message;
  ASSERT_TRUE(std::filesystem::is_directory(kept)) << message;
  const Csv state = read_csv(kept / "state.csv");
  EXPECT_EQ(state.header.front(), "t");
  EXPECT_EQ(state.header.back(), "contact.normal_force");
  EXPECT_LE(std::filesystem::file_size(kept / "state.csv"), 4096u);
  const nlohmann::json summary = read_summary(kept);
  EXPECT_EQ(summary["status"], "duration_reached");
  EXPECT_EQ(summary["counts"]["state_rows"], 250);  // what the run produced, not what was kept
  const std::string write_error = summary["write_error"];
  EXPECT_NE(write_error.find("state.csv"), std::string::npos) << write_error;
  EXPECT_NE(write_error.find("File too large"), std::string::npos) << write_error;

  // the same run with room for it is complete (the largest file is model.mjb: the model with the
  // pixels of its skybox and floor textures, 1.4 MB)
  Planar2Run again;
  const std::filesystem::path roomy = dir.path() / "roomy";
  const test::LimitedRun ok = test::with_file_size_limit(4 << 20, [&] {
    Recorder recorder(again.sim, roomy);
    ConstantReferenceSource source(again.reference);
    recorder.finalize(again.sim.run(source, 0.5, &recorder));
    return std::string("finalized");
  });
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  expect_complete(roomy);
  EXPECT_TRUE(std::filesystem::exists(roomy / "model.mjb"));
}

TEST(Recorder, BadOptionsAndLateControllersAreRefused) {
  Planar2Run p;
  test::TempDir dir("options");
  RecorderOptions bad;
  bad.state_decimation = 0;
  EXPECT_THROW(Recorder(p.sim, dir.path(), bad), Error);
  RecorderOptions frame;
  frame.frame = "no_such_frame";
  EXPECT_THROW(Recorder(p.sim, dir.path(), frame), Error);
  EXPECT_EQ(test::partial_folders(dir.path()), 0);  // nothing touched the disk

  // a controller added after the recorder changes the columns: run() refuses
  Simulation sim(p.robot);
  Recorder early(sim, dir.path() / "early");
  test::PdTorque pd(p.chain, 1.0, 1.0);
  sim.add_controller(pd);
  ConstantReferenceSource source(p.reference);
  EXPECT_THROW(sim.run(source, 0.1, &early), Error);
  Simulation other(p.robot);
  EXPECT_THROW(other.run(source, 0.1, &early), Error);
}

TEST(Recorder, ChannelsAreTaskColumnsReadEveryTick) {
  Planar2Run p;
  test::TempDir dir("channels");
  double force = 0.0, slip = -1.0;
  RecorderOptions options;
  options.channels = {{"grasp.force", &force}, {"grasp.slip", &slip}};
  Recorder recorder(p.sim, dir.path() / "run", options);
  for (int k = 0; k < 5; ++k) {
    force = 0.5 * k;
    ASSERT_TRUE(p.sim.tick(p.reference, &recorder).ok());
  }
  recorder.finalize("finished");
  const Csv task = read_csv(dir.path() / "run" / "task.csv");
  ASSERT_EQ(task.header.back(), "grasp.slip");
  ASSERT_EQ(task.header[task.header.size() - 2], "grasp.force");
  ASSERT_EQ(task.rows.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(task.value(k, "grasp.force"), 0.5 * static_cast<double>(k));
    EXPECT_EQ(task.value(k, "grasp.slip"), -1.0);
  }
  // refused before anything touches the disk: no value, no name, a name already taken
  for (const RecorderChannel& bad : {RecorderChannel{"x", nullptr}, RecorderChannel{"", &force},
                                     RecorderChannel{"gripper_ref", &force}}) {
    RecorderOptions o;
    o.channels = {bad};
    EXPECT_THROW(Recorder(p.sim, dir.path() / "bad", o), Error) << bad.name;
    const std::filesystem::path folder = dir.path() / "bad";
    EXPECT_TRUE(!std::filesystem::exists(folder) || test::partial_folders(folder) == 0);
  }
}

// A caller that returns early without finalize still gets the run's status (here: interrupted).
TEST(Recorder, DestroyedAfterARunKeepsTheRunStatus) {
  Planar2Run p;
  test::TempDir dir("run_status");
  {
    InterruptGuard guard;
    Recorder recorder(p.sim, dir.path());
    bool raised = false;  // once: the handler is one-shot, a second SIGINT would end the process
    FunctionReferenceSource source([&](const mjData& d, Reference& r) {
      r = p.reference;
      if (d.time >= 0.05 - 1e-9 && !raised) {
        raised = true;
        std::raise(SIGINT);
      }
      return true;
    });
    EXPECT_EQ(p.sim.run(source, 1.0, &recorder).status, RunStatus::interrupted);
  }
  expect_complete(dir.path());
  const nlohmann::json s = read_summary(dir.path());
  EXPECT_EQ(s["status"], "interrupted");
  EXPECT_NEAR(s["end_time"].get<double>(), 0.06, 1e-9);
}

// A second recording into the same directory replaces the first one whole.
TEST(Recorder, ASecondRecordingReplacesTheFirst) {
  test::TempDir dir("replace");
  for (int round = 0; round < 2; ++round) {
    Planar2Run p;
    Recorder recorder(p.sim, dir.path());
    for (int k = 0; k < 2 + round; ++k) p.sim.tick(p.reference, &recorder);
    recorder.finalize("finished");
  }
  expect_complete(dir.path());
  EXPECT_EQ(read_csv(dir.path() / "task.csv").rows.size(), 3u);
  EXPECT_EQ(read_summary(dir.path())["counts"]["task_rows"], 3);
}

// issue 29, item 15: two runs recording into one folder both reported success, the last one's
// files winning (or a mix of both). The folder is locked while a recorder lives: the second is
// refused before anything runs, naming the folder and the first one's PID.
TEST(Recorder, OneRecorderPerFolderAtATime) {
  test::TempDir dir("locked_folder");
  Planar2Run p;
  std::optional<Recorder> first(std::in_place, p.sim, dir.path());
  const std::filesystem::path lock = dir.path() / ".mjarm-lock";
  EXPECT_TRUE(std::filesystem::exists(lock));
  Planar2Run q;
  try {
    Recorder second(q.sim, dir.path());
    FAIL() << "a second recorder of the folder was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("recording folder '" + dir.path().string() +
                           "' is being written by another mjarm (PID " +
                           std::to_string(::getpid()) + ", since "),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("wait for it to end or choose another folder"), std::string::npos)
        << message;
  }
  EXPECT_EQ(q.sim.ticks(), 0);
  EXPECT_EQ(test::partial_folders(dir.path()), 1);  // the first one's staging folder only
  p.sim.tick(p.reference, &*first);
  first->finalize("finished");
  EXPECT_FALSE(std::filesystem::exists(lock));  // released once finalized, no file left behind
  Recorder third(q.sim, dir.path());            // the folder is free again
  third.finalize("finished");
  expect_complete(dir.path());
  first.reset();

  // a writer killed while it held the folder: the kernel dropped its lock, its file stays and
  // is taken over
  const pid_t child = ::fork();
  if (child == 0) {
    try {
      Planar2Run c;
      Recorder killed(c.sim, dir.path());
      ::_exit(0);  // no destructor, as after SIGKILL
    } catch (...) {
      ::_exit(1);
    }
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(std::filesystem::exists(lock));
  Recorder after(q.sim, dir.path());
  after.finalize("finished");
}

// issue 29, item 15: summary.json did not say whose recording it is. It records the
// invocation: command line, working directory, PID, start time, seed, mjarm and MuJoCo versions.
TEST(Recorder, TheSummaryRecordsTheInvocation) {
  test::TempDir dir("invocation");
  for (const bool seeded : {true, false}) {
    Planar2Run p;
    RecorderOptions options;
    if (seeded) options.seed = 18446744073709551615ull;  // the largest seed, kept exactly
    Recorder recorder(p.sim, dir.path(), options);
    recorder.finalize("finished");
    const nlohmann::json in = read_summary(dir.path())["invocation"];
    ASSERT_TRUE(in.is_object()) << in;
    ASSERT_FALSE(in["command_line"].empty());
    EXPECT_NE(in["command_line"][0].get<std::string>().find("test_sim"), std::string::npos) << in;
    EXPECT_EQ(in["working_directory"], std::filesystem::current_path().string());
    EXPECT_EQ(in["pid"], static_cast<long>(::getpid()));
    EXPECT_EQ(in["started"].get<std::string>().size(), 20u) << in;  // 2025-01-31T12:00:00Z
    if (seeded) {
      EXPECT_EQ(in["seed"].get<std::uint64_t>(), 18446744073709551615ull) << in;
    } else {
      EXPECT_TRUE(in["seed"].is_null()) << in;
    }
    EXPECT_EQ(in["mjarm_version"], version());
    EXPECT_EQ(in["mujoco_version"], mj_versionString());
  }
}

TEST(Recorder, KinematicMovesAreStateRows) {
  const Robot robot = Robot::bundled("planar2");
  SimulationOptions options;
  options.mode = SimulationMode::kinematic;
  Simulation sim(robot, options);
  test::TempDir dir("kinematic");
  {
    Recorder recorder(sim, dir.path(), RecorderOptions{1, 256, "tip", {}, {}});
    for (int k = 1; k <= 10; ++k) {
      const double q[2] = {0.01 * k, -0.02 * k};
      sim.move(q, 0.01, &recorder);
    }
    recorder.finalize("finished");
  }
  const Csv state = read_csv(dir.path() / "state.csv");
  ASSERT_EQ(state.rows.size(), 10u);
  EXPECT_NEAR(state.value(9, "t"), 0.1, 1e-12);
  EXPECT_EQ(state.value(9, "q.elbow"), -0.2);
  EXPECT_NEAR(state.value(9, "v.shoulder"), 1.0, 1e-9);
}

}  // namespace
}  // namespace mjarm
