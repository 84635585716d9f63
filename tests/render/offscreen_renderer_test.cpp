// OffscreenRenderer: real pictures headless, the robot where the camera says it is, model, free
// and follow cameras, lifetimes (sequence, side by side, after close), bad input.

#include "mjarm/render/offscreen_renderer.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/render/png.hpp"
#include "render_test_support.hpp"

namespace mjarm {
namespace {

using test::changed_pixels;
using test::error_of;
using test::pixel_stats;
using test::same;

constexpr int kW = 320;
constexpr int kH = 240;

// a scene with two model cameras looking at a red ball
constexpr const char* kCameraScene = R"(
<mujoco model="cameras">
  <include file="common/scene.xml"/>
  <worldbody>
    <camera name="overhead" pos="0 0 3" xyaxes="1 0 0 0 1 0"/>
    <camera name="side" pos="2 0 0.5" xyaxes="0 1 0 0 0 1"/>
    <body name="ball" pos="0.3 0.1 0.4">
      <geom type="sphere" size="0.1" rgba="1 0 0 1"/>
    </body>
  </worldbody>
</mujoco>)";

const CameraSpec kFront = CameraSpec::free_camera({0.2, 0.0, 0.45}, 1.9, 150.0, -20.0);

TEST(OffscreenRenderer, PandaFrameIsNotBlankAndRowZeroIsTheTop) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  OffscreenRenderer renderer(panda, kW, kH);
  const Image image = renderer.render(*d, kFront);
  ASSERT_EQ(image.width, kW);
  ASSERT_EQ(image.height, kH);
  const auto stats = pixel_stats(image);
  EXPECT_GT(stats.grey_stddev, 15.0) << "a flat picture";
  EXPECT_LT(stats.dark_share, 0.05) << "a black picture";
  // looking down at the floor from above: sky at the top (bluish), floor at the bottom (grey,
  // bright): a frame read bottom-up would show them swapped
  const std::uint8_t* sky = image.at(kW / 2, 2);
  const std::uint8_t* floor = image.at(kW / 2, kH - 3);
  EXPECT_GT(sky[2], sky[0] + 20) << "top row is not sky";
  EXPECT_GT(floor[0] + floor[1] + floor[2], sky[0] + sky[1] + sky[2]) << "bottom row is not floor";
}

TEST(OffscreenRenderer, RobotPixelsAreWhereTheRobotProjects) {
  const Robot panda = Robot::bundled("panda");
  const Robot empty = test::empty_scene();
  DataPtr d = test::panda_home(panda);
  DataPtr e = empty.make_data();
  RenderOptions plain;  // no shadows or reflections: the robot changes only its own pixels
  plain.shadows = false;
  plain.reflections = false;
  OffscreenRenderer with_robot(panda, kW, kH, plain);
  OffscreenRenderer without(empty, kW, kH, plain);
  const Image a = with_robot.render(*d, kFront);
  const Image b = without.render(*e, kFront);
  const std::vector<bool> changed = changed_pixels(a, b);

  // the box around the projections of every robot geom's bounding sphere
  const CameraView view = with_robot.view(*d, kFront);
  const mjModel& m = panda.model();
  const Eigen::Vector3d right = view.forward.cross(view.up);
  double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_bodyid[g] == 0) continue;
    const Eigen::Vector3d c(d->geom_xpos + 3 * g);
    for (int corner = 0; corner < 4; ++corner) {
      const double r = m.geom_rbound[g];
      const Eigen::Vector3d p = c + r * ((corner & 1) ? right : Eigen::Vector3d(-right)) +
                                r * ((corner & 2) ? view.up : Eigen::Vector3d(-view.up));
      const Eigen::Vector3d uvd = project(view, kW, kH, p);
      ASSERT_GT(uvd.z(), 0.0);
      u0 = std::min(u0, uvd.x());
      u1 = std::max(u1, uvd.x());
      v0 = std::min(v0, uvd.y());
      v1 = std::max(v1, uvd.y());
    }
  }
  std::size_t total = 0, inside = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (!changed[static_cast<std::size_t>(y * kW + x)]) continue;
      ++total;
      if (x + 1 >= u0 && x <= u1 && y + 1 >= v0 && y <= v1) ++inside;
    }
  }
  const double box_share = (u1 - u0) * (v1 - v0) / (kW * kH);
  const double changed_share = static_cast<double>(total) / (kW * kH);
  RecordProperty("changed_share", std::to_string(changed_share));
  RecordProperty("box_share", std::to_string(box_share));
  RecordProperty("inside_share", std::to_string(static_cast<double>(inside) / total));
  EXPECT_GT(changed_share, 0.02) << "the robot is hardly visible";
  EXPECT_LT(box_share, 0.4) << "the projected box is too large for the test to mean much";
  EXPECT_GE(static_cast<double>(inside), 0.99 * static_cast<double>(total))
      << inside << " of " << total << " changed pixels inside the robot's projected box [" << u0
      << ", " << u1 << "] × [" << v0 << ", " << v1 << "]";
  // and the robot covers a good part of its box (it is drawn where it projects, not elsewhere)
  EXPECT_GT(static_cast<double>(total), 0.15 * box_share * kW * kH);
}

