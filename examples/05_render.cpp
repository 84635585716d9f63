// 05_render: render the bundled Panda at its "home" keyframe without any display or GPU, write
// the picture as a PNG and check that the arm is in it: the picture of the same camera with the
// arm out of the scene (only the floor, sky and lights of models/common/scene.xml) must differ.
//
// Usage: example_05_render [out.png]   (default: 05_render.png in the current directory)

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "mjarm/model/robot.hpp"
#include "mjarm/render/offscreen_renderer.hpp"
#include "mjarm/render/png.hpp"

int main(int argc, char** argv) try {
  const char* out = argc > 1 ? argv[1] : "05_render.png";
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  mjarm::DataPtr data = robot.make_data();
  const std::vector<double> home = robot.keyframe_qpos("home");
  for (int i = 0; i < robot.nq(); ++i) data->qpos[i] = home[static_cast<std::size_t>(i)];
  mj_forward(&robot.model(), data.get());

  // a three-quarter view from the front right, looking slightly down at the arm's middle
  const auto camera = mjarm::CameraSpec::free_camera({0.2, 0.0, 0.45}, 1.9, 150.0, -20.0);
  mjarm::OffscreenRenderer renderer(robot, 640, 480);
  const mjarm::Image image = renderer.render(*data, camera);
  mjarm::write_png(image, out);

  // the empty scene: same floor, lights and camera, no arm
  const mjarm::Robot empty = mjarm::Robot::from_string(
      R"(<mujoco model="empty"><include file="common/scene.xml"/></mujoco>)",
      mjarm::Robot::models_dir());
  mjarm::DataPtr empty_data = empty.make_data();
  mjarm::OffscreenRenderer empty_renderer(empty, 640, 480);
  const mjarm::Image background = empty_renderer.render(*empty_data, camera);

  std::size_t changed = 0;
  for (std::size_t p = 0; p < image.pixels(); ++p) {
    int difference = 0;
    for (int c = 0; c < 3; ++c)
      difference += std::abs(image.rgb[3 * p + c] - background.rgb[3 * p + c]);
    if (difference > 30) ++changed;
  }
  const double share = static_cast<double>(changed) / static_cast<double>(image.pixels());
  std::printf("%s\n", renderer.gl_description().c_str());
  std::printf("wrote %s (%d×%d); the arm changes %.1f%% of the pixels of the empty scene\n", out,
              image.width, image.height, 100.0 * share);
  return share > 0.02 ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "05_render: %s\n", e.what());
  return 1;
}
