// `mjarm bench otg [--cases N] [--dofs D] [--seed S] [--reference-cases K] [--structure-seeds M]
// [--clock wall|cpu] [--json]`: the validation protocol and timing of the jerk-limited online
// trajectory generator (docs/trajectory_otg.md).

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/trajectory/otg/validation/protocol.hpp"
#include "output.hpp"

namespace mjarm::cli {

Command add_bench_otg_subcommand(CLI::App& bench, std::function<std::uint64_t()> allocations) {
  struct Options {
    int cases = 100000;
    int dofs = 7;
    std::uint64_t seed = 0;
    int reference_cases = 100;
    int reference_steps = 100;
    int structure_seeds = 32;
    double brake_share = 0.1;
    std::string clock = "wall";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "otg",
      "jerk-limited online trajectory generation: N random n-DoF cases (position and velocity "
      "interface, some DoFs starting beyond their limits) — failures, worst limit violation at "
      "the analytic extrema, worst target error, mean/p99 calculation time, heap allocations per "
      "calculation; and time optimality of K one-DoF cases against two independent methods: a grid "
      "search and an exhaustive search over the switching structures");
  // bounds that run in minutes here, not days (10^7 cases: about an hour; a reference case of
  // 400 steps: about 2 s, of 2000: minutes); Ctrl-C keeps the figures of the cases done
  app->add_option("--cases", options->cases, "random n-DoF cases N")->check(count_in(1, 10000000));
  app->add_option("--dofs", options->dofs, "degrees of freedom per case")->check(CLI::Range(1, 64));
  app->add_option("--seed", options->seed, "seed of the cases")->check(non_negative_integer());
  app->add_option("--reference-cases", options->reference_cases,
                  "one-DoF cases checked against the grid reference (a QP per probed duration)")
      ->check(count_in(0, 100000));
  app->add_option("--reference-steps", options->reference_steps, "jerk steps of the reference grid")
      ->check(count_in(10, 400));
  app->add_option("--structure-seeds", options->structure_seeds,
                  "starting points per switching structure of the structure search on each "
                  "reference case (0: no structure search)")
      ->check(count_in(0, 256));
  app->add_option("--brake-share", options->brake_share,
                  "share of DoFs that start beyond their limits")
      ->check(CLI::Range(0.0, 1.0));
  app->add_option("--clock", options->clock,
                  "wall: steady clock; cpu: the thread's CPU time (for a shared machine)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  add_json_flag(*app, options->json);

  return {
      app, [options, allocations] {
        OtgValidationOptions protocol;
        protocol.cases = options->cases;
        protocol.dofs = options->dofs;
        protocol.seed = options->seed;
        protocol.reference_cases = options->reference_cases;
        protocol.reference_steps = options->reference_steps;
        protocol.structure_seeds = options->structure_seeds;
        protocol.brake_share = options->brake_share;
        protocol.thread_cpu_clock = options->clock == "cpu";
        protocol.allocation_count = allocations;
        Progress progress("validating",
                          options->cases + options->reference_cases + options->reference_cases / 4);
        protocol.progress = [&progress](int done, int) { progress.update(done); };
        const InterruptGuard interrupts;  // Ctrl-C: the figures of the cases done so far
        protocol.stop = [] { return interrupt_requested(); };
        const OtgValidationResult r = run_otg_validation(protocol);
        progress.finish();
        const auto stopped = [&] {
          if (r.interrupted)
            throw InterruptedError("bench otg: interrupted after " + std::to_string(r.cases) +
                                       " of " + std::to_string(options->cases) + " cases and " +
                                       std::to_string(r.reference_cases) + " of " +
                                       std::to_string(options->reference_cases) +
                                       " reference cases",
                                   interrupt_signal());
        };
        const double calculations = 2.0 * r.cases;
        const double per_calculation =
            r.allocations_counted ? static_cast<double>(r.allocations) / calculations : -1.0;
        if (options->json) {
          print_json({{"interrupted", r.interrupted},
                      {"cases", r.cases},
                      {"dofs", r.dofs},
                      {"seed", options->seed},
                      {"braking_dofs", r.braking_dofs},
                      {"position_failures", r.position_failures},
                      {"velocity_failures", r.velocity_failures},
                      {"check_failures", r.check_failures},
                      {"worst_limit_violation", r.worst_limit_violation},
                      {"worst_target_error", r.worst_target_error},
                      {"worst_velocity_target_error", r.worst_velocity_target_error},
                      {"worst_sync_error_s", r.worst_sync_error},
                      {"first_failure", r.first_failure},
                      {"first_velocity_failure", r.first_velocity_failure},
                      {"clock", options->clock},
                      {"mean_us", r.mean_us},
                      {"median_us", r.median_us},
                      {"p99_us", r.p99_us},
                      {"max_us", r.max_us},
                      {"velocity_mean_us", r.velocity_mean_us},
                      {"allocations_per_calculation", per_calculation},
                      {"reference_cases", r.reference_cases},
                      {"optimality_beaten", r.optimality_beaten},
                      {"reference_not_within_3_percent", r.reference_not_within},
                      {"sync_reference_cases", r.sync_reference_cases},
                      {"sync_mismatches", r.sync_mismatches},
                      {"blocked_intervals_checked", r.blocked_checked},
                      {"blocked_mismatches", r.blocked_mismatches},
                      {"blocked_cases", r.blocked_cases},
                      {"blocked_end_failures", r.blocked_end_failures},
                      {"blocked_end_not_confirmed", r.blocked_end_not_confirmed},
                      {"first_reference_failure", r.first_reference_failure},
                      {"structure_seeds", options->structure_seeds},
                      {"structure_cases", r.structure_cases},
                      {"structure_retries", r.structure_retries},
                      {"structure_not_found", r.structure_not_found},
                      {"structure_shorter", r.structure_shorter},
                      {"structure_longer", r.structure_longer},
                      {"structure_inside_blocked", r.structure_inside_blocked},
                      {"structure_blocked_ends", r.structure_blocked_ends},
                      {"structure_blocked_ends_missing", r.structure_blocked_ends_missing},
                      {"structure_mean_ms", r.structure_mean_ms},
                      {"first_structure_failure", r.first_structure_failure}});
          return stopped();
        }
        print_fields(
            std::cout,
            {{"cases", std::to_string(r.cases) + " × " + std::to_string(r.dofs) + " DoF, seed " +
                           std::to_string(options->seed)},
             {"starting beyond limits", std::to_string(r.braking_dofs) + " DoFs"},
             {"position failures", std::to_string(r.position_failures)},
             {"velocity failures", std::to_string(r.velocity_failures)},
             {"check failures", std::to_string(r.check_failures)},
             {"worst limit violation",
              compact(r.worst_limit_violation) + " (relative, at analytic extrema)"},
             {"worst target error", compact(r.worst_target_error) + " (p, v, a)"},
             {"worst velocity target error", compact(r.worst_velocity_target_error) + " (v, a)"},
             {"worst sync error [s]", compact(r.worst_sync_error)}});
        if (!r.first_failure.empty()) std::cout << "first failure: " << r.first_failure << '\n';
        if (!r.first_velocity_failure.empty())
          std::cout << "first velocity failure: " << r.first_velocity_failure << '\n';
        std::cout << '\n';
        Table table({{"calculation (" + options->clock + " clock)", Table::Align::left},
                     {"mean [µs]"},
                     {"median [µs]"},
                     {"p99 [µs]"},
                     {"max [µs]"},
                     {"alloc/calc"}});
        table.add_row({"position, " + std::to_string(r.dofs) + " DoF", fixed(r.mean_us, 2),
                       fixed(r.median_us, 2), fixed(r.p99_us, 2), fixed(r.max_us, 1),
                       per_calculation < 0.0 ? "-" : compact(per_calculation)});
        table.add_row({"velocity, " + std::to_string(r.dofs) + " DoF", fixed(r.velocity_mean_us, 2),
                       "", "", "", ""});
        table.print(std::cout);
        std::cout << "\ntime optimality (one DoF, grid reference of " << options->reference_steps
                  << " steps): " << r.reference_cases << " cases, " << r.optimality_beaten
                  << " beaten by a grid motion, " << r.reference_not_within
                  << " without a grid motion within 3 % above; limiting DoF of "
                  << r.sync_reference_cases << " n-DoF cases: " << r.sync_mismatches
                  << " with a shorter motion; blocked intervals (" << r.blocked_cases
                  << " cases drawn with one): " << r.blocked_checked << " probed, "
                  << r.blocked_mismatches << " with a motion inside, " << r.blocked_end_failures
                  << " ends without a profile just outside, " << r.blocked_end_not_confirmed
                  << " ends the grid does not confirm\n";
        if (!r.first_reference_failure.empty())
          std::cout << "first reference mismatch: " << r.first_reference_failure << '\n';
        std::cout << "time optimality (one DoF, exhaustive search over the switching structures, "
                  << options->structure_seeds << " seeds each): " << r.structure_cases << " cases ("
                  << fixed(r.structure_mean_ms, 0) << " ms each), " << r.structure_shorter
                  << " with a motion shorter than t_min, " << r.structure_longer
                  << " whose shortest motion is longer, " << r.structure_not_found
                  << " without a motion; blocked intervals: " << r.structure_inside_blocked
                  << " cases with a motion inside, " << r.structure_blocked_ends_missing << " of "
                  << r.structure_blocked_ends << " ends not found as extremal motions\n";
        if (!r.first_structure_failure.empty())
          std::cout << "first structure mismatch: " << r.first_structure_failure << '\n';
        stopped();
      }};
}

}  // namespace mjarm::cli
