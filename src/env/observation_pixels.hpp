#pragma once
// The cameras of an `ObservationSet` (private to src/env): one headless renderer for the
// environment's pictures, the cameras the `pixels:` and `depth:` observations name, and the
// buffers each picture is read into (allocated once).

#include <memory>
#include <string>
#include <vector>

#include "mjarm/env/observation_set.hpp"
#include "mjarm/render/offscreen_renderer.hpp"

namespace mjarm {

struct ObservationSet::Cameras {
  Cameras(const Robot& robot, int width, int height);

  /// The index of camera @p name ("free" or a model camera), added on first use.
  /// @throws Error naming the model's cameras for an unknown one.
  int camera(const std::string& name);

  /// Renders camera @p index of @p d into the buffers (pixels and depth both). Never throws: a
  /// failed picture is black at the far plane.
  void render(int index, const mjData& d) noexcept;

  const Robot robot;
  const int width, height;
  std::unique_ptr<OffscreenRenderer> renderer;  // made at the first camera
  std::vector<std::string> names;
  std::vector<CameraSpec> specs;
  Image image;
  std::vector<float> depth;
  int rendered = -1;  // the camera in the buffers this fill (pixels and depth: one picture)
};

/// The names of @p robot's pictures: `pixels:` and `depth:` of `free` and of every named camera.
std::vector<std::string> pixel_observations(const Robot& robot);

}  // namespace mjarm
