// mjarm: command-line access to the library. Parse → call the library → print.

#include <mujoco/mujoco.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/mujoco_library.hpp"
#include "mjarm/version.hpp"
#include "output.hpp"

namespace {

int fail(const std::string& message, int code, bool hint) {
  std::cerr << "mjarm: error: " << message << '\n';
  if (hint) std::cerr << "Run with --help for more information.\n";
  return code;
}

// a full disk or a closed pipe must not look like success: @p code, or 1 when stdout failed
int flushed(int code) {
  std::cout.flush();
  if (!std::cout && code == 0) return fail("cannot write to standard output", 1, false);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mjarm::cli;
  // a MuJoCo library other than the one mjarm was compiled for is refused before anything runs
  try {
    mjarm::check_mujoco_library();
  } catch (const mjarm::Error& e) {
    return fail(e.what(), 1, false);
  }
  CLI::App app(
      "mjarm: robot arms on MuJoCo — inspect models, forward kinematics, workspace and "
      "singularity analysis.",
      "mjarm");
  app.footer(
      "Exit codes: 0 success, 1 the command failed, 2 the command line is wrong.\n"
      "Run `mjarm COMMAND --help` for the options of one command.");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("mjarm ") + mjarm::version() + " (MuJoCo " +
                                        mj_versionString() + ")");

  // every command, in the order `mjarm --help` lists them
  struct Entry {
    const char* name;
    Command (*add)(CLI::App&);
  };
  static constexpr Entry kCommands[] = {
      {"models", add_models_command},
      {"info", add_info_command},
      {"fk", add_fk_command},
      {"workspace", add_workspace_command},
      {"singularities", add_singularities_command},
      {"ik", add_ik_command},
      {"bench", add_bench_command},
      {"render", add_render_command},
      {"view", add_view_command},
      {"replay", add_replay_command},
      {"bimanual", add_bimanual_command},
      {"run", add_run_command},
      {"plot", add_plot_command},
      {"replay-html", add_replay_html_command},
      {"traj", add_traj_command},
      {"plan", add_plan_command},
      {"env", add_env_command},
      {"soak", add_soak_command},
      {"sweep", add_sweep_command},
      {"demo", add_demo_command},
  };
  // `mjarm COMMAND …` registers that command alone: the options of all of them (about 40 ms of a
  // sanitized build's start, `run`'s scenario parameters most) are built only for `mjarm`,
  // `mjarm --help` and `--version`, which list or need them all
  const bool named = argc > 1 && argv[1][0] != '-';
  std::vector<Command> commands;
  std::vector<std::string> names;
  for (const Entry& entry : kCommands) {
    names.push_back(entry.name);
    if (named && names.back() != argv[1]) continue;
    commands.push_back(entry.add(app));
    if (commands.back().app->get_name() != entry.name)
      return fail(std::string("internal: command '") + commands.back().app->get_name() +
                      "' registered as '" + entry.name + "'",
                  1, false);
  }
  add_model_size_option(app);

  // name an unknown command instead of CLI11's generic "a subcommand is required"
  if (named && commands.empty())
    return fail(std::string("unknown command '") + argv[1] + "'; commands: " + join(names), 2,
                true);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return flushed(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return flushed(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return flushed(app.exit(e));
  } catch (const CLI::ParseError& e) {
    if (argc == 1) {
      // bare `mjarm`: show what it can do
      std::cerr << app.help();
      return 2;
    }
    return fail(e.what(), 2, true);
  }

  try {
    for (const auto& command : commands) {
      if (command.app->parsed()) command.run();
    }
  } catch (const UsageError& e) {
    return fail(e.what(), 2, true);
  } catch (const InterruptedError& e) {
    std::cout.flush();
    return fail(e.what(), e.exit_code(), false);
  } catch (const mjarm::Error& e) {
    return fail(e.what(), 1, false);
  } catch (const std::exception& e) {
    return fail(e.what(), 1, false);
  }
  return flushed(0);
}
