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

  std::vector<Command> commands;
  commands.push_back(add_models_command(app));
  commands.push_back(add_info_command(app));
  commands.push_back(add_fk_command(app));
  commands.push_back(add_workspace_command(app));
  commands.push_back(add_singularities_command(app));
  commands.push_back(add_ik_command(app));
  commands.push_back(add_bench_command(app));
  commands.push_back(add_render_command(app));
  commands.push_back(add_view_command(app));
  commands.push_back(add_replay_command(app));
  commands.push_back(add_bimanual_command(app));
  commands.push_back(add_run_command(app));
  commands.push_back(add_plot_command(app));
  commands.push_back(add_replay_html_command(app));
  commands.push_back(add_traj_command(app));
  commands.push_back(add_plan_command(app));
  commands.push_back(add_env_command(app));
  commands.push_back(add_soak_command(app));
  commands.push_back(add_sweep_command(app));
  commands.push_back(add_demo_command(app));
  add_model_size_option(app);

  // name an unknown command instead of CLI11's generic "a subcommand is required"
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    bool known = false;
    for (const auto& command : commands) {
      names.push_back(command.app->get_name());
      known = known || names.back() == argv[1];
    }
    if (!known)
      return fail(std::string("unknown command '") + argv[1] + "'; commands: " + join(names), 2,
                  true);
  }

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
