// `mjarm bench ik MODEL --site S --samples N --timeout-ms T --seed K [--clock wall|cpu]`: the
// TRAC-IK protocol.

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/ik/ik_benchmark.hpp"
#include "output.hpp"

namespace mjarm::cli {
namespace {

Json result_json(const IkBenchmarkResult& r) {
  return {{"solver", r.solver},
          {"seed_mode", to_string(r.seed_mode)},
          {"timeout_ms", r.timeout_ms},
          {"samples", r.samples},
          {"successes", r.successes},
          {"success_rate", r.success_rate},
          {"mean_time_ms", r.mean_time_ms},
          {"median_time_ms", r.median_time_ms},
          {"p99_time_ms", r.p99_time_ms},
          {"max_time_ms", r.max_time_ms},
          {"mean_iterations", r.mean_iterations}};
}

}  // namespace

Command add_bench_command(CLI::App& root) {
  struct Options {
    std::string model;
    std::string site;
    int samples = 10000;
    double timeout_ms = 5.0;
    std::uint64_t seed = 0;
    std::string clock = "wall";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* bench =
      root.add_subcommand("bench", "benchmarks of the library (see `mjarm bench ik --help`)");
  bench->require_subcommand(1);
  CLI::App* app = bench->add_subcommand(
      "ik",
      "TRAC-IK protocol: N random configurations inside the limits → forward kinematics → solve "
      "that 6-D pose from the mid-range configuration, then again from random configurations; "
      "success = x, y, z, roll, pitch, yaw each within 1e-5 and joints within limits");
  add_model_argument(*app, options->model)->required();
  add_site_option(*app, options->site);
  app->add_option("--samples", options->samples, "number of random targets N")
      ->check(CLI::Range(1, 10000000));
  app->add_option("--timeout-ms", options->timeout_ms, "time budget per solve [ms]")
      ->check(CLI::PositiveNumber);
  app->add_option("--seed", options->seed, "seed of the targets (and of the random starts)")->check(non_negative_integer());
  app->add_option("--clock", options->clock,
                  "wall: the published protocol (steady clock); cpu: the solving thread's CPU "
                  "time, for a shared machine (a solve over budget counts as failed)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  add_json_flag(*app, options->json);

  return {bench, [options, app] {
            if (!app->parsed()) return;
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            std::vector<IkBenchmarkResult> results;
            for (const IkSeedMode mode : {IkSeedMode::mid_range, IkSeedMode::random}) {
              IkBenchmarkOptions protocol;
              protocol.samples = options->samples;
              protocol.seed = options->seed;
              protocol.seed_mode = mode;
              protocol.timeout = std::chrono::duration<double, std::milli>(options->timeout_ms);
              protocol.clock = options->clock == "cpu" ? IkBenchmarkClock::thread_cpu
                                                       : IkBenchmarkClock::wall;
              Progress progress(std::string("solving (") + to_string(mode) + " seeds)",
                                options->samples);
              protocol.progress = [&progress](int done, int) { progress.update(done); };
              results.push_back(run_ik_benchmark(chain, protocol));
              progress.finish();
            }
            if (options->json) {
              Json runs = Json::array();
              for (const auto& r : results) runs.push_back(result_json(r));
              return print_json({{"model", robot.name()},
                                 {"frame", chain.frame().name},
                                 {"joints", chain.size()},
                                 {"samples", options->samples},
                                 {"timeout_ms", options->timeout_ms},
                                 {"seed", options->seed},
                                 {"clock", to_string(results.front().clock)},
                                 {"runs", runs}});
            }
            print_fields(std::cout, {{"model", robot.name()},
                                     {"frame", chain.frame().name},
                                     {"solver", results.front().solver},
                                     {"samples", std::to_string(options->samples)},
                                     {"timeout [ms]", compact(options->timeout_ms)},
                                     {"seed", std::to_string(options->seed)},
                                     {"clock", to_string(results.front().clock)}});
            std::cout << '\n';
            Table table({{"start", Table::Align::left},
                         {"success [%]"},
                         {"mean [ms]"},
                         {"median [ms]"},
                         {"p99 [ms]"},
                         {"max [ms]"},
                         {"iterations"}});
            for (const auto& r : results) {
              table.add_row({to_string(r.seed_mode), fixed(100.0 * r.success_rate, 2),
                             fixed(r.mean_time_ms, 4), fixed(r.median_time_ms, 4),
                             fixed(r.p99_time_ms, 4), fixed(r.max_time_ms, 3),
                             fixed(r.mean_iterations, 1)});
            }
            table.print(std::cout);
          }};
}

}  // namespace mjarm::cli
