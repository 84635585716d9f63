// The end of a run's outputs: the result line reaches the recording, and a failing video or
// recorder becomes a message instead of an exception.

#include "tasks/run_outputs.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "mjarm/sim/simulation.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

struct FinishingVideo {
  int finished = 0;
  void finish(const mjData&) { ++finished; }
};

struct BrokenVideo {
  void finish(const mjData&) { throw Error("video: ffmpeg exited with status 1"); }
};

struct CrashingVideo {
  void finish(const mjData&) { throw std::logic_error("a bug, not a write failure"); }
};

TEST(RunOutputs, AVideoThatFinishesLeavesNoMessage) {
  const Robot robot = Robot::bundled("planar2_torque");
  Simulation sim(robot, SimulationOptions{});
  FinishingVideo video;
  EXPECT_EQ(finish_video(video, sim.data()), "");
  EXPECT_EQ(video.finished, 1);
}

TEST(RunOutputs, AVideoWriteFailureBecomesItsMessageAndOtherErrorsPropagate) {
  const Robot robot = Robot::bundled("planar2_torque");
  Simulation sim(robot, SimulationOptions{});
  BrokenVideo broken;
  EXPECT_EQ(finish_video(broken, sim.data()), "video: ffmpeg exited with status 1");
  CrashingVideo crashing;
  EXPECT_THROW(finish_video(crashing, sim.data()), std::logic_error);
}

TEST(RunOutputs, TheResultLineAndTheOutcomeReachTheRecording) {
  const Robot robot = Robot::bundled("planar2_torque");
  Simulation sim(robot, SimulationOptions{});
  const std::filesystem::path dir = test::scratch() / "run_outputs";
  std::filesystem::remove_all(dir);
  Recorder recorder(sim, dir);
  RunResult run;
  run.status = RunStatus::finished;
  EXPECT_EQ(finish_recording(recorder, 0.25, "success in 0.25 s", run), "");
  EXPECT_TRUE(recorder.finalized());
  const std::string events = test::slurp(dir / "events.csv");
  EXPECT_NE(events.find("result,success in 0.25 s"), std::string::npos) << events;
  EXPECT_NE(test::slurp(dir / "summary.json").find("\"finished\""), std::string::npos);
}

}  // namespace
}  // namespace mjarm
