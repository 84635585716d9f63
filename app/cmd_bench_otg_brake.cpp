// `mjarm bench otg-brake [--cases N] [--dofs D] [--seed S] [--family-members M]
// [--structure-cases K] [--structure-seeds M] [--json]`: the jerk-limited generator from starts
// beyond the limits — its durations against the best feasible ones, with the standard brake and
// with the generator's (docs/trajectory_otg.md, "Brake").

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/trajectory/otg/validation/brake_optimality.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

std::string percent_of(int part, int whole) {
  return whole > 0 ? fixed(100.0 * part / whole, 2) + " %" : "-";
}

std::string figures_text(const BrakeDurationFigures& f, int dofs) {
  return std::to_string(f.longer) + " of " + std::to_string(dofs) + " longer (" +
         percent_of(f.longer, dofs) + "), up to " + fixed(100.0 * (f.worst_ratio - 1.0), 2) +
         " % longer; " + std::to_string(f.shorter) + " shorter";
}

}  // namespace

Command add_bench_otg_brake_subcommand(CLI::App& bench) {
  struct Options {
    int cases = 10000;
    int dofs = 7;
    std::uint64_t seed = 0;
    int family_members = 1000;
    int structure_cases = 0;
    int structure_seeds = 16;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "otg-brake",
      "jerk-limited generation from starts beyond the limits: N random n-DoF cases, every DoF "
      "beyond its limits or unable to avoid overshooting them; per DoF the duration of brake and "
      "time-optimal profile against the best of its brake family (a scan) and, for the first K, "
      "against the exhaustive structure search — for the standard brake and the generator's");
  app->add_option("--cases", options->cases, "random n-DoF cases N")->check(count_in(1, 1000000));
  app->add_option("--dofs", options->dofs, "degrees of freedom per case")->check(CLI::Range(1, 64));
  app->add_option("--seed", options->seed, "seed of the cases")->check(non_negative_integer());
  app->add_option("--family-members", options->family_members,
                  "brake-family members scanned per DoF")
      ->check(count_in(2, 100000));
  app->add_option("--structure-cases", options->structure_cases,
                  "DoFs also given to the structure search (about a second each)")
      ->check(count_in(0, 100000));
  app->add_option("--structure-seeds", options->structure_seeds,
                  "starting points per switching structure of the structure search")
      ->check(count_in(1, 256));
  add_json_flag(*app, options->json);

  return {app, [options] {
            BrakeOptimalityOptions protocol;
            protocol.cases = options->cases;
            protocol.dofs = options->dofs;
            protocol.seed = options->seed;
            protocol.family_members = options->family_members;
            protocol.structure_cases = options->structure_cases;
            protocol.structure_seeds = options->structure_seeds;
            Progress progress("validating", options->cases * options->dofs);
            protocol.progress = [&progress](int done, int) { progress.update(done); };
            const InterruptGuard interrupts;  // Ctrl-C: the figures of the cases done so far
            protocol.stop = [] { return interrupt_requested(); };
            const BrakeOptimalityResult r = run_brake_optimality(protocol);
            progress.finish();
            if (options->json) {
              print_json({{"interrupted", r.interrupted},
                          {"cases", r.cases},
                          {"dofs", r.dofs},
                          {"seed", options->seed},
                          {"braking_dofs", r.braking_dofs},
                          {"with_choice", r.with_choice},
                          {"failures", r.failures},
                          {"check_failures", r.check_failures},
                          {"worst_limit_excess", r.worst_limit_excess},
                          {"worst_target_error", r.worst_target_error},
                          {"worst_sync_error_s", r.worst_sync_error},
                          {"standard_longer", r.standard.longer},
                          {"standard_worst_ratio", r.standard.worst_ratio},
                          {"optimal_longer", r.optimal.longer},
                          {"optimal_worst_ratio", r.optimal.worst_ratio},
                          {"optimal_shorter", r.optimal.shorter},
                          {"structure_cases", r.structure_cases},
                          {"structure_not_found", r.structure_not_found},
                          {"structure_standard_longer", r.structure_standard.longer},
                          {"structure_standard_worst_ratio", r.structure_standard.worst_ratio},
                          {"structure_optimal_longer", r.structure_optimal.longer},
                          {"structure_optimal_shorter", r.structure_optimal.shorter},
                          {"structure_optimal_worst_ratio", r.structure_optimal.worst_ratio},
                          {"structure_mean_ms", r.structure_mean_ms},
                          {"first_failure", r.first_failure},
                          {"first_structure_mismatch", r.first_structure_mismatch}});
            } else {
              print_fields(
                  std::cout,
                  {{"cases", std::to_string(r.cases) + " × " + std::to_string(r.dofs) +
                                 " DoF, seed " + std::to_string(options->seed)},
                   {"DoFs beyond their limits", std::to_string(r.braking_dofs) + " (" +
                                                    std::to_string(r.with_choice) +
                                                    " with a choice of brake)"},
                   {"failures", std::to_string(r.failures)},
                   {"check failures", std::to_string(r.check_failures)},
                   {"worst limit excess", compact(r.worst_limit_excess) + " (after the brakes)"},
                   {"worst target error", compact(r.worst_target_error)},
                   {"worst sync error [s]", compact(r.worst_sync_error)},
                   {"standard brake vs family best", figures_text(r.standard, r.braking_dofs)},
                   {"generator vs family best", figures_text(r.optimal, r.braking_dofs)},
                   {"standard brake vs structure search",
                    figures_text(r.structure_standard, r.structure_cases - r.structure_not_found)},
                   {"generator vs structure search",
                    figures_text(r.structure_optimal, r.structure_cases - r.structure_not_found)},
                   {"structure search", std::to_string(r.structure_cases) + " DoFs, " +
                                            std::to_string(r.structure_not_found) +
                                            " without a motion, " + fixed(r.structure_mean_ms, 0) +
                                            " ms each"}});
              if (!r.first_failure.empty())
                std::cout << "first failure: " << r.first_failure << '\n';
              if (!r.first_structure_mismatch.empty())
                std::cout << "first structure mismatch: " << r.first_structure_mismatch << '\n';
            }
            if (r.interrupted)
              throw InterruptedError(
                  "bench otg-brake: interrupted after " + std::to_string(r.cases) + " cases",
                  interrupt_signal());
          }};
}

}  // namespace mjarm::cli
