// VideoWriter: valid MP4 files (ffprobe counts the frames) after close, and no video (the old
// file kept) after an early end, an exception unwinding, an interrupt or abandon(); clear errors
// for a missing ffmpeg, bad sizes, unwritable paths and an ffmpeg that dies mid-run (no SIGPIPE
// death).

#include "mjarm/render/video_writer.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/render/frame_schedule.hpp"
#include "mjarm/render/offscreen_renderer.hpp"
#include "render_test_support.hpp"

namespace mjarm {
namespace {

using test::error_of;
using test::has_moov_atom;
using test::hostile_video_name;
using test::moving_square;
using test::probe;
using test::Probe;

namespace fs = std::filesystem;

TEST(VideoWriter, WritesAValidMp4WithEveryFrame) {
  const fs::path path = test::scratch() / "closed.mp4";
  VideoWriter video(path, 64, 48, 25.0);
  for (int k = 0; k < 12; ++k) video.write(moving_square(64, 48, k));
  EXPECT_EQ(video.frames(), 12);
  video.close();
  video.close();  // idempotent
  EXPECT_FALSE(video.is_open());
  EXPECT_TRUE(has_moov_atom(path));
  const Probe p = probe(path);
  EXPECT_EQ(p.frames, 12);
  EXPECT_EQ(p.width, 64);
  EXPECT_EQ(p.height, 48);
  EXPECT_EQ(p.codec, "h264");
  EXPECT_NE(error_of([&] { video.write(moving_square(64, 48, 0)); }).find("after close"),
            std::string::npos);
}

TEST(VideoWriter, AnyFileNameIsWrittenAsGiven) {
  const fs::path dir = test::scratch() / "hostile\n$(touch PWNED4)";
  fs::create_directories(dir);
  const fs::path path = dir / hostile_video_name();
  const fs::path saved = fs::current_path();
  fs::current_path(dir);  // where a `touch` run by mistake would write
  std::string error;
  try {
    VideoWriter video(path, 64, 48, 25.0);
    for (int k = 0; k < 6; ++k) video.write(moving_square(64, 48, k));
    video.close();
  } catch (const Error& e) {
    error = e.what();
  }
  fs::current_path(saved);
  ASSERT_EQ(error, "");
  EXPECT_EQ(probe("file:" + path.string()).frames, 6);
  // (the video's own name holds the word: a file made by `touch` starts with it)
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_NE(entry.path().filename().string().rfind("PWNED", 0), 0u) << entry.path();
  for (const auto& entry : fs::directory_iterator(test::scratch()))
    EXPECT_NE(entry.path().filename().string().rfind("PWNED", 0), 0u) << entry.path();
}

// issue 29, items 7 and 14: a video that was not closed after its last frame (a run that
// stopped early, an exception, Ctrl-C) was finalized with the frames so far and renamed over
// the old file: a 3-frame video replaced a whole one. A complete video or none: the old file
// stays as it was, and nothing is left beside it.
TEST(VideoWriter, DestroyedWithoutCloseWritesNoVideo) {
  const fs::path dir = test::scratch() / "dropped_video";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "dropped.mp4";
  std::ofstream(path) << "old video\n";
  {
    VideoWriter video(path, 64, 48, 30.0);
    for (int k = 0; k < 7; ++k) video.write(moving_square(64, 48, k));
  }  // a run that ended early: no close()
  EXPECT_EQ(test::slurp(path), "old video\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove(path);
  {
    VideoWriter video(path, 64, 48, 30.0);
    video.write(moving_square(64, 48, 0));
  }
  EXPECT_FALSE(fs::exists(path));  // no file was there: none is made
}

TEST(VideoWriter, ExceptionUnwindingPastTheWriterLeavesTheOldFile) {
  const fs::path path = test::scratch() / "thrown.mp4";
  std::ofstream(path) << "old video\n";
  EXPECT_THROW(
      {
        VideoWriter video(path, 64, 48, 30.0);
        for (int k = 0; k < 20; ++k) {
          video.write(moving_square(64, 48, k));
          if (k == 4) throw std::runtime_error("the run failed");
        }
      },
      std::runtime_error);
  EXPECT_EQ(test::slurp(path), "old video\n");
}

// Ctrl-C (or SIGTERM) pending when the run closes its video: the frames end where the run was
// cut, so close() writes nothing and says so; abandon() (a run that failed) likewise
TEST(VideoWriter, AVideoCutByAnInterruptOrAbandonedIsNotWritten) {
  const fs::path dir = test::scratch() / "interrupted_video";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "run.mp4";
  std::ofstream(path) << "old video\n";
  {
    const InterruptGuard interrupts;
    VideoWriter video(path, 64, 48, 30.0);
    for (int k = 0; k < 5; ++k) video.write(moving_square(64, 48, k));
    std::raise(SIGINT);  // the handler only sets the flag
    const std::string message = error_of([&] { video.close(); });
    EXPECT_NE(message.find("video '" + path.string() +
                           "' was not written: interrupted after 5 frames (the file already at '" +
                           path.string() + "' is kept)"),
              std::string::npos)
        << message;
    EXPECT_FALSE(video.complete());
    EXPECT_FALSE(video.is_open());
  }
  EXPECT_EQ(test::slurp(path), "old video\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);

  VideoWriter video(path, 64, 48, 30.0);
  video.write(moving_square(64, 48, 0));
  video.abandon();
  video.abandon();  // idempotent
  EXPECT_FALSE(video.is_open());
  EXPECT_FALSE(video.complete());
  video.close();  // nothing left to close
  EXPECT_EQ(test::slurp(path), "old video\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(VideoWriter, Mpeg4EncoderAndTwoWritersAtOnce) {
  const fs::path a = test::scratch() / "a.mp4";
  const fs::path b = test::scratch() / "b.mp4";
  VideoOptions mpeg4;
  mpeg4.codec = "mpeg4";
  VideoWriter first(a, 64, 48, 10.0, mpeg4);
  VideoWriter second(b, 32, 32, 10.0);
  for (int k = 0; k < 6; ++k) {
    first.write(moving_square(64, 48, k));
    if (k % 2 == 0) second.write(moving_square(32, 32, k / 2));
  }
  // closing the first must not wait for the second (its ffmpeg must not hold the first pipe)
  first.close();
  EXPECT_EQ(probe(a).frames, 6);
  EXPECT_EQ(probe(a).codec, "mpeg4");
  second.close();
  EXPECT_EQ(probe(b).frames, 3);
}

TEST(VideoWriter, FfmpegMissingNamesTheDebianPackage) {
  VideoOptions options;
  options.ffmpeg = "/nonexistent/bin/ffmpeg";
  const std::string message =
      error_of([&] { VideoWriter(test::scratch() / "x.mp4", 64, 48, 30.0, options); });
  EXPECT_NE(message.find("ffmpeg not found"), std::string::npos) << message;
  EXPECT_NE(message.find("package `ffmpeg`"), std::string::npos) << message;

  // the same when PATH has no ffmpeg
  const fs::path empty_dir = test::scratch() / "empty_bin";
  fs::create_directories(empty_dir);
  const std::string saved = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  ::setenv("PATH", empty_dir.c_str(), 1);
  const std::string on_path =
      error_of([&] { VideoWriter(test::scratch() / "y.mp4", 64, 48, 30.0); });
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_NE(on_path.find("no 'ffmpeg' on PATH"), std::string::npos) << on_path;
  EXPECT_NE(on_path.find("apt-get install ffmpeg"), std::string::npos) << on_path;
}

TEST(VideoWriter, ZeroOrOddSizesAndBadRatesAreErrors) {
  const fs::path path = test::scratch() / "size.mp4";
  EXPECT_NE(error_of([&] { VideoWriter(path, 0, 48, 30.0); }).find("must be positive"),
            std::string::npos);
  EXPECT_NE(error_of([&] { VideoWriter(path, 64, 0, 30.0); }).find("must be positive"),
            std::string::npos);
  const std::string odd = error_of([&] { VideoWriter(path, 641, 480, 30.0); });
  EXPECT_NE(odd.find("must be even"), std::string::npos) << odd;
  EXPECT_NE(odd.find("642×480"), std::string::npos) << odd;
  EXPECT_THROW(VideoWriter(path, 64, 47, 30.0), Error);
  EXPECT_THROW(VideoWriter(path, 64, 48, 0.0), Error);
  EXPECT_THROW(VideoWriter(path, 64, 48, NAN), Error);
  // a frame of the wrong size
  VideoWriter video(path, 64, 48, 30.0);
  EXPECT_NE(error_of([&] { video.write(Image(48, 64)); }).find("does not match"),
            std::string::npos);
  video.write(moving_square(64, 48, 0));
  video.close();
  EXPECT_EQ(probe(path).frames, 1);
}

TEST(VideoWriter, UnwritablePathFailsBeforeAnyFrame) {
  const fs::path missing = test::scratch() / "no_such_folder" / "out.mp4";
  const std::string message = error_of([&] { VideoWriter(missing, 64, 48, 30.0); });
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  EXPECT_THROW(VideoWriter(test::scratch(), 64, 48, 30.0), Error);  // a folder
}

TEST(VideoWriter, FfmpegDyingMidRunIsAnErrorNotASignal) {
  // an "ffmpeg" that exits at once: writes hit a closed pipe
  VideoOptions options;
  options.ffmpeg = "/bin/false";
  VideoWriter video(test::scratch() / "dies.mp4", 64, 48, 30.0, options);
  std::string message;
  for (int k = 0; k < 200 && message.empty(); ++k) {
    try {
      video.write(moving_square(64, 48, k % 20));
    } catch (const Error& e) {
      message = e.what();
    }
  }
  if (message.empty()) message = error_of([&] { video.close(); });
  EXPECT_NE(message.find("exit status 1"), std::string::npos) << message;
  EXPECT_FALSE(video.is_open());

  // an encoder ffmpeg does not know: ffmpeg's own message comes through
  VideoOptions unknown;
  unknown.codec = "mjarm_no_such_encoder";
  VideoWriter bad(test::scratch() / "unknown.mp4", 64, 48, 30.0, unknown);
  std::string reason;
  try {
    for (int k = 0; k < 200; ++k) bad.write(moving_square(64, 48, k % 20));
    bad.close();
  } catch (const Error& e) {
    reason = e.what();
  }
  EXPECT_NE(reason.find("mjarm_no_such_encoder"), std::string::npos) << reason;
}

TEST(VideoWriter, RendererFramesAtVideoRate) {
  // one simulated second of a moving panda, physics at 2 ms, video at 10 frames/s: 11 frames
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  OffscreenRenderer renderer(panda, 160, 120);
  const fs::path path = test::scratch() / "panda.mp4";
  VideoWriter video(path, 160, 120, 10.0);
  FrameSchedule schedule(10.0);
  const auto camera = CameraSpec::free_camera({0.2, 0.0, 0.45}, 1.9, 150.0, -20.0);
  Image frame;
  const double q0 = d->qpos[0];
  for (int step = 0; step <= 500; ++step) {
    d->time = 0.002 * step;
    d->qpos[0] = q0 + 0.8 * d->time;
    mj_kinematics(&panda.model(), d.get());
    if (const int due = schedule.frames_due(d->time); due > 0) {
      renderer.render(*d, camera, frame);
      for (int k = 0; k < due; ++k) video.write(frame);
    }
  }
  video.close();
  EXPECT_EQ(video.frames(), 11);
  EXPECT_EQ(probe(path).frames, 11);
}
}  // namespace
}  // namespace mjarm
