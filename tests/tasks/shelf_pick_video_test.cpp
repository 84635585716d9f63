// The video of a shelf pick through the library: the default camera frames the robot and the
// pick point, a video does not change the figures, and an encoder that dies mid-run leaves the
// run going and reports why.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/tasks/shelf_pick/shelf_pick.hpp"
#include "mjarm/tasks/shelf_pick/video.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

using test::scratch;

bool inside(const Eigen::Vector3d& uvd, int width, int height) {
  return uvd.z() > 0.0 && uvd.x() >= 0.0 && uvd.x() < width && uvd.y() >= 0.0 && uvd.y() < height;
}

TEST(ShelfPickCamera, DefaultFramesTheRobotAndThePickPoint) {
  for (const char* name : {"planar2", "panda"}) {
    ShelfPickRequest request;
    request.robot = name;
    const ShelfPickPlan plan = plan_shelf_pick(request);
    DataPtr d = plan.model.make_data();
    for (int i = 0; i < plan.model.nq(); ++i) d->qpos[i] = plan.qpos_start[i];
    mj_forward(&plan.model.model(), d.get());
    const CameraSpec spec = shelf_pick_camera(plan, *d, "", 4.0 / 3.0);
    ASSERT_EQ(spec.kind, CameraKind::free);
    const CameraView view = free_camera_view(spec.lookat, spec.distance, spec.azimuth,
                                             spec.elevation, plan.model.model().vis.global.fovy);
    // the pick point, the tip and every body origin of the arm are in a 640×480 picture
    EXPECT_TRUE(inside(project(view, 640, 480, plan.pick), 640, 480)) << name;
    EXPECT_TRUE(inside(project(view, 640, 480, plan.goal.X_WS.p), 640, 480)) << name;
    for (int b = 1; b < plan.model.model().nbody; ++b)
      EXPECT_TRUE(inside(project(view, 640, 480, Eigen::Vector3d::Map(d->xpos + 3 * b)), 640, 480))
          << name << " body " << b;
    // not from far away: the pick point and the start tip are apart by ≥ 5 % of the width
    const double apart =
        (project(view, 640, 480, plan.pick) - project(view, 640, 480, plan.goal.X_WS.p))
            .head<2>()
            .norm();
    EXPECT_GT(apart, 0.05 * 640) << name;

    const CameraSpec follow = shelf_pick_camera(plan, *d, "follow");
    EXPECT_EQ(follow.kind, CameraKind::follow);
    EXPECT_EQ(follow.name, plan.robot->frame);
  }
  // planar2 is seen square onto its plane (looking along +y)
  ShelfPickRequest request;
  request.robot = "planar2";
  const ShelfPickPlan plan = plan_shelf_pick(request);
  DataPtr d = plan.model.make_data();
  mj_forward(&plan.model.model(), d.get());
  EXPECT_EQ(shelf_pick_camera(plan, *d, "").azimuth, 90.0);

  try {
    shelf_pick_camera(plan, *d, "overhead");
    ADD_FAILURE() << "an unknown camera was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'overhead' is not a camera of model 'planar2_torque' "
                                         "(its cameras: none)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(shelf_pick_camera(plan, *d, "", 0.0), Error);
}

ShelfPickOptions planar2_pick() {
  ShelfPickOptions options;
  options.request.robot = "planar2";
  options.request.controller = "ct";
  options.request.seed = 3;
  return options;
}

void expect_same_figures(const ShelfPickReport& a, const ShelfPickReport& b) {
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.run.end_time, b.run.end_time);
  EXPECT_EQ(a.run.ticks, b.run.ticks);
  EXPECT_EQ(a.metrics.time_to_tolerance, b.metrics.time_to_tolerance);
  EXPECT_EQ(a.metrics.overshoot, b.metrics.overshoot);
  EXPECT_EQ(a.metrics.hold_mean, b.metrics.hold_mean);
  EXPECT_EQ(a.metrics.steady_state_max, b.metrics.steady_state_max);
  EXPECT_EQ(a.metrics.final_error, b.metrics.final_error);
  EXPECT_EQ(a.saturated_ticks, b.saturated_ticks);
}

TEST(ShelfPickVideo, SameFiguresAndOneFramePerPeriodOfSimulatedTime) {
  const ShelfPickReport plain = run_shelf_pick(planar2_pick());
  ShelfPickOptions options = planar2_pick();
  options.video.path = scratch() / "pick.mp4";
  options.video.options.width = 64;
  options.video.options.height = 48;
  options.video.options.fps = 20.0;
  options.video.options.render.shadows = false;
  const ShelfPickReport filmed = run_shelf_pick(options);
  expect_same_figures(plain, filmed);
  EXPECT_EQ(filmed.video, options.video.path);
  EXPECT_TRUE(filmed.video_error.empty()) << filmed.video_error;
  EXPECT_EQ(filmed.video_frames,
            static_cast<std::int64_t>(std::floor(filmed.run.end_time * 20.0 + 1e-9)) + 1);
  EXPECT_GT(fs::file_size(options.video.path), 0u);
  EXPECT_TRUE(plain.video.empty());
  EXPECT_EQ(plain.video_frames, 0);
}

TEST(ShelfPickVideo, AnEncoderDyingMidRunLeavesTheRunAlone) {
  // an "ffmpeg" that takes a few frames, then fails
  const fs::path script = scratch() / "dying_ffmpeg";
  std::ofstream(script)
      << "#!/bin/sh\nhead -c 40000 > /dev/null\necho 'no space left' >&2\nexit 1\n";
  ::chmod(script.c_str(), 0755);
  ShelfPickOptions options = planar2_pick();
  options.video.path = scratch() / "dies.mp4";
  options.video.options.width = 64;
  options.video.options.height = 48;
  options.video.options.render.shadows = false;
  options.video.options.encoding.ffmpeg = script.string();
  const ShelfPickReport report = run_shelf_pick(options);
  expect_same_figures(run_shelf_pick(planar2_pick()), report);
  EXPECT_NE(report.video_error.find("no space left"), std::string::npos) << report.video_error;
  EXPECT_NE(report.video_error.find(options.video.path.string()), std::string::npos)
      << report.video_error;
  EXPECT_LT(report.video_frames, static_cast<std::int64_t>(report.run.end_time * 30.0));
}

}  // namespace
}  // namespace mjarm