TEST(OffscreenRenderer, HiddenGeomGroupsRemoveTheRobot) {
  const Robot panda = Robot::bundled("panda");
  const Robot empty = test::empty_scene();
  DataPtr d = test::panda_home(panda);
  DataPtr e = empty.make_data();
  RenderOptions sky_only;
  sky_only.shadows = false;
  sky_only.reflections = false;
  sky_only.geom_groups = {false, false, false, false, false, false};
  OffscreenRenderer r(panda, kW, kH, sky_only);
  OffscreenRenderer s(empty, kW, kH, sky_only);
  const Image a = r.render(*d, kFront);
  const Image b = s.render(*e, kFront);
  std::size_t changed = 0;
  for (bool c : changed_pixels(a, b, 6)) changed += c ? 1 : 0;
  EXPECT_EQ(changed, 0u) << "with every geom group hidden both scenes show only the sky";
  // switching the groups back on brings the robot back
  RenderOptions all;
  r.set_options(all);
  EXPECT_TRUE(r.options().geom_groups[0]);
  EXPECT_FALSE(same(r.render(*d, kFront), a));
}

TEST(OffscreenRenderer, FreeCameraFollowsTheDocumentedConventions) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  OffscreenRenderer renderer(panda, kW, kH);
  for (const double azimuth : {0.0, 90.0, 150.0, -60.0}) {
    for (const double elevation : {-45.0, -10.0, 20.0}) {
      const auto spec = CameraSpec::free_camera({0.1, -0.2, 0.4}, 1.7, azimuth, elevation);
      const CameraView mujoco = renderer.view(*d, spec);
      const CameraView ours = free_camera_view(spec.lookat, spec.distance, azimuth, elevation,
                                               panda.model().vis.global.fovy);
      EXPECT_LT((mujoco.position - ours.position).norm(), 1e-5) << azimuth << " " << elevation;
      EXPECT_LT((mujoco.forward - ours.forward).norm(), 1e-5);
      EXPECT_LT((mujoco.up - ours.up).norm(), 1e-5);
      EXPECT_NEAR(mujoco.fovy, ours.fovy, 1e-3);
      // negative elevation: the camera is above the look-at point
      EXPECT_EQ(ours.position.z() > spec.lookat.z(), elevation < 0.0);
    }
  }
}

TEST(OffscreenRenderer, ModelCamerasSeeTheBallWhereItProjects) {
  const Robot scene = Robot::from_string(kCameraScene, MJARM_MODELS_DIR);
  DataPtr d = scene.make_data();
  mj_forward(&scene.model(), d.get());
  OffscreenRenderer renderer(scene, kW, kH);
  const Eigen::Vector3d ball(0.3, 0.1, 0.4);
  for (const char* name : {"overhead", "side"}) {
    const CameraSpec spec = CameraSpec::model_camera(name);
    const CameraView view = renderer.view(*d, spec);
    const int cam = scene.camera(name);
    EXPECT_LT((view.position - Eigen::Vector3d(d->cam_xpos + 3 * cam)).norm(), 1e-5) << name;
    EXPECT_NEAR(view.fovy, scene.model().cam_fovy[cam], 1e-3);
    const Eigen::Vector3d uvd = project(view, kW, kH, ball);
    ASSERT_GT(uvd.z(), 0.0) << name;
    const Image image = renderer.render(*d, spec);
    const std::uint8_t* px = image.at(static_cast<int>(uvd.x()), static_cast<int>(uvd.y()));
    EXPECT_GT(px[0], 100) << name << ": the ball's centre is not red";
    EXPECT_LT(px[1] + px[2], px[0]) << name;
  }
}

