// `mjarm replay-html RECORDING -o FILE [--model M] [--rate HZ] [--title T] [--json]`: one HTML file
// that replays a recording in any browser, offline (docs/replay.md).

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/plot/recording.hpp"
#include "mjarm/web/recorded_model.hpp"
#include "mjarm/web/replay_html.hpp"
#include "mjarm/web/replay_html_json.hpp"

namespace mjarm::cli {

Command add_replay_html_command(CLI::App& root) {
  struct Options {
    std::string recording;
    std::string out;
    std::string model;
    ReplayHtmlOptions replay;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "replay-html",
      "write one self-contained HTML file that replays a recording in a browser (offline): the "
      "scene in 3D, play, scrub, step, cameras, plots");
  app->footer(
      "RECORDING is a folder written by `mjarm run … --record DIR`. The file holds the page's "
      "script (three.js, bundled when mjarm was built) and the run: every body's pose at --rate "
      "frames per simulated second (the page interpolates between them), the model's geoms and "
      "cameras, the phases and the figures of `mjarm plot`. A run whose page would exceed "
      "--max-mb keeps fewer frames (the page, the output and --json say how many). The model is "
      "the recording's model.mjb unless --model names it; a --model whose mesh files are gone "
      "is drawn with boxes in their place, with a warning. docs/replay.md");
  app->add_option("RECORDING", options->recording,
                  "recording folder (state.csv, task.csv, events.csv, summary.json, model.mjb)")
      ->required();
  app->add_option("-o,--out", options->out, "the HTML file to write")->required();
  app->add_option("--model", options->model,
                  "the model the recording was made on (bundled name or MJCF file) [default: the "
                  "recording's model.mjb]");
  app->add_option("--rate", options->replay.rate, "frames kept per simulated second [Hz]")
      ->capture_default_str()
      ->check(number_in(1.0, 10000.0));
  app->add_option("--title", options->replay.title, "the page's title [default: RECORDING's name]");
  app->add_option("--max-mb", options->replay.max_mb,
                  "largest file [MB]: a longer run keeps fewer frames, and the page says so")
      ->capture_default_str()
      ->check(number_in(1.0, 4000.0));
  add_json_flag(*app, options->json);

  return {app, [options] {
            check_output_file(options->out, "--out");
            const plot::Recording recording =
                plot::Recording::load(options->recording, plot::TableRows::header_only);
            // a model whose meshes are gone is drawn with boxes, and the page says so
            const Robot robot = options->model.empty()
                                    ? recorded_model(recording)
                                    : load_model(options->model, {.missing_meshes_as_boxes = true});
            const ReplayHtmlReport report =
                write_replay_html(robot, recording, options->out, options->replay);
            for (const std::string& warning : report.warnings)
              std::cerr << "mjarm: warning: " << warning << "\n";
            if (options->json) {
              print_json(replay_html_json(report, options->recording));
              return;
            }
            std::cout << report.path.string() << ": " << report.bytes << " bytes, " << report.frames
                      << " frames of " << report.state_rows << " state rows ("
                      << readable(report.rate) << " per second, largest gap "
                      << readable(report.largest_gap) << " s), " << report.drawn_geoms
                      << " geoms drawn, " << report.cameras << " cameras, " << report.plots
                      << " plots\n";
            if (report.decimated) std::cout << report.decimation << "\n";
          }};
}

}  // namespace mjarm::cli
