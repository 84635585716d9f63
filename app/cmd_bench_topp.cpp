// `mjarm bench topp [--paths N] [--dofs D] [--seed S] [--grid N] [--reference-paths K]
// [--reference-start topp|own] [--refinement-paths M] [--jerk-paths J] [--clock wall|cpu]
// [--cases-out FILE] [--json]`: the validation protocol and timing of the time-optimal path
// parameterization (docs/trajectory.md "Time-optimal path parameterization").

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"
#include "mjarm/trajectory/path/validation/topp_protocol.hpp"
#include "output.hpp"

namespace mjarm::cli {

Command add_bench_topp_subcommand(CLI::App& bench, std::function<std::uint64_t()> allocations) {
  struct Options {
    int paths = 10000;
    int dofs = 7;
    std::uint64_t seed = 0;
    int grid = 100;
    int reference_paths = 10000;
    std::string reference_start = "topp";
    int refinement_paths = 1000;
    int jerk_paths = 10000;
    std::string clock = "wall";
    std::string cases_out;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "topp",
      "time-optimal path parameterization (TOPP-RA): N random n-DoF paths through 5-8 waypoints "
      "under random velocity and acceleration limits — failures, the worst limit excess at the "
      "grid points and at the analytic extrema between them, the duration against an "
      "independent minimum of the same grid problem (Newton steps on dense QPs), the change on a "
      "4x finer grid, and the median/p95 calculation time");
  app->add_option("--paths", options->paths, "random paths N")->check(count_in(1, 10000000));
  app->add_option("--dofs", options->dofs, "joints per path")->check(CLI::Range(1, 64));
  app->add_option("--seed", options->seed, "seed of the paths")->check(non_negative_integer());
  app->add_option("--grid", options->grid, "grid steps of the path parameter")
      ->check(count_in(2, 100000));
  app->add_option("--reference-paths", options->reference_paths,
                  "the first K paths also solved by the reference (a few ms each)")
      ->check(count_in(0, 10000000));
  app->add_option("--reference-start", options->reference_start,
                  "topp: the reference's Newton steps start at TOPP-RA's profile (fewer steps); "
                  "own: at its own feasible point (one more QP)")
      ->check(CLI::IsMember({"topp", "own"}));
  app->add_option("--refinement-paths", options->refinement_paths,
                  "the first M paths also timed on a grid 4x finer")
      ->check(count_in(0, 10000000));
  app->add_option("--jerk-paths", options->jerk_paths,
                  "the first J paths also run through the jerk-limited waypoint variant")
      ->check(count_in(0, 10000000));
  app->add_option("--clock", options->clock,
                  "wall: steady clock; cpu: the thread's CPU time (for a shared machine)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  app->add_option("--cases-out", options->cases_out,
                  "write every path (waypoints, limits, grid, duration, calculation time) as one "
                  "JSON line to FILE, for a peer comparison (bench/peers/toppra_side_by_side.py)");
  add_json_flag(*app, options->json);

  return {
      app, [options, allocations] {
        ToppValidationOptions protocol;
        protocol.paths = options->paths;
        protocol.dofs = options->dofs;
        protocol.seed = options->seed;
        protocol.grid_intervals = options->grid;
        protocol.reference_paths = options->reference_paths;
        protocol.reference_from_topp = options->reference_start == "topp";
        protocol.refinement_paths = options->refinement_paths;
        protocol.jerk_paths = options->jerk_paths;
        protocol.thread_cpu_clock = options->clock == "cpu";
        protocol.allocation_count = allocations;
        // the cases file is complete or not written at all (docs/cli.md, "Files written")
        std::unique_ptr<FileWriter> cases;
        if (!options->cases_out.empty()) {
          cases = std::make_unique<FileWriter>(options->cases_out, FileWriter::Mode::replace,
                                               "TOPP cases");
          protocol.each_path = [&cases](int k, const ToppCase& c, const TimeOptimalPath& topp,
                                        double us) {
            Json waypoints = Json::array();
            for (const Eigen::VectorXd& w : c.waypoints) waypoints.push_back(vector_json(w));
            cases->write(Json{{"path", k},
                              {"waypoints", std::move(waypoints)},
                              {"max_velocity", vector_json(c.max_velocity)},
                              {"max_acceleration", vector_json(c.max_acceleration)},
                              {"grid_intervals", topp.grid().size() - 1},
                              {"status", to_string(topp.status())},
                              {"duration", topp.duration()},
                              {"calculation_us", us}}
                             .dump() +
                         "\n");
          };
        }
        Progress progress("parameterizing", options->paths);
        protocol.progress = [&progress](int done, int) { progress.update(done); };
        const InterruptGuard interrupts;  // Ctrl-C: the figures of the paths done so far
        protocol.stop = [] { return interrupt_requested(); };
        const ToppValidationResult r = run_topp_validation(protocol);
        progress.finish();
        if (cases && !r.interrupted) cases->commit();
        const double samples = 51.0 * (r.paths - r.failures);
        const double per_sample = r.allocations_counted && samples > 0
                                      ? static_cast<double>(r.sampling_allocations) / samples
                                      : -1.0;
        if (options->json) {
          print_json({{"interrupted", r.interrupted},
                      {"paths", r.paths},
                      {"dofs", r.dofs},
                      {"seed", options->seed},
                      {"grid_intervals", r.grid_intervals},
                      {"failures", r.failures},
                      {"worst_grid_excess", r.worst_grid_excess},
                      {"worst_excess", r.worst_excess},
                      {"reference_paths", r.reference_paths},
                      {"reference_start", options->reference_start},
                      {"reference_failures", r.reference_failures},
                      {"worst_longer_than_reference", r.worst_longer},
                      {"mean_longer_than_reference", r.mean_longer},
                      {"paths_longer_than_reference_1e-6", r.longer_paths},
                      {"worst_shorter_than_reference", r.worst_shorter},
                      {"reference_mean_ms", r.reference_mean_ms},
                      {"reference_mean_newton_steps", r.reference_mean_newton},
                      {"refinement_paths", r.refinement_paths},
                      {"worst_refinement_change", r.worst_refinement_change},
                      {"jerk_paths", r.jerk_paths},
                      {"jerk_failures", r.jerk_failures},
                      {"jerk_worst_excess", r.jerk_worst_excess},
                      {"jerk_reduced_waypoints", r.jerk_reduced_waypoints},
                      {"jerk_stopped_waypoints", r.jerk_stopped_waypoints},
                      {"jerk_mean_over_topp", r.jerk_mean_over_topp},
                      {"jerk_mean_over_stops", r.jerk_mean_over_stops},
                      {"jerk_worst_over_stops", r.jerk_worst_over_stops},
                      {"clock", options->clock},
                      {"mean_us", r.mean_us},
                      {"median_us", r.median_us},
                      {"p95_us", r.p95_us},
                      {"max_us", r.max_us},
                      {"allocations_per_sample", per_sample},
                      {"first_failure", r.first_failure}});
        } else {
          print_fields(
              std::cout,
              {{"paths", std::to_string(r.paths) + " × " + std::to_string(r.dofs) +
                             " joints, seed " + std::to_string(options->seed) + ", grid " +
                             std::to_string(r.grid_intervals) + " steps"},
               {"failures", std::to_string(r.failures)},
               {"worst limit excess at the grid points",
                compact(r.worst_grid_excess) + " (relative; ≤ 0: within)"},
               {"worst limit excess anywhere",
                compact(r.worst_excess) + " (relative, at the analytic extrema)"},
               {"reference paths", std::to_string(r.reference_paths) + " (" +
                                       std::to_string(r.reference_failures) + " not solved, " +
                                       fixed(r.reference_mean_ms, 1) + " ms and " +
                                       fixed(r.reference_mean_newton, 1) + " Newton steps each)"},
               {"longer than the grid minimum",
                "worst " + compact(r.worst_longer) + ", mean " + compact(r.mean_longer) + ", " +
                    std::to_string(r.longer_paths) + " paths by > 1e-6 (relative)"},
               {"shorter than the grid minimum", compact(r.worst_shorter) + " (relative)"},
               {"change on a 4× finer grid", compact(r.worst_refinement_change) + " (worst of " +
                                                 std::to_string(r.refinement_paths) +
                                                 " paths, relative)"},
               {"jerk-limited through the waypoints",
                std::to_string(r.jerk_paths) + " paths (j = 10·a), " +
                    std::to_string(r.jerk_failures) + " failures, worst excess " +
                    compact(r.jerk_worst_excess) + ", " + std::to_string(r.jerk_reduced_waypoints) +
                    " waypoint velocities halved, " + std::to_string(r.jerk_stopped_waypoints) +
                    " waypoints given a stop"},
               {"jerk-limited duration",
                "mean " + fixed(r.jerk_mean_over_topp, 3) + "× the time-optimal path's, mean " +
                    fixed(r.jerk_mean_over_stops, 3) + " (worst " +
                    fixed(r.jerk_worst_over_stops, 3) + ")× stopping at every waypoint"},
               {"allocations per sample", per_sample < 0.0 ? "-" : compact(per_sample)}});
          if (!r.first_failure.empty()) std::cout << "first failure: " << r.first_failure << '\n';
          std::cout << '\n';
          Table table({{"parameterization (" + options->clock + " clock)", Table::Align::left},
                       {"mean [µs]"},
                       {"median [µs]"},
                       {"p95 [µs]"},
                       {"max [µs]"}});
          table.add_row(
              {std::to_string(r.dofs) + " joints, " + std::to_string(r.grid_intervals) + " steps",
               fixed(r.mean_us, 1), fixed(r.median_us, 1), fixed(r.p95_us, 1), fixed(r.max_us, 1)});
          table.print(std::cout);
        }
        if (r.interrupted)
          throw InterruptedError("bench topp: interrupted after " + std::to_string(r.paths) +
                                     " of " + std::to_string(options->paths) + " paths",
                                 interrupt_signal());
      }};
}

}  // namespace mjarm::cli