TEST(OffscreenRenderer, UnknownCameraListsTheCameras) {
  const Robot scene = Robot::from_string(kCameraScene, MJARM_MODELS_DIR);
  DataPtr d = scene.make_data();
  OffscreenRenderer renderer(scene, kW, kH);
  const std::string message =
      error_of([&] { renderer.render(*d, CameraSpec::model_camera("top")); });
  EXPECT_NE(message.find("camera 'top' not found in model 'cameras'"), std::string::npos)
      << message;
  EXPECT_NE(message.find("overhead, side"), std::string::npos) << message;
  // a model without cameras says so
  const Robot panda = Robot::bundled("panda");
  DataPtr p = panda.make_data();
  OffscreenRenderer panda_renderer(panda, kW, kH);
  const std::string none =
      error_of([&] { panda_renderer.view(*p, CameraSpec::model_camera("x")); });
  EXPECT_NE(none.find("cameras: (none)"), std::string::npos) << none;
  // and an unknown follow target lists sites and bodies
  const std::string follow =
      error_of([&] { panda_renderer.render(*p, CameraSpec::follow("hand", 1.0, 90, -30)); });
  EXPECT_NE(follow.find("attachment_site"), std::string::npos) << follow;
  EXPECT_NE(follow.find("link7"), std::string::npos) << follow;
}

TEST(OffscreenRenderer, FollowCameraKeepsTheEndEffectorAtTheCentre) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  OffscreenRenderer renderer(panda, kW, kH);
  const CameraSpec follow = CameraSpec::follow("attachment_site", 0.8, 120.0, -30.0);
  const int site = panda.site("attachment_site");
  const Image first = renderer.render(*d, follow);
  Eigen::Vector3d p_first(d->site_xpos + 3 * site);
  // move the arm: the site moves, the camera goes with it
  d->qpos[0] += 0.8;
  d->qpos[3] += 0.5;
  mj_forward(&panda.model(), d.get());
  const Eigen::Vector3d p_second(d->site_xpos + 3 * site);
  ASSERT_GT((p_second - p_first).norm(), 0.1);
  const CameraView view = renderer.view(*d, follow);
  const Eigen::Vector3d uvd = project(view, kW, kH, p_second);
  EXPECT_NEAR(uvd.x(), kW / 2.0, 1e-3);
  EXPECT_NEAR(uvd.y(), kH / 2.0, 1e-3);
  EXPECT_NEAR(uvd.z(), 0.8, 1e-5);
  const Image second = renderer.render(*d, follow);
  EXPECT_FALSE(same(first, second));
  EXPECT_GT(pixel_stats(second).grey_stddev, 10.0);
}

TEST(OffscreenRenderer, SeveralCamerasInOneRun) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  OffscreenRenderer renderer(panda, kW, kH);
  const std::vector<CameraSpec> cameras = {
      kFront, CameraSpec::free_camera({0, 0, 0.4}, 2.2, 30.0, -15.0),
      CameraSpec::follow("attachment_site", 0.6, 200.0, -15.0)};
  std::vector<Image> images;
  Image frame;  // reused: render resizes it once
  for (int round = 0; round < 2; ++round) {
    for (const auto& camera : cameras) {
      renderer.render(*d, camera, frame);
      if (round == 0)
        images.push_back(frame);
      else
        EXPECT_TRUE(
            same(frame, images[images.size() - cameras.size() + (&camera - cameras.data())]));
    }
  }
  for (std::size_t i = 0; i < images.size(); ++i) {
    EXPECT_GT(pixel_stats(images[i]).grey_stddev, 10.0) << i;
    for (std::size_t j = i + 1; j < images.size(); ++j) EXPECT_FALSE(same(images[i], images[j]));
  }
}

