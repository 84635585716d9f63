// `mjarm bench ompl [--pairs N] [--seed S] [--planner NAME] [--budget S] [--checker-states K]
// [--json]`: the shelf benchmark of the OMPL planner (planning/ompl_benchmark.hpp).

#include <iostream>
#include <map>
#include <memory>

#include "commands.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/planning/ompl_benchmark.hpp"
#include "output.hpp"

namespace mjarm::cli {

Command add_bench_ompl_subcommand(CLI::App& bench) {
  struct Options {
    int pairs = 100;
    std::uint64_t seed = 1;
    std::string planner = "rrtconnect";
    double budget = 5.0;
    int checker_states = 20000;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "ompl",
      "the OMPL planner on the shelf benchmark: the panda between the cells of a three-level "
      "shelf with clutter, seeded start/goal pairs; success rate, planning time, path length, "
      "checks per plan, and the cost of one validity check against mj_forward");
  app->add_option("--pairs", options->pairs, "start/goal pairs planned")
      ->check(count_in(1, 100000));
  app->add_option("--seed", options->seed, "seed of the pairs and of the plans");
  app->add_option("--planner", options->planner, "rrtconnect, prm, rrtstar or bitstar");
  app->add_option("--budget", options->budget, "time budget of each plan [s]")
      ->check(number_in(0.001, 3600.0));
  app->add_option("--checker-states", options->checker_states,
                  "random states timed for the cost per check")
      ->check(count_in(1, 10000000));
  add_json_flag(*app, options->json);
  return {
      app, [options] {
        OmplBenchmarkOptions protocol;
        protocol.pairs = options->pairs;
        protocol.seed = options->seed;
        protocol.planner = parse_enum<OmplPlannerType>(options->planner, "planner");
        protocol.time_budget = options->budget;
        protocol.checker_states = options->checker_states;
        check(protocol);
        Progress progress("planning", options->pairs);
        protocol.progress = [&progress](int done, int) { progress.update(done); };
        const InterruptGuard interrupts;
        protocol.stop = [] { return interrupt_requested(); };
        const OmplBenchmarkResult r = run_ompl_benchmark(protocol);
        progress.finish();
        const auto stopped = [&] {
          if (!r.interrupted) return;
          throw InterruptedError("bench ompl: interrupted after " + std::to_string(r.pairs) +
                                     " of " + std::to_string(options->pairs) + " pairs",
                                 interrupt_signal());
        };
        std::map<std::string, int> statuses;
        for (const OmplStatus s : r.statuses) ++statuses[to_string(s)];
        if (options->json) {
          Json counts = Json::object();
          for (const auto& [name, count] : statuses) counts[name] = count;
          print_json({{"interrupted", r.interrupted},
                      {"scene", "panda_shelf"},
                      {"planner", options->planner},
                      {"seed", options->seed},
                      {"budget_s", options->budget},
                      {"pairs", r.pairs},
                      {"successes", r.successes},
                      {"success_rate", r.success_rate},
                      {"time_median_s", r.time_median},
                      {"time_p95_s", r.time_p95},
                      {"length_median_rad", r.length_median},
                      {"checks_median", r.checks_median},
                      {"knots_median", r.knots_median},
                      {"duration_median_s", r.duration_median},
                      {"time_optimal", r.time_optimal},
                      {"time_optimal_median_s", r.time_optimal_median},
                      {"time_optimal_ratio_median", r.time_optimal_ratio_median},
                      {"time_optimal_ratio_max", r.time_optimal_ratio_max},
                      {"check_us", r.check_us},
                      {"forward_us", r.forward_us},
                      {"checker_states", options->checker_states},
                      {"collision_share", r.collision_share},
                      {"statuses", counts}});
          return stopped();
        }
        std::string status_text;
        for (const auto& [name, count] : statuses)
          status_text += (status_text.empty() ? "" : ", ") + name + " " + std::to_string(count);
        print_fields(std::cout,
                     {{"scene", "panda_shelf: 3 levels x 2 cells, 3 boxes per cell"},
                      {"planner", options->planner + ", budget " + compact(options->budget) +
                                      " s per plan, seed " + std::to_string(options->seed)},
                      {"pairs", std::to_string(r.pairs) + (r.interrupted ? " (interrupted)" : "")},
                      {"statuses", status_text}});
        std::cout << '\n';
        Table table({{"success [%]"},
                     {"time median [ms]"},
                     {"time p95 [ms]"},
                     {"length median [rad]"},
                     {"checks median"},
                     {"knots median"},
                     {"motion median [s]"}});
        table.add_row({fixed(100.0 * r.success_rate, 1), fixed(1e3 * r.time_median, 1),
                       fixed(1e3 * r.time_p95, 1), fixed(r.length_median, 2),
                       fixed(r.checks_median, 0), fixed(r.knots_median, 0),
                       fixed(r.duration_median, 2)});
        table.print(std::cout);
        std::cout << "time-optimal timing: " << r.time_optimal << " of " << r.successes
                  << " paths, median " << fixed(r.time_optimal_median, 2)
                  << " s; over the blended spline's duration median "
                  << fixed(r.time_optimal_ratio_median, 3) << ", largest "
                  << fixed(r.time_optimal_ratio_max, 3) << "\n\n";
        Table cost({{"per state", Table::Align::left}, {"[µs]"}});
        cost.add_row(
            {"validity check (mj_kinematics + mj_collision + filter)", fixed(r.check_us, 2)});
        cost.add_row({"mj_forward (its mj_collision included) + filter", fixed(r.forward_us, 2)});
        cost.print(std::cout);
        std::cout << "(" << options->checker_states << " random states, "
                  << fixed(100.0 * r.collision_share, 1) << " % in collision)\n";
        stopped();
      }};
}

}  // namespace mjarm::cli
