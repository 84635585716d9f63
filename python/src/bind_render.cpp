// render room: headless offscreen rendering (images as NumPy arrays), cameras, video.
#include <cstring>

#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/render/camera.hpp"
#include "mjarm/render/offscreen_renderer.hpp"
#include "mjarm/render/video_writer.hpp"

namespace mjarm::python {
namespace {

/// (height, width, 3) uint8 array owning a copy of the image's rows (top row first).
py::array_t<std::uint8_t> to_numpy(const Image& image) {
  py::array_t<std::uint8_t> a({image.height, image.width, 3});
  std::memcpy(a.mutable_data(), image.rgb.data(), image.rgb.size());
  return a;
}

}  // namespace

void bind_render(py::module_& m) {
  def_enum<CameraKind>(m, "CameraKind");
  auto camera = py::class_<CameraSpec>(m, "CameraSpec",
                                       "A model camera, a free camera or one following a frame.");
  camera.def(py::init<>())
      .def_static("model_camera", &CameraSpec::model_camera, py::arg("name"))
      .def_static(
          "free_camera",
          [](py::handle lookat, double d, double az, double el) {
            return CameraSpec::free_camera(to_fixed<3>(lookat, "lookat"), d, az, el);
          },
          py::arg("lookat"), py::arg("distance"), py::arg("azimuth") = 135.0,
          py::arg("elevation") = -25.0)
      .def_static("follow", &CameraSpec::follow, py::arg("frame"), py::arg("distance"),
                  py::arg("azimuth") = 135.0, py::arg("elevation") = -25.0)
      .def("describe", &CameraSpec::describe);
  def_fields(camera);
  m.def(
      "frame_robot",
      [](const Robot& r, const DataHandle& d, double az, double el) {
        return frame_robot(r, data_of(r, d, "frame_robot"), az, el);
      },
      py::arg("robot"), py::arg("data"), py::arg("azimuth") = 135.0, py::arg("elevation") = -25.0,
      "A free camera that frames the whole robot.");

  py::class_<RenderOptions> render_options(m, "RenderOptions");
  render_options.def(py::init<>());
  def_fields(render_options);
  py::class_<OffscreenRenderer>(m, "OffscreenRenderer",
                                "Headless rendering (EGL, no display). render() returns an "
                                "(height, width, 3) uint8 array, top row first.")
      .def(py::init<const Robot&, int, int, RenderOptions>(), py::arg("robot"), py::arg("width"),
           py::arg("height"), py::arg("options") = RenderOptions{})
      .def(
          "render",
          [](OffscreenRenderer& r, const DataHandle& d, const CameraSpec& camera) {
            const mjData& data =
                data_of(r.robot(), d, "OffscreenRenderer.render", "the renderer's model");
            Image image;
            {
              py::gil_scoped_release release;
              image = r.render(data, camera);
            }
            return to_numpy(image);
          },
          py::arg("data"), py::arg("camera"))
      .def_property_readonly("width", &OffscreenRenderer::width, "image width [pixels]")
      .def_property_readonly("height", &OffscreenRenderer::height, "image height [pixels]")
      .def("close", &OffscreenRenderer::close)
      .def_property_readonly("is_open", &OffscreenRenderer::is_open, "False after close()");

  py::class_<VideoWriter>(m, "VideoWriter", "MP4 through ffmpeg: a complete video or none.")
      .def(py::init([](const std::filesystem::path& p, int w, int h, double fps) {
             return std::make_unique<VideoWriter>(p, w, h, fps);
           }),
           py::arg("path"), py::arg("width"), py::arg("height"), py::arg("fps"))
      .def(
          "write",
          [](VideoWriter& v, py::handle frame) {
            const auto a =
                py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(frame);
            if (!a || a.ndim() != 3 || a.shape(0) != v.height() || a.shape(1) != v.width() ||
                a.shape(2) != 3) {
              throw py::value_error("frame: expected a uint8 array of shape (" +
                                    std::to_string(v.height()) + ", " + std::to_string(v.width()) +
                                    ", 3)");
            }
            Image image(v.width(), v.height());
            std::memcpy(image.rgb.data(), a.data(), image.rgb.size());
            v.write(image);
          },
          py::arg("frame"))
      .def("close", &VideoWriter::close)
      .def_property_readonly("frames", &VideoWriter::frames, "frames written so far")
      .def_property_readonly(
          "complete", &VideoWriter::complete,
          "True once the finalized, checked video is at path() (after a successful close())");
}

}  // namespace mjarm::python