TEST(OffscreenRenderer, SecondRendererAfterTheFirstAndTwoAtOnce) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  Image first;
  {
    OffscreenRenderer a(panda, kW, kH);
    first = a.render(*d, kFront);
  }  // destroyed: its context and the EGL display go
  OffscreenRenderer b(panda, kW, kH);
  const Image second = b.render(*d, kFront);
  EXPECT_LT(pixel_stats(first).dark_share, 0.05);
  EXPECT_TRUE(same(first, second)) << "a second renderer draws the same picture";
  // two alive, used in turn, then one closed while the other keeps going
  OffscreenRenderer c(panda, kW, kH);
  EXPECT_TRUE(same(c.render(*d, kFront), first));
  EXPECT_TRUE(same(b.render(*d, kFront), first));
  b.close();
  EXPECT_TRUE(same(c.render(*d, kFront), first));
  // moving keeps the context working
  OffscreenRenderer moved = std::move(c);
  EXPECT_FALSE(c.is_open());
  EXPECT_TRUE(same(moved.render(*d, kFront), first));
}

TEST(OffscreenRenderer, UseAfterCloseThrows) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  OffscreenRenderer renderer(panda, kW, kH);
  EXPECT_TRUE(renderer.is_open());
  renderer.close();
  renderer.close();  // idempotent
  EXPECT_FALSE(renderer.is_open());
  const std::string message = error_of([&] { renderer.render(*d, kFront); });
  EXPECT_NE(message.find("after close"), std::string::npos) << message;
  EXPECT_THROW(renderer.view(*d, kFront), Error);
  EXPECT_THROW(renderer.set_options({}), Error);
  EXPECT_THROW(static_cast<void>(renderer.gl_description()), Error);
}

TEST(OffscreenRenderer, BadSizesAndNumbersAreErrors) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  EXPECT_NE(error_of([&] { OffscreenRenderer(panda, 0, 240); }).find("at least 1×1"),
            std::string::npos);
  EXPECT_THROW(OffscreenRenderer(panda, 320, -5), Error);
  EXPECT_THROW(OffscreenRenderer(panda, 1 << 20, 16), Error);
  OffscreenRenderer renderer(panda, kW, kH);
  EXPECT_NE(error_of([&] {
              renderer.render(*d, CameraSpec::free_camera({0, 0, 0}, 0.0, 90, -30));
            }).find("distance"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              renderer.render(*d, CameraSpec::free_camera({0, 0, 0}, 1.0, 90, -90));
            }).find("elevation"),
            std::string::npos);
  EXPECT_THROW(renderer.render(*d, CameraSpec::free_camera({0, NAN, 0}, 1.0, 90, -30)), Error);
  // an mjData of another model
  const Robot ur5e = Robot::bundled("ur5e");
  DataPtr other = ur5e.make_data();
  EXPECT_NE(error_of([&] { renderer.render(*other, kFront); }).find("not made for model 'panda'"),
            std::string::npos);
}

// issue 16, item 6's class (a number that overflows downstream gives a silently wrong result):
// `mjarm render --lookat 1e308 0 0` or `--distance 1e39` wrote an all-black picture and exit 0
// (single precision makes them infinite); a camera that cannot see any of the model is an error
TEST(OffscreenRenderer, ACameraThatCannotSeeTheModelIsAnError) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  OffscreenRenderer renderer(panda, kW, kH);
  const mjModel& m = panda.model();
  const double zfar = m.vis.map.zfar * m.stat.extent;  // the far clipping plane [m]
  const Eigen::Vector3d centre(m.stat.center[0], m.stat.center[1], m.stat.center[2]);
  for (const CameraSpec& far : {CameraSpec::free_camera({1e308, 0, 0}, 1.0, 90, -30),
                                CameraSpec::free_camera(centre, 1e39, 90, -30),
                                CameraSpec::free_camera(centre, zfar + 2.0 * m.stat.extent, 90, 0),
                                CameraSpec::follow("attachment_site", 1e20, 90, -30)}) {
    const std::string message = error_of([&] { renderer.render(*d, far); });
    EXPECT_NE(message.find("beyond the far clipping plane"), std::string::npos) << message;
    EXPECT_NE(message.find("model 'panda'"), std::string::npos) << message;
  }
  // just inside the plane the nearest part of the model is drawn: not an error
  const Image image =
      renderer.render(*d, CameraSpec::free_camera(centre, zfar + 0.5 * m.stat.extent, 90, 0));
  EXPECT_EQ(image.width, kW);
}

