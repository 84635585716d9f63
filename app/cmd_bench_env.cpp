// `mjarm bench env [--task T] [--action-space S] [--steps N] [--rounds R] [--envs E]
// [--batch-steps B] [--threads T] [--seed S] [--json]`: what an environment step costs beyond its
// physics, and how a vectorized batch scales (docs/env.md, protocol in env/env_benchmark.hpp).

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "field_options.hpp"
#include "mjarm/env/env_benchmark.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/interrupt.hpp"
#include "output.hpp"

namespace mjarm::cli {

Command add_bench_env_subcommand(CLI::App& bench) {
  struct Options {
    std::string task = "reach";
    std::string action_space = "ee_pose_deltas";
    int steps = 5000;
    int warmup = 100;
    int rounds = 3;
    int envs = 8;
    int batch_steps = 250;
    int threads = 2;
    std::uint64_t seed = 1;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "env",
      "learning environment: the cost of an environment step beyond the bare mj_step calls of "
      "its physics (thread CPU time, same physics replayed), and the steps per second of a "
      "vectorized batch on 1 thread and on --threads (wall clock with the load average, and "
      "from the threads' CPU clocks)");
  app->add_option("--task", options->task, "environment task")
      ->check(CLI::IsMember(env_task_names()));
  app->add_option("--action-space", options->action_space, "action space")
      ->check(name_of<ActionSpace>("action space"));
  app->add_option("--steps", options->steps, "timed environment steps per round")
      ->check(count_in(1, 1000000));
  app->add_option("--warmup", options->warmup, "untimed steps before each timed run")
      ->check(count_in(0, 100000));
  app->add_option("--rounds", options->rounds, "rounds of each measurement (median / best)")
      ->check(count_in(1, 100));
  app->add_option("--envs", options->envs, "environments of the vectorized batch")
      ->check(count_in(1, 4096));
  app->add_option("--batch-steps", options->batch_steps, "timed batch steps per vectorized run")
      ->check(count_in(1, 100000));
  app->add_option("--threads", options->threads, "thread count compared with one")
      ->check(count_in(1, 256));
  app->add_option("--seed", options->seed, "seed of the actions and environments")
      ->check(non_negative_integer());
  add_json_flag(*app, options->json);

  return {
      app, [options] {
        EnvBenchmarkOptions o;
        o.task = options->task;
        o.action_space = action_space(options->action_space);
        o.steps = options->steps;
        o.warmup = options->warmup;
        o.rounds = options->rounds;
        o.envs = options->envs;
        o.batch_steps = options->batch_steps;
        o.max_threads = options->threads;
        o.seed = options->seed;
        // counted in environment steps: a run of a million steps moves the line too
        Progress progress("benchmarking (environment steps)", 1);
        o.progress = [&progress](std::int64_t done, std::int64_t total) {
          progress.update(done, total);
        };
        const InterruptGuard interrupts;  // Ctrl-C: the figures of the steps done
        o.stop = [] { return interrupt_requested(); };
        const EnvBenchmarkResult r = run_env_benchmark(o);
        progress.finish();
        const bool stopped = r.status == EnvBenchmarkStatus::interrupted;
        if (options->json) {
          Json rounds = Json::array(), runs_json = Json::array();
          for (const EnvOverheadRound& x : r.rounds) rounds.push_back(fields_to_json(x));
          for (const VectorRun& v : r.vector_runs) runs_json.push_back(fields_to_json(v));
          print_json({{"status", to_string(r.status)},
                      {"task", r.task},
                      {"model", r.model},
                      {"action_space", to_string(r.action_space)},
                      {"control_period_s", r.control_period},
                      {"physics_steps_per_step", r.physics_steps_per_step},
                      {"steps", r.steps},
                      {"env_us_per_step", r.env_us_per_step},
                      {"bare_us_per_step", r.bare_us_per_step},
                      {"overhead", r.overhead},
                      {"replay_identical", r.replay_identical},
                      {"rounds", rounds},
                      {"envs", r.envs},
                      {"batch_steps", r.batch_steps},
                      {"vector_runs", runs_json},
                      {"speedup_wall", r.speedup},
                      {"speedup_cpu", r.cpu_speedup},
                      {"cpu_cost_ratio", r.cpu_cost_ratio},
                      {"threads_identical", r.threads_identical},
                      {"load_before", r.load_before},
                      {"load_after", r.load_after},
                      {"hardware_threads", r.hardware_threads}});
        } else {
          // rounds cut short by an interrupt say how many steps they took
          std::int64_t steps_done = 0;
          bool whole = true;
          for (const EnvOverheadRound& x : r.rounds) {
            steps_done += x.steps;
            whole = whole && x.steps == r.steps;
          }
          const std::string rounds_text =
              whole ? std::to_string(r.rounds.size()) + " × " + std::to_string(r.steps) + " steps"
                    : std::to_string(r.rounds.size()) +
                          (r.rounds.size() == 1 ? " round, " : " rounds, ") +
                          std::to_string(steps_done) + " steps, the last cut short";
          const bool timed = !r.rounds.empty();
          print_fields(
              std::cout,
              {{"task", r.task + " on " + r.model + ", " + to_string(r.action_space) + ", " +
                            std::to_string(r.physics_steps_per_step) + " physics steps of " +
                            compact(r.control_period / r.physics_steps_per_step) + " s per step"},
               {"environment step", timed ? fixed(r.env_us_per_step, 1) +
                                                " µs (thread CPU, median of " + rounds_text + ")"
                                          : "— (interrupted before the first timed step)"},
               {"bare mj_step ×" + std::to_string(r.physics_steps_per_step),
                timed ? fixed(r.bare_us_per_step, 1) + " µs (same physics replayed)" : "—"},
               {"overhead", timed ? fixed(100.0 * r.overhead, 1) + " % (target ≤ 10 %)" : "—"},
               {"replay identical", timed ? (r.replay_identical ? "yes" : "no") : "—"}});
          if (!r.vector_runs.empty()) {
            // a ratio needs a run of each thread count: an interrupt may leave it unmeasured
            const auto measured = [](double v, int decimals, const std::string& unit) {
              return v > 0.0 ? fixed(v, decimals) + unit : std::string("— (not measured)");
            };
            std::cout << '\n';
            Table table({{"run", Table::Align::left},
                         {"threads"},
                         {"batch steps"},
                         {"steps/s (wall)"},
                         {"process CPU [s]"},
                         {"work CPU [s]"},
                         {"critical CPU [s]"}});
            for (std::size_t k = 0; k < r.vector_runs.size(); ++k) {
              const VectorRun& v = r.vector_runs[k];
              table.add_row({std::to_string(k + 1), std::to_string(v.threads),
                             std::to_string(v.batch_steps), fixed(v.steps_per_second, 0),
                             fixed(v.cpu_s, 3), fixed(v.work_cpu_s, 3),
                             fixed(v.critical_cpu_s, 3)});
            }
            table.print(std::cout);
            std::cout << '\n';
            print_fields(
                std::cout,
                {{"batch", std::to_string(r.envs) + " environments × " +
                               std::to_string(r.batch_steps) + " steps per run"},
                 {"speedup (CPU clocks)", measured(r.cpu_speedup, 2, "× (target ≥ 1.8×)")},
                 {"CPU per step, threaded / single", measured(r.cpu_cost_ratio, 3, "")},
                 {"speedup (wall, best runs)", measured(r.speedup, 2, "×")},
                 {"load average", fixed(r.load_before[0], 2) + " before, " +
                                      fixed(r.load_after[0], 2) + " after, " +
                                      std::to_string(r.hardware_threads) + " hardware threads"},
                 {"same arrays on every thread count", r.threads_identical ? "yes"
                                                       : stopped ? "not compared (interrupted)"
                                                                 : "no"}});
          }
        }
        if (stopped) {
          std::int64_t steps = 0, batch_steps = 0;
          for (const EnvOverheadRound& x : r.rounds) steps += x.steps;
          for (const VectorRun& v : r.vector_runs) batch_steps += v.batch_steps;
          throw InterruptedError("bench env: interrupted after " + std::to_string(steps) +
                                     " timed steps in " + std::to_string(r.rounds.size()) + " of " +
                                     std::to_string(options->rounds) + " overhead rounds (" +
                                     std::to_string(r.steps) + " steps each) and " +
                                     std::to_string(batch_steps) + " batch steps in " +
                                     std::to_string(r.vector_runs.size()) + " vectorized runs",
                                 interrupt_signal());
        }
      }};
}

}  // namespace mjarm::cli
