#pragma once
/// @file
/// The `mjarm` subcommands. Each `add_*_command` registers its options on the root parser and
/// returns the action to run once parsing succeeded; the printing pieces below are shared with
/// `demo`, which strings several commands together.

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/model/robot.hpp"
#include "options.hpp"
#include "output.hpp"

namespace mjarm::cli {

/// A registered subcommand and the action that runs it (throws on failure).
struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
};

Command add_models_command(CLI::App& root);         ///< `mjarm models` (cmd_info.cpp)
Command add_info_command(CLI::App& root);           ///< `mjarm info MODEL`
Command add_fk_command(CLI::App& root);             ///< `mjarm fk MODEL --site S --q …`
Command add_workspace_command(CLI::App& root);      ///< `mjarm workspace MODEL …`
Command add_singularities_command(CLI::App& root);  ///< `mjarm singularities MODEL …`
Command add_demo_command(CLI::App& root);           ///< `mjarm demo`
Command add_ik_command(CLI::App& root);             ///< `mjarm ik MODEL …` (cmd_ik.cpp)
Command add_bench_command(CLI::App& root);          ///< `mjarm bench ik MODEL …` (cmd_bench.cpp)
/// `mjarm bench otg …` on @p bench (cmd_bench_otg.cpp); @p allocations counts heap allocations.
Command add_bench_otg_subcommand(CLI::App& bench, std::function<std::uint64_t()> allocations);
Command add_render_command(CLI::App& root);  ///< `mjarm render MODEL --out P` (cmd_render.cpp)
Command add_view_command(CLI::App& root);    ///< `mjarm view [MODEL]` (cmd_view.cpp)
Command add_run_command(CLI::App& root);     ///< `mjarm run shelf-pick …` (cmd_run.cpp)
Command add_plot_command(CLI::App& root);    ///< `mjarm plot RECORDING …` (cmd_plot.cpp)

/// Everything `info` reports about a model, as JSON.
Json model_json(const Robot& robot);
/// A short summary of a model: name, source, sizes, joints table, actuators table.
void print_model_summary(std::ostream& os, const Robot& robot);

/// The pose (and, when @p with_jacobian, the world-aligned Jacobian) of @p kin's frame at the
/// last `update()`, as JSON; @p config says where q came from.
Json pose_json(const ChainKinematics& kin, const Configuration& config, bool with_jacobian);
/// The same as tables: configuration, position, rotation, quaternion, roll-pitch-yaw.
void print_pose(std::ostream& os, const ChainKinematics& kin, const Configuration& config,
                bool with_jacobian);

/// Runs `sample_workspace` with a progress line on a terminal; the manipulability measured is
/// that of the position block. @p keep_points stores every sample (for CSV export).
/// @throws Error when @p samples is 0.
WorkspaceResult run_workspace(const Chain& chain, std::size_t samples, std::uint64_t seed,
                              bool keep_points);
/// A workspace result as JSON (without the points).
Json workspace_json(const Chain& chain, const WorkspaceResult& result);
/// A workspace result as tables: bounding box, centroid, reach, manipulability, rate.
void print_workspace(std::ostream& os, const Chain& chain, const WorkspaceResult& result);

}  // namespace mjarm::cli
