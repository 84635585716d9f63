// web room: a recording's replay page, one self-contained HTML file that replays it in a browser
// (docs/replay.md), as `mjarm replay-html` writes it.
#include <optional>

#include "bindings.hpp"
#include "mjarm/plot/recording.hpp"
#include "mjarm/web/recorded_model.hpp"
#include "mjarm/web/replay_html.hpp"
#include "mjarm/web/replay_html_json.hpp"
#include "parameter_values.hpp"

namespace mjarm::python {

void bind_web(py::module_& m) {
  m.def("replay_html_available", &replay_html_available,
        "True when this build holds the replay page's script (three.js, bundled when mjarm was "
        "built with node and npm: MJARM_WEB); replay_html raises mjarm.Error otherwise.");
  m.def(
      "replay_html",
      [](const std::filesystem::path& recording, const std::filesystem::path& output,
         std::optional<Robot> model, double rate, std::optional<std::string> title) {
        ReplayHtmlOptions options;
        options.rate = rate;
        if (title) options.title = *title;
        ReplayHtmlReport report;
        {
          py::gil_scoped_release release;
          const plot::Recording loaded = plot::Recording::load(recording);
          report =
              write_replay_html(model ? *model : recorded_model(loaded), loaded, output, options);
        }
        return py::dict(python_of(replay_html_json(report, recording)));
      },
      py::arg("recording"), py::arg("output"), py::arg("model") = py::none(),
      py::arg("rate") = 60.0, py::arg("title") = py::none(),
      "Writes one self-contained HTML file that replays the recording (a folder written by a "
      "Recorder or `mjarm run ... --record DIR`) in any browser, offline, and returns what "
      "`mjarm replay-html --json` prints: {recording, path, bytes, frames, state_rows, rate, "
      "start_time, end_time, largest_gap, bodies, drawn_geoms, meshes, cameras, plots}. model: "
      "the model it was recorded on (default: the recording's model.mjb); rate: frames kept per "
      "simulated second [Hz, 1 to 10000]; title: the page's (default: the recording's folder "
      "name). The file is complete or not there. Raises mjarm.Error for a missing or incomplete "
      "recording, a model that does not match it, an unwritable output, or a build without the "
      "page (replay_html_available()).");
}

}  // namespace mjarm::python
