// `mjarm plot RECORDING [--out DIR] [--size WxH] [--json]`: PNG figures of a recording made with
// `mjarm run … --record DIR`, drawn by gnuplot (Debian package gnuplot-nox).

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/plot/plots.hpp"

namespace mjarm::cli {
Command add_plot_command(CLI::App& root) {
  struct Options {
    std::string recording;
    std::string out;
    std::string size = "1280x720";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "plot",
      "draw PNG figures of a recording: tracking error, joint torques, contact force, phases");
  app->footer(
      "RECORDING is a folder written by `mjarm run … --record DIR`. Four figures are written: "
      "tracking_error.png, joint_torques.png, contact_force.png, phases.png; the gnuplot script "
      "and data stay in OUT/gnuplot/. Needs gnuplot (Debian: apt-get install gnuplot-nox).");
  app->add_option("RECORDING", options->recording,
                  "recording folder (state.csv, task.csv, events.csv, summary.json)")
      ->required();
  app->add_option("--out", options->out, "folder for the PNG files [default: RECORDING/plots]");
  app->add_option("--size", options->size, "figure size WIDTHxHEIGHT [pixels]")
      ->capture_default_str()
      ->check(pixel_size({200, 150}, false, {8192, 8192}));
  add_json_flag(*app, options->json);

  return {app, [options] {
            const PixelSize size = parse_pixel_size(options->size);
            plot::PlotOptions plot_options;
            plot_options.width = size.width;
            plot_options.height = size.height;
            const plot::Recording recording = plot::Recording::load(options->recording);
            const std::filesystem::path out = options->out.empty()
                                                  ? recording.directory() / "plots"
                                                  : std::filesystem::path(options->out);
            check_output_folder(out.string(), "--out");
            // Ctrl-C stops gnuplot; what it drew and its data are removed (exit 130)
            const InterruptGuard interrupts;
            std::vector<plot::PlotInfo> plots;
            try {
              plots = plot::make_plots(recording, out, plot_options);
            } catch (const Error& e) {
              if (interrupt_requested()) throw InterruptedError(e.what(), interrupt_signal());
              throw;
            }
            if (options->json) {
              Json document;
              document["recording"] = options->recording;
              document["out"] = out.string();
              document["size"] = {{"width", size.width}, {"height", size.height}};
              document["plots"] = Json::array();
              for (const plot::PlotInfo& p : plots) {
                document["plots"].push_back({{"name", p.name},
                                             {"path", p.path.string()},
                                             {"title", p.title},
                                             {"series", p.series},
                                             {"notes", p.notes}});
              }
              print_json(document);
              return;
            }
            for (const plot::PlotInfo& p : plots) std::cout << p.path.string() << '\n';
          }};
}

}  // namespace mjarm::cli
