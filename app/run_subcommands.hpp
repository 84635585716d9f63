// What the subcommands of `mjarm run` share (cmd_run.cpp): the video bound, the refusal of
// another scenario's options, and the options that set a simulation.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "commands.hpp"
#include "mjarm/scenarios/scenario.hpp"

namespace mjarm::cli {

/// Most frames `run --video` may film after the approach (--fps × --settle-time): 5 minutes of
/// video at 30 fps, about 20 minutes of software rendering at 640x480.
inline constexpr double kMaxVideoFrames = 9000.0;

/// Refuses what a scenario's subcommand did not take (it allows extras so as to say this): an
/// option of another scenario or a misspelt one, with the closest of its own.
/// @throws UsageError when @p app has arguments left
void refuse_extras(const CLI::App& app);

/// The options of the shelf pick and the planned motion that set the simulation.
struct SimulationCli {
  std::uint64_t seed = 1;
  double control_period = 0.0;
  double max_acceleration = 1e6;
  double settle_time = 1.0;
};

/// Adds --seed, --control-period, --max-acceleration and --settle-time.
void add_simulation_options(CLI::App& app, SimulationCli& o, const std::string& seed_help,
                            const std::string& settle_help);

/// `mjarm run shelf-pick` (cmd_run_shelf_pick.cpp).
Command add_shelf_pick_subcommand(CLI::App& run);

/// `mjarm run SCENARIO` for a scenario of the registry without a subcommand of its own: its
/// parameters, --record, --video and --json (cmd_run_scenario.cpp).
Command add_scenario_subcommand(CLI::App& run, const Scenario& scenario);

}  // namespace mjarm::cli
