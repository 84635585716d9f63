// teleop room: the passive viewer, a window on the user's own loop (mjarm.viewer.launch_passive).
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/teleop/passive_viewer.hpp"
#include "mjarm/teleop/passive_web_viewer.hpp"
#include "spec_support.hpp"

namespace mjarm::python {
namespace {

Rgba to_rgba(py::handle object) {
  const Eigen::Vector4d c = to_fixed<4>(object, "rgba");
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]),
          static_cast<float>(c[3])};
}

}  // namespace

void bind_teleop(py::module_& m) {
  auto options = py::class_<PassiveViewerOptions>(
      m, "PassiveViewerOptions", "How the passive viewer's window looks and runs.");
  fields_init<PassiveViewerOptions>(options, "PassiveViewerOptions");
  def_fields(options);
  options
      .def_property(
          "camera", [](const PassiveViewerOptions& o) { return o.camera; },
          [](PassiveViewerOptions& o, std::optional<CameraSpec> c) { o.camera = std::move(c); },
          "the camera at the start: a free or model CameraSpec (None: frames the model)")
      .def_property(
          "script",
          [](const PassiveViewerOptions& o) -> py::object {
            return o.script ? py::cast(o.script->commands.size()) : py::none();
          },
          [](PassiveViewerOptions& o, std::optional<std::string> text) {
            if (text) {
              o.script = ViewerScript::parse(*text);
            } else {
              o.script.reset();
            }
          },
          "scripted input as text (select, press, move, release, drag, key, set, screenshot, "
          "wait; see docs/viewer.md); reads back the number of commands, or None");

  py::class_<ViewerReport>(m, "ViewerReport", "What a viewer's window did.")
      .def_readonly("ended_by", &ViewerReport::ended_by,
                    "how it ended: 'window closed', 'escape', 'closed by the program', 'end of "
                    "script', 'quit', 'interrupted', 'error'")
      .def_readonly("frames", &ViewerReport::frames, "frames drawn")
      .def_readonly("wall_seconds", &ViewerReport::wall_seconds, "how long the window was open [s]")
      .def_readonly("gl", &ViewerReport::gl, "OpenGL vendor, renderer and version")
      .def_property_readonly(
          "screenshots",
          [](const ViewerReport& r) {
            std::vector<std::string> paths;
            for (const auto& shot : r.screenshots) paths.push_back(shot.path);
            return paths;
          },
          "the screenshots a script wrote, in order (paths)");

  py::class_<PassiveViewer>(
      m, "PassiveViewer",
      "A window on your own loop (mujoco.viewer.launch_passive): the window runs in a thread of "
      "its own and draws the state your loop hands over with sync(). Double-click selects a "
      "body; Ctrl + right drag pulls it, Ctrl + left drag turns it (a spring written into the "
      "data's xfrc_applied at each sync). Markers and plotted values go with the next sync. "
      "A context manager: leaving the block closes the window. Prefer "
      "mjarm.viewer.launch_passive.")
      .def(py::init(
               [](const Robot& robot, const DataHandle& data, const PassiveViewerOptions& options) {
                 mjData& d = data_of(robot, data, "PassiveViewer");
                 py::gil_scoped_release release;  // the window opens in its own thread
                 return std::make_unique<PassiveViewer>(robot, d, options);
               }),
           py::arg("robot"), py::arg("data"), py::arg("options") = PassiveViewerOptions{},
           py::keep_alive<1, 3>(),
           "Opens the window on robot showing data, which your loop keeps stepping. Raises "
           "mjarm.Error when there is no display, the data is another model's, or an option is "
           "out of range.")
      .def("is_running", &PassiveViewer::running,
           "False once the window closed (the user, escape, the script's end, close(), an error).")
      .def("sync", &PassiveViewer::sync,
           "Hands the current state, markers and plotted values over to the window, and writes "
           "the mouse's perturbation into the data. Raises the window's error (once); nothing "
           "once the window closed.")
      .def(
          "close",
          [](PassiveViewer& v) {
            py::gil_scoped_release release;
            v.close();
          },
          "Closes the window and waits for its thread.")
      .def("__enter__", [](PassiveViewer& v) -> PassiveViewer& { return v; })
      .def("__exit__",
           [](PassiveViewer& v, const py::args&) {
             py::gil_scoped_release release;
             v.close();
           })
      .def(
          "add_frame",
          [](PassiveViewer& v, py::handle pose, double length) {
            return v.markers().add_frame(to_pose(pose, "pose"), length);
          },
          py::arg("pose"), py::arg("length") = 0.1,
          "Draws the axes of pose (a Pose or 4x4 matrix; x red, y green, z blue), length [m] "
          "long, with the next sync. False when the markers of one sync are used up.")
      .def(
          "add_arrow",
          [](PassiveViewer& v, py::handle from, py::handle to, py::handle rgba, double radius) {
            return v.markers().add_arrow(to_fixed<3>(from, "from"), to_fixed<3>(to, "to"),
                                         to_rgba(rgba), radius);
          },
          py::arg("start"), py::arg("end"),
          py::arg("rgba") = std::vector<double>{0.9, 0.6, 0.1, 1.0}, py::arg("radius") = 0.006,
          "An arrow from start to end [m], radius [m] thick.")
      .def(
          "add_sphere",
          [](PassiveViewer& v, py::handle p, double radius, py::handle rgba) {
            return v.markers().add_sphere(to_fixed<3>(p, "position"), radius, to_rgba(rgba));
          },
          py::arg("position"), py::arg("radius"),
          py::arg("rgba") = std::vector<double>{0.2, 0.6, 0.9, 0.6}, "A ball of radius [m].")
      .def(
          "add_line",
          [](PassiveViewer& v, py::handle a, py::handle b, py::handle rgba, double width) {
            return v.markers().add_line(to_fixed<3>(a, "start"), to_fixed<3>(b, "end"),
                                        to_rgba(rgba), width);
          },
          py::arg("start"), py::arg("end"),
          py::arg("rgba") = std::vector<double>{1.0, 1.0, 1.0, 1.0}, py::arg("width") = 2.0,
          "A line segment, width pixels wide.")
      .def(
          "add_text",
          [](PassiveViewer& v, py::handle p, const std::string& text, py::handle rgba) {
            return v.markers().add_text(to_fixed<3>(p, "position"), text, to_rgba(rgba));
          },
          py::arg("position"), py::arg("text"),
          py::arg("rgba") = std::vector<double>{1.0, 1.0, 1.0, 1.0},
          "A text label (at most 99 bytes shown) at position [m].")
      .def("plot", &PassiveViewer::plot, py::arg("line"), py::arg("value"),
           "Sets plot line's value for the next sync (the 'Your plots' figure; at most 8 lines).")
      .def_property_readonly("report", &PassiveViewer::report,
                             "what the window did (complete once it closed)")
      .def_property_readonly("syncs", &PassiveViewer::syncs, "states handed over so far")
      .def_property_readonly("selected_body", &PassiveViewer::selected_body,
                             "the body the mouse selected (0: none)")
      .def_property_readonly("perturbing", &PassiveViewer::perturbing,
                             "whether a Ctrl drag pulls or turns the selected body now");

  auto server_options = py::class_<LiveServerOptions>(
      m, "LiveServerOptions",
      "Where the web viewer listens and how it sends (127.0.0.1 by default; any other interface "
      "needs the access token printed within its url).");
  fields_init<LiveServerOptions>(server_options, "LiveServerOptions");
  def_fields(server_options);
  py::class_<PassiveWebViewer>(
      m, "PassiveWebViewer",
      "The passive viewer for machines without a display: your loop steps the data and calls "
      "sync(); every browser at url sees the bodies move. sync() never waits for a browser. A "
      "context manager: leaving the block stops serving. Prefer mjarm.viewer.launch_passive(..., "
      "web=True).")
      .def(py::init(
               [](const Robot& robot, const DataHandle& data, const LiveServerOptions& options) {
                 return std::make_unique<PassiveWebViewer>(
                     robot, data_of(robot, data, "PassiveWebViewer"), options);
               }),
           py::arg("robot"), py::arg("data"), py::arg("options") = LiveServerOptions{},
           py::keep_alive<1, 3>(),
           "Serves robot's bodies as data holds them on the replay page's scene in live mode. "
           "Raises mjarm.Error when the data is another model's, the build holds no page "
           "(MJARM_WEB; the message says how to get it) or the address cannot be listened on.")
      .def("sync", &PassiveWebViewer::sync,
           "Publishes the data's time and body poses (as the last mj_step or mj_forward left "
           "them) to every browser; returns at once.")
      .def("is_running", &PassiveWebViewer::running, "False once closed.")
      .def("close", &PassiveWebViewer::close, "Stops serving; the browsers are disconnected.")
      .def("__enter__", [](PassiveWebViewer& v) -> PassiveWebViewer& { return v; })
      .def("__exit__", [](PassiveWebViewer& v, const py::args&) { v.close(); })
      .def_property_readonly("url", &PassiveWebViewer::url,
                             "the page's address, with ?token=... when one is needed")
      .def_property_readonly("syncs", &PassiveWebViewer::syncs, "states published so far")
      .def_property_readonly(
          "stats",
          [](const PassiveWebViewer& v) {
            const LiveServerStats s = v.stats();
            py::dict d;
            d["clients"] = s.clients;
            d["connections"] = s.connections;
            d["published"] = s.published;
            d["sent"] = s.sent;
            d["skipped"] = s.skipped;
            d["refused"] = s.refused;
            d["pages"] = s.pages;
            return d;
          },
          "what the server did: clients now, connections, frames published, sent and skipped, "
          "requests refused, pages served");
}

}  // namespace mjarm::python
