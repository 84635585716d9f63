#include "observation_pixels.hpp"

#include <algorithm>

#include "mjarm/error.hpp"

namespace mjarm {

ObservationSet::Cameras::Cameras(const Robot& r, int w, int h) : robot(r), width(w), height(h) {
  if (w < 16 || h < 16 || w > 4096 || h > 4096) {
    throw Error("environment: pictures are 16…4096 pixels wide and high, got " + std::to_string(w) +
                "×" + std::to_string(h));
  }
}

std::vector<std::string> pixel_observations(const Robot& robot) {
  std::vector<std::string> cameras{"free"};
  const mjModel& m = robot.model();
  for (int id = 0; id < m.ncam; ++id) {
    const char* name = mj_id2name(&m, mjOBJ_CAMERA, id);
    if (name != nullptr && name[0] != '\0') cameras.emplace_back(name);
  }
  std::vector<std::string> out;
  for (const std::string& c : cameras) out.push_back("pixels:" + c);
  for (const std::string& c : cameras) out.push_back("depth:" + c);
  return out;
}

int ObservationSet::Cameras::camera(const std::string& name) {
  const auto known = std::find(names.begin(), names.end(), name);
  if (known != names.end()) return static_cast<int>(known - names.begin());
  CameraSpec spec;
  if (name == "free") {
    // a free camera framing the model at its reference configuration
    DataPtr d = robot.make_data();
    mj_forward(&robot.model(), d.get());
    spec = frame_robot(robot, *d);
  } else {
    if (mj_name2id(&robot.model(), mjOBJ_CAMERA, name.c_str()) < 0) {
      std::string cameras;
      for (const std::string& p : pixel_observations(robot))
        if (p.rfind("pixels:", 0) == 0) cameras += (cameras.empty() ? "" : ", ") + p.substr(7);
      throw Error("observation of camera '" + name + "': model '" + robot.name() +
                  "' has no such camera; cameras: " + cameras);
    }
    spec = CameraSpec::model_camera(name);
  }
  if (!renderer) {
    // no shadows nor reflections: on a CPU renderer the shadow map costs most of a picture
    RenderOptions options;
    options.shadows = false;
    options.reflections = false;
    renderer = std::make_unique<OffscreenRenderer>(robot, width, height, options);
  }
  names.push_back(name);
  specs.push_back(spec);
  image = Image(width, height);
  depth.assign(image.pixels(), 0.0f);
  return static_cast<int>(names.size()) - 1;
}

void ObservationSet::Cameras::render(int index, const mjData& d) noexcept {
  // pixels and depth of one camera in one step come from one picture
  if (rendered == index) return;
  try {
    renderer->render(d, specs[static_cast<std::size_t>(index)], image, depth);
    rendered = index;
  } catch (...) {
    std::fill(image.rgb.begin(), image.rgb.end(), std::uint8_t{0});
    std::fill(depth.begin(), depth.end(), 0.0f);
    rendered = -1;
  }
}

}  // namespace mjarm
