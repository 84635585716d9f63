#pragma once
/// @file
/// The `mjarm` subcommands. Each `add_*_command` registers its options on the root parser and
/// returns the action to run once parsing succeeded; the printing pieces below are shared with
/// `demo`, which strings several commands together.

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/planning/cartesian_path.hpp"
#include "mjarm/planning/waypoint_planner.hpp"
#include "mjarm/tasks/docking/docking.hpp"
#include "mjarm/tasks/pick_place/pick_place.hpp"
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
/// `mjarm bench otg-brake …` on @p bench (cmd_bench_otg_brake.cpp).
Command add_bench_otg_brake_subcommand(CLI::App& bench);
/// `mjarm bench topp …` on @p bench (cmd_bench_topp.cpp); @p allocations as above.
Command add_bench_topp_subcommand(CLI::App& bench, std::function<std::uint64_t()> allocations);
/// `mjarm bench traj …` on @p bench (cmd_bench_motion.cpp); @p allocations as above.
Command add_bench_traj_subcommand(CLI::App& bench, std::function<std::uint64_t()> allocations);
/// `mjarm bench plan …` on @p bench (cmd_bench_motion.cpp).
Command add_bench_plan_subcommand(CLI::App& bench);
/// `mjarm bench ompl …` on @p bench (cmd_bench_ompl.cpp).
Command add_bench_ompl_subcommand(CLI::App& bench);
/// `mjarm bench env …` on @p bench (cmd_bench_env.cpp).
Command add_bench_env_subcommand(CLI::App& bench);
/// `mjarm bench diffik …` on @p bench (cmd_bench_diffik.cpp).
Command add_bench_diffik_subcommand(CLI::App& bench);
/// `mjarm bench analytic-ik …` on @p bench (cmd_bench_analytic_ik.cpp).
Command add_bench_analytic_ik_subcommand(CLI::App& bench);
Command add_env_command(CLI::App& root);     ///< `mjarm env list|run …` (cmd_env.cpp)
Command add_render_command(CLI::App& root);  ///< `mjarm render MODEL --out P` (cmd_render.cpp)
Command add_view_command(CLI::App& root);    ///< `mjarm view [MODEL]` (cmd_view.cpp)
Command add_replay_command(CLI::App& root);  ///< `mjarm replay FILE` (cmd_teleop.cpp)
Command add_bimanual_command(CLI::App& root);  ///< `mjarm bimanual` (cmd_teleop.cpp)
Command add_run_command(CLI::App& root);     ///< `mjarm run shelf-pick …` (cmd_run.cpp)
Command add_plot_command(CLI::App& root);    ///< `mjarm plot RECORDING …` (cmd_plot.cpp)
/// `mjarm replay-html RECORDING -o FILE` (cmd_replay_html.cpp)
Command add_replay_html_command(CLI::App& root);
Command add_traj_command(CLI::App& root);    ///< `mjarm traj KIND …` (cmd_traj.cpp)
Command add_plan_command(CLI::App& root);    ///< `mjarm plan ROBOT --waypoints F` (cmd_plan.cpp)
Command add_soak_command(CLI::App& root);    ///< `mjarm soak [--minutes M]` (cmd_soak.cpp)
Command add_sweep_command(CLI::App& root);  ///< `mjarm sweep run FILE --out DIR …` (cmd_sweep.cpp)

/// What `mjarm plan` and `mjarm run plan` read from the command line.
struct PlanCliOptions {
  std::string model;
  std::string site;
  std::string waypoints;
  std::vector<double> q;
  std::string key;
  std::vector<double> max_velocity, max_acceleration, max_torque;
  double min_sigma = 0.02;
  std::uint64_t seed = 1;
  std::string planner = "waypoint";  ///< waypoint | ompl:NAME (--planner)
};
/// Registers --waypoints, --q, --key, the limit overrides, --min-sigma, --planner (and --seed when
/// @p with_seed; `run` has its own).
void add_plan_options(CLI::App& app, PlanCliOptions& options, bool with_seed);
/// A planned path with everything needed to print or run it.
struct PlannedPath {
  Robot robot;
  std::optional<Chain> chain;
  Configuration start;
  std::vector<Pose> poses;
  PlanResult result;
};
/// Loads the model (@p model when given, else options.model) and the waypoint file, and plans
/// (start: --q, --key, else keyframe 'home').
/// @throws UsageError for limit lists of the wrong length; Error for bad files or models.
PlannedPath plan_path(const PlanCliOptions& options, std::optional<Robot> model = std::nullopt);
/// The plan as JSON / as a table of per-waypoint checks.
Json plan_json(const PlannedPath& plan);
void print_plan(std::ostream& os, const PlannedPath& plan);
/// What `mjarm plan --cartesian` reads besides the plan's options (cmd_plan_cartesian.cpp).
struct CartesianCliOptions {
  bool on = false;             ///< --cartesian
  bool no_collisions = false;  ///< --no-collisions
  CartesianPathOptions path;   ///< --max-step, --max-rotation-step, --jump-*
};
/// Registers --cartesian and its options on `mjarm plan` (after the plan's own: --cartesian
/// excludes the options of a timed plan).
void add_cartesian_options(CLI::App& app, CartesianCliOptions& options);
/// Follows the waypoint file's straight lines, prints the result (--json: one document).
/// @throws Error when the path is not complete (after printing); UsageError for bad options.
void run_cartesian_plan(const PlanCliOptions& options, const CartesianCliOptions& cartesian,
                        bool json);