TEST(OffscreenRenderer, LargerThanTheModelOffscreenBufferAndOddSizes) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  const mjModel& m = panda.model();
  ASSERT_EQ(m.vis.global.offwidth, 1280);
  OffscreenRenderer big(panda, 1601, 901);
  const Image image = big.render(*d, kFront);
  EXPECT_EQ(image.width, 1601);
  EXPECT_EQ(image.height, 901);
  EXPECT_LT(pixel_stats(image).dark_share, 0.05);
  EXPECT_EQ(m.vis.global.offwidth, 1280) << "the shared model was modified";
  EXPECT_EQ(m.vis.global.offheight, 720);
  OffscreenRenderer tiny(panda, 1, 1);
  EXPECT_EQ(tiny.render(*d, kFront).rgb.size(), 3u);
}

// the shadow map is sized to the picture (the power of two at or above 4 × its longer side at
// most, docs/rendering.md): a small picture still shows the ball's shadow on the floor, and the
// shared model keeps its own shadow map size
TEST(OffscreenRenderer, ASmallPictureStillShowsShadows) {
  const Robot scene = Robot::from_string(kCameraScene, MJARM_MODELS_DIR);
  DataPtr d = scene.make_data();
  mj_forward(&scene.model(), d.get());
  const int model_side = scene.model().vis.quality.shadowsize;
  RenderOptions lit;
  lit.reflections = false;
  RenderOptions unlit = lit;
  unlit.shadows = false;
  // from above at 45°: the ball 0.4 m over the floor and, below it, its shadow (the key light
  // shines straight down): 31 pixels of the 64×48 darker when measured
  const CameraSpec spec = CameraSpec::free_camera({0.3, 0.1, 0.2}, 1.5, 90.0, -45.0);
  OffscreenRenderer with_shadows(scene, 64, 48, lit);
  OffscreenRenderer without_shadows(scene, 64, 48, unlit);
  const Image a = with_shadows.render(*d, spec);
  const Image b = without_shadows.render(*d, spec);
  int darker = 0;
  for (std::size_t p = 0; p < a.pixels(); ++p) {
    const int lit_sum = a.rgb[3 * p] + a.rgb[3 * p + 1] + a.rgb[3 * p + 2];
    const int unlit_sum = b.rgb[3 * p] + b.rgb[3 * p + 1] + b.rgb[3 * p + 2];
    if (lit_sum + 60 < unlit_sum) ++darker;
  }
  EXPECT_GE(darker, 10) << "no shadow in a 64×48 picture";
  EXPECT_EQ(scene.model().vis.quality.shadowsize, model_side) << "the shared model was modified";
}

TEST(OffscreenRenderer, CallerDataIsOnlyRead) {
  const Robot panda = Robot::bundled("panda");
  DataPtr d = test::panda_home(panda);
  // the data's own buffer (mjModel::nbuffer is the model's)
  const std::size_t bytes = static_cast<std::size_t>(d->nbuffer);
  const std::vector<std::uint8_t> before(static_cast<std::uint8_t*>(d->buffer),
                                         static_cast<std::uint8_t*>(d->buffer) + bytes);
  const int pstack = static_cast<int>(d->pstack);
  OffscreenRenderer renderer(panda, kW, kH);
  renderer.render(*d, kFront);
  renderer.render(*d, CameraSpec::follow("link4", 1.0, 30, -20));
  EXPECT_EQ(std::memcmp(before.data(), d->buffer, bytes), 0);
  EXPECT_EQ(static_cast<int>(d->pstack), pstack);
}

TEST(OffscreenRenderer, FramingShowsTheWholeRobot) {
  for (const char* name : {"panda", "ur5e", "dual_arm"}) {
    const Robot robot = Robot::bundled(name);
    DataPtr d = robot.make_data();
    mj_forward(&robot.model(), d.get());
    const CameraSpec spec = frame_robot(robot, *d);
    OffscreenRenderer renderer(robot, kW, kH);
    const CameraView view = renderer.view(*d, spec);
    for (int b = 1; b < robot.model().nbody; ++b) {
      const Eigen::Vector3d uvd = project(view, kW, kH, Eigen::Vector3d(d->xpos + 3 * b));
      EXPECT_GT(uvd.z(), 0.0) << name;
      EXPECT_TRUE(uvd.x() > 0 && uvd.x() < kW && uvd.y() > 0 && uvd.y() < kH)
          << name << " body " << b << " outside the picture";
    }
  }
  EXPECT_THROW(frame_robot(test::empty_scene(), *test::empty_scene().make_data()), Error);
}

}  // namespace
}  // namespace mjarm
