// `mjarm run SCENARIO` for a scenario of the registry that has no subcommand of its own
// (bimanual-lift, wiping, and any scenario added later): every parameter as an option, with
// --record, --video and --json, run through `Scenario::run` (docs/scenarios.md).

#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/scenarios/scenario.hpp"
#include "options.hpp"
#include "output.hpp"
#include "parameter_options.hpp"
#include "run_subcommands.hpp"

namespace mjarm::cli {

namespace {

void print_outcome(const Scenario& scenario, const TrialOutcome& o) {
  std::cout << scenario.name() << ": " << o.verdict << (o.success ? "" : " (failed)") << " — "
            << (o.message.empty() ? std::string("at t = " + fixed(o.end_time, 3) + " s")
                                  : o.message)
            << '\n';
  Table table({{"metric", Table::Align::left}, {"value"}, {"unit", Table::Align::left}});
  for (std::size_t i = 0; i < scenario.metrics().size(); ++i) {
    const MetricInfo& m = scenario.metrics()[i];
    table.add_row({m.name, general(o.metrics.at(i), 4), m.unit});
  }
  table.print(std::cout, 2);
  if (!o.recording.empty()) std::cout << "recording: " << o.recording.string() << '\n';
  for (const auto& video : o.videos) std::cout << "video: " << video.string() << '\n';
  if (!o.recording_error.empty()) std::cout << "recording error: " << o.recording_error << '\n';
  if (!o.video_error.empty()) std::cout << "video error: " << o.video_error << '\n';
}

}  // namespace

Command add_scenario_subcommand(CLI::App& run, const Scenario& scenario) {
  struct Options {
    std::string record;
    VideoCli video;
    bool json = false;
    std::unique_ptr<ParameterOptions> parameters;
  };
  auto o = std::make_shared<Options>();
  CLI::App* app = run.add_subcommand(std::string(scenario.name()),
                                     std::string(scenario.doc()) + " (docs/scenarios.md)");
  app->allow_extras();
  app->add_option("--record", o->record, "record state, task and events into DIR");
  add_video_options(*app, o->video, "the run",
                    "video camera: " + std::string(scenario.camera()) + " (default: the first)");
  add_json_flag(*app, o->json);
  o->parameters = std::make_unique<ParameterOptions>(*app, scenario, std::set<std::string>{});
  return {app, [o, app, &scenario] {
            refuse_extras(*app);
            ScenarioOutputs outputs;
            if (!o->record.empty()) {
              check_output_folder(o->record, "--record");
              outputs.record = o->record;
            }
            if (!o->video.path.empty()) {
              check_output_file(o->video.path, "--video");
              const PixelSize size = parse_pixel_size(o->video.size);
              outputs.video = o->video.path;
              outputs.width = size.width;
              outputs.height = size.height;
              outputs.fps = o->video.fps;
              if (!o->video.camera.empty()) outputs.cameras = {o->video.camera};
            }
            const Json values = o->parameters->values();
            try {
              scenario.resolve(values);  // a refused value is a usage error, before any work
            } catch (const Error& e) {
              throw UsageError(e.what());
            }
            const InterruptGuard interrupts;
            const TrialOutcome outcome = scenario.run(values, outputs);
            if (o->json)
              print_json(outcome_json(scenario, outcome));
            else
              print_outcome(scenario, outcome);
            if (outcome.status == RunStatus::interrupted)
              throw InterruptedError(std::string(scenario.name()) + " was interrupted at t = " +
                                         fixed(outcome.end_time, 3) + " s",
                                     interrupt_signal());
          }};
}

}  // namespace mjarm::cli