/// `mjarm run plan ROBOT --waypoints F --controller C [--scene S]` (cmd_run_plan.cpp).
/// @param scene a scene file whose world the robot is placed in (empty: none)
/// @param control_period, max_acceleration as `SimulationOptions` (0: one physics step)
void run_plan_scenario(const PlanCliOptions& options, const std::string& scene,
                       const std::string& controller, double settle_time, double control_period,
                       double max_acceleration, bool json);

/// What `mjarm run docking` reads from the command line besides the shared run options.
struct DockingCliOptions {
  bool sensorless = false;              ///< --sensorless: the observer instead of the F/T sensor
  bool friction = false;                ///< --friction: the joint-friction variant
  std::vector<double> offset;           ///< --offset DX DY [mm] DYAW [°] (empty: none)
  bool grid = false;                    ///< --grid: the 27 offsets
  bool gate = false;                    ///< --gate: the tracking gate
  bool map = false;                     ///< --map: the capture region (polar offsets)
  double map_step = 1.0;                ///< --map-step: its radial step [mm]
  double map_yaw_step = 5.0;            ///< --map-yaw-step: its yaw step [°]
  std::string reference = "two-phase";  ///< --reference
  double insertion_speed = 0.01;        ///< --insertion-speed [m/s]
  double preload = 5.0;                 ///< --preload [N]
  std::vector<double> stiffness;        ///< --stiffness (6 values; empty: the law's default)
  std::string plot;                     ///< --plot DIR
  int jobs = 0;                         ///< --jobs
  Json parameters = Json::object();  ///< the registry's parameters given (--criteria.max-force …)
};
/// Registers the docking options on `mjarm run` (cmd_run_docking.cpp).
void add_docking_options(CLI::App& app, DockingCliOptions& options);
/// `mjarm run docking --controller C …`: one run, `--grid` or `--gate`; a video of more than
/// @p max_video_frames frames is refused before the work.
void run_docking_scenario(const DockingCliOptions& options, const std::string& controller,
                          const DockingVideo& video, const std::string& record, bool json,
                          double max_video_frames);
/// `mjarm run docking --map`: the capture region per law over radial offsets 0–15 mm ×
/// 8 directions × yaw 0–25° from @p base (cmd_run_docking_map.cpp); the polar heat maps and the
/// table (docking_map.json) into options.plot when given.
void run_docking_map(const DockingCliOptions& options, const std::vector<DockingLaw>& laws,
                     const DockingOptions& base, bool json);
/// The options of `mjarm run` that every scenario shares.
struct RunCommonOptions {
  std::string robot;  ///< empty: the scenario's default
  std::uint64_t seed = 1;
  std::string record;
  double control_period = 0.0;
  double max_acceleration = 1e6;
  double settle_time = 1.0;
  std::string video;
  std::string size = "640x480";
  double fps = 30.0;
  bool json = false;
  bool html = false;      ///< --html given: the replay page of each recording
  std::string html_file;  ///< its FILE; empty: beside the recording
};
/// What `mjarm run pick-place` reads from the command line beyond the shared options.
struct PickPlaceCliOptions {
  PickPlaceOptions options;  ///< constants, criteria, classic edits
  std::string grasp = "weld";
  std::string mode = "position";
  std::uint64_t trials = 1;
  std::uint64_t threads = 0;
  std::vector<double> object, target, solref;
  double object_size = 0.0;
  std::vector<std::string> cameras;
  bool separate = false;
  Json parameters = Json::object();  ///< the registry's parameters given (--criteria.max-tilt …)
};
/// Registers the pick-place options on `run` (cmd_run_pick_place.cpp).
void add_pick_place_options(CLI::App& app, PickPlaceCliOptions& options);
/// `mjarm run pick-place …`: one trial, or a batch with its table.
void run_pick_place_scenario(PickPlaceCliOptions options, const RunCommonOptions& common);

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

/// Most workspace samples a command draws (`workspace`, `demo`): about 10 minutes of sampling
/// on the panda (0.2 million samples per second measured on a shared 2-core machine).
inline constexpr std::uint64_t kMaxWorkspaceSamples = 100'000'000;

/// Checks before the work that a workspace CSV of @p samples points can be written at @p out:
/// the points fit in memory (`kMaxKeptWorkspacePoints`), the file can be created and its
/// folder has room for it.
/// @throws UsageError naming what is wrong.
void check_workspace_csv(const std::string& out, std::size_t samples);

/// Runs `sample_workspace` with a progress line on a terminal; the manipulability measured is
/// that of the position block. @p keep_points stores every sample (for CSV export). Stops early
/// on Ctrl-C when the caller holds an `InterruptGuard` (the result then says `interrupted`).
/// @throws Error when @p samples is 0.
WorkspaceResult run_workspace(const Chain& chain, std::size_t samples, std::uint64_t seed,
                              bool keep_points);
/// A workspace result as JSON (without the points).
Json workspace_json(const Chain& chain, const WorkspaceResult& result);
/// A workspace result as tables: bounding box, centroid, reach, manipulability, rate.
void print_workspace(std::ostream& os, const Chain& chain, const WorkspaceResult& result);

}  // namespace mjarm::cli
