// `mjarm run SCENARIO`: runs a ready-made closed-loop scenario in simulation and prints its
// figures, optionally with a video of the run. One subcommand per scenario, each with its own
// options and every other parameter of the registry (parameter_options.hpp): shelf-pick
// (cmd_run_shelf_pick.cpp), pick-place (cmd_run_pick_place.cpp), docking (cmd_run_docking.cpp),
// plan (cmd_run_plan.cpp), every other scenario of the registry from its parameters alone
// (cmd_run_scenario.cpp); `mjarm run --list`.

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "output.hpp"
#include "parameter_options.hpp"
#include "run_replay.hpp"
#include "run_subcommands.hpp"

namespace mjarm::cli {

namespace {

/// `mjarm run --list`: every scenario of the registry with its parameters, metrics and verdicts.
void list_scenarios(bool json) {
  if (json) {
    Json doc = Json::array();
    for (const Scenario* s : scenarios()) doc.push_back(scenario_json(*s));
    print_json({{"scenarios", doc}});
    return;
  }
  Table table({{"scenario", Table::Align::left},
               {"parameters"},
               {"metrics"},
               {"what it does", Table::Align::left}});
  for (const Scenario* s : scenarios())
    table.add_row({std::string(s->name()), std::to_string(s->parameters().size()),
                   std::to_string(s->metrics().size()), std::string(s->doc())});
  table.print(std::cout, 0);
}

}  // namespace

void refuse_extras(const CLI::App& app) {
  const std::vector<std::string> extra = app.remaining();
  if (extra.empty()) return;
  const std::string where = "run " + app.get_name();
  const auto option = std::find_if(extra.begin(), extra.end(),
                                   [](const std::string& w) { return w.rfind("-", 0) == 0; });
  if (option == extra.end())
    throw UsageError(where + ": unexpected argument '" + extra.front() + "'");
  const std::string word = option->substr(0, option->find('='));
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options())
    for (const std::string& name : o->get_lnames()) names.push_back("--" + name);
  const std::vector<std::string> closest = closest_names(word, names);
  throw UsageError(where + ": unknown option '" + word + "'" +
                   (closest.empty() ? std::string() : "; closest: " + join(closest)) + " (mjarm " +
                   where + " --help lists them)");
}

void add_simulation_options(CLI::App& app, SimulationCli& o, const std::string& seed_help,
                            const std::string& settle_help) {
  app.add_option("--seed", o.seed, seed_help)->check(non_negative_integer())->capture_default_str();
  app.add_option("--control-period", o.control_period,
                 "control period [s], a whole multiple of the timestep (0: one physics step)")
      ->check(duration_at_most(1.0, "s", true))
      ->capture_default_str();
  app.add_option("--max-acceleration", o.max_acceleration,
                 "divergence bound on |joint acceleration| [rad/s²]")
      ->check(finite_number())
      ->capture_default_str();
  app.add_option("--settle-time", o.settle_time, settle_help)
      ->check(duration_at_most(60.0, "s"))
      ->capture_default_str();
}

namespace {

/// `mjarm run pick-place`: one trial, or a batch (--trials).
Command add_pick_place_subcommand(CLI::App& run) {
  struct Options {
    std::string robot, record, html;
    SimulationCli sim;
    VideoCli video;
    bool json = false;
    PickPlaceCliOptions pick_place;
    std::unique_ptr<ParameterOptions> parameters;
  };
  auto o = std::make_shared<Options>();
  const Scenario& scenario = find_scenario("pick-place");
  CLI::App* app =
      run.add_subcommand("pick-place", std::string(scenario.doc()) + " (docs/pick_place.md)");
  app->allow_extras();
  app->add_option("--robot", o->robot, "arm6 | panda_hand (default arm6)");
  add_simulation_options(*app, o->sim,
                         "seed: draws the object, its size, mass, friction and the "
                         "target (same seed, same trial)",
                         "DONE lasts this long before the trial is judged [s]");
  CLI::Option* record =
      app->add_option("--record", o->record,
                      "record state, task and events into DIR (with --trials: DIR/seed_K each)");
  CLI::Option* html = add_run_html_option(
      *app, record, o->html,
      "with --record: also write the replay page, one self-contained HTML file "
      "(docs/replay.md); without FILE beside the recording, DIR.html; with --trials one beside "
      "each trial's recording, DIR/seed_K.html (and no FILE)");
  add_video_options(*app, o->video, "the run");
  add_json_flag(*app, o->json);
  add_pick_place_options(*app, o->pick_place);
  // the parameters its older options set under other names
  o->parameters = std::make_unique<ParameterOptions>(
      *app, scenario,
      std::set<std::string>{"weld.time-constant", "weld.damping-ratio", "motion.approach-height",
                            "motion.descend-height", "motion.lift-height", "motion.move-height",
                            "motion.place-height", "motion.dwell-time", "motion.grip-time",
                            "motion.release-time", "motion.limits.max-velocity",
                            "motion.limits.max-acceleration", "motion.settle-time"});
  return {app, [o, app, html] {
            refuse_extras(*app);
            RunCommonOptions common;
            common.html = html->count() > 0;
            common.html_file = o->html;
            common.robot = o->robot;
            common.seed = o->sim.seed;
            common.record = o->record;
            common.control_period = o->sim.control_period;
            common.max_acceleration = o->sim.max_acceleration;
            common.settle_time = o->sim.settle_time;
            common.video = o->video.path;
            common.size = o->video.size;
            common.fps = o->video.fps;
            common.json = o->json;
            PickPlaceCliOptions pick_place = o->pick_place;
            pick_place.parameters = o->parameters->values();
            run_pick_place_scenario(pick_place, common);
          }};
}

/// `mjarm run docking`: one run, the 27-offset grid or the tracking gate.
Command add_docking_subcommand(CLI::App& run) {
  struct Options {
    std::string controller = "se3", record;
    VideoCli video;
    bool json = false;
    DockingCliOptions docking;
    std::unique_ptr<ParameterOptions> parameters;
  };
  auto o = std::make_shared<Options>();
  const Scenario& scenario = find_scenario("docking");
  CLI::App* app = run.add_subcommand("docking", std::string(scenario.doc()) + " (docs/docking.md)");
  app->allow_extras();
  app->add_option("--controller", o->controller, "cic | hqp-ac | se3 | all (all: --grid or --gate)")
      ->capture_default_str();
  app->add_option("--record", o->record, "record state, task and events into DIR");
  add_video_options(*app, o->video, "the run",
                    "video camera: a camera of the model, or 'follow' (the peg tip); default: a "
                    "free camera close to the socket");
  add_json_flag(*app, o->json);
  add_docking_options(*app, o->docking);
  // the parameters its older options set under other names (--controller, --friction,
  // --sensorless, --offset DX DY DYAW, --reference, --insertion-speed, --preload, --stiffness)
  o->parameters = std::make_unique<ParameterOptions>(
      *app, scenario,
      std::set<std::string>{"controller.law", "controller.source", "joint-friction", "offset.dx",
                            "offset.dy", "offset.dyaw", "motion.reference",
                            "motion.insertion-speed", "motion.preload", "controller.se3-stiffness",
                            "controller.cic-stiffness", "controller.hqp-stiffness"});
  return {app, [o, app] {
            refuse_extras(*app);
            if (!o->record.empty()) check_output_folder(o->record, "--record");
            DockingVideo video;
            if (!o->video.path.empty()) {
              check_output_file(o->video.path, "--video");
              const PixelSize size = parse_pixel_size(o->video.size);
              video.path = o->video.path;
              video.camera = o->video.camera;
              video.options.width = size.width;
              video.options.height = size.height;
              video.options.fps = o->video.fps;
            }
            DockingCliOptions docking = o->docking;
            docking.parameters = o->parameters->values();
            run_docking_scenario(docking, o->controller, video, o->record, o->json,
                                 kMaxVideoFrames);
          }};
}

/// `mjarm run plan ROBOT --waypoints FILE`: the planned motion tracked in simulation.
Command add_plan_subcommand(CLI::App& run) {
  struct Options {
    PlanCliOptions plan;
    std::string scene;
    std::string controller = "osc";
    SimulationCli sim;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* app = run.add_subcommand(
      "plan",
      "plan through Cartesian waypoints and track the plan in simulation (docs/planning.md)");
  app->allow_extras();
  app->add_option("ROBOT", o->plan.model, "the robot (planar2 | panda)");
  add_plan_options(*app, o->plan, false);
  app->get_option("--waypoints")->required(false);
  app->add_option("--controller", o->controller, "ct | osc | task-pd | accel")
      ->capture_default_str();
  app->add_option("--scene", o->scene,
                  "a scene file (docs/scene.md) whose world the robot is placed in, at the "
                  "origin: its fixtures, objects and other robots are obstacles to the plan, and "
                  "a contact while tracking fails the run");
  add_simulation_options(*app, o->sim, "seed of the IK branches and detours",
                         "time the final target is held after the plan ends [s]");
  add_json_flag(*app, o->json);
  return {app, [o, app] {
            refuse_extras(*app);
            if (o->plan.waypoints.empty()) throw UsageError("run plan needs --waypoints FILE");
            const InterruptGuard interrupts;
            o->plan.seed = o->sim.seed;
            run_plan_scenario(o->plan, o->scene, o->controller, o->sim.settle_time,
                              o->sim.control_period, o->sim.max_acceleration, o->json);
          }};
}

}  // namespace

Command add_run_command(CLI::App& root) {
  auto list = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  CLI::App* app = root.add_subcommand(
      "run",
      "run a closed-loop scenario in simulation and print its figures: mjarm run SCENARIO "
      "[options] (mjarm run --list names them); mjarm run SCENARIO --help for its "
      "options and parameters; mjarm run --list");
  app->require_subcommand(0, 1);
  app->allow_extras();  // an unknown scenario, named with the closest below
  app->add_flag("--list", *list,
                "list the scenarios of the registry (--json: each with its parameters, units, "
                "ranges, defaults, metrics and verdicts)");
  app->add_flag("--json", *json, "with --list: JSON");
  std::vector<Command> scenarios{add_shelf_pick_subcommand(*app), add_pick_place_subcommand(*app),
                                 add_docking_subcommand(*app), add_plan_subcommand(*app)};
  for (const Scenario* s : mjarm::scenarios())  // the others, from the registry alone
    if (std::none_of(scenarios.begin(), scenarios.end(),
                     [s](const Command& c) { return c.app->get_name() == s->name(); }))
      scenarios.push_back(add_scenario_subcommand(*app, *s));
  // --html [FILE] beside --record DIR: the recorded run's replay page (docs/replay.md), checked
  // before the run and written once it ended, from the recording as `mjarm replay-html DIR -o
  // FILE` would; without FILE beside the recording, DIR.html. The pick and place adds its own
  // (a batch's trials get one page each).
  for (Command& scenario : scenarios) {
    CLI::Option* record = scenario.app->get_option_no_throw("--record");
    if (record == nullptr || scenario.app->get_option_no_throw("--html") != nullptr) continue;
    auto html = std::make_shared<std::string>();
    CLI::Option* option = add_run_html_option(
        *scenario.app, record, *html,
        "with --record: also write the run's replay page, one self-contained HTML file "
        "(docs/replay.md); without FILE beside the recording, DIR.html");
    scenario.run = [run = scenario.run, html, option, record] {
      if (option->count() == 0) return run();
      const std::string recording = record->as<std::string>();
      const std::filesystem::path page =
          html->empty() ? replay_page_beside(recording) : std::filesystem::path(*html);
      check_run_replay("--html", page);
      run();
      write_run_replay(recording, page);
    };
  }
  return {app, [app, list, json, scenarios] {
            std::vector<std::string> names;
            for (const Command& scenario : scenarios) names.push_back(scenario.app->get_name());
            if (!app->remaining().empty())
              throw UsageError(unknown_name_message("scenario", app->remaining().front(), names));
            for (const Command& scenario : scenarios) {
              if (!scenario.app->parsed()) continue;
              if (*list) throw UsageError("--list lists every scenario: give no SCENARIO with it");
              return scenario.run();
            }
            if (*list) return list_scenarios(*json);
            throw UsageError("run needs a SCENARIO (" + join(names, " | ") +
                             ") or --list; mjarm run SCENARIO --help");
          }};
}

}  // namespace mjarm::cli
