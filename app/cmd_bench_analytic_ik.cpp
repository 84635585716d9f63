// `mjarm bench analytic-ik [MODEL] [--site S] [--samples N] [--seed S] [--json]`: the closed-form
// 6R solver's accuracy (every branch through MuJoCo's forward kinematics) over N random
// configurations, and its time per solve (all branches).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <vector>

#include "commands.hpp"
#include "mjarm/benchmark_timing.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/ik/analytic_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/random.hpp"
#include "options.hpp"
#include "output.hpp"

namespace mjarm::cli {
namespace {

/// What the protocol measured.
struct AnalyticIkFigures {
  int samples = 0;
  int solved = 0;     ///< samples with at least one branch
  int recovered = 0;  ///< samples whose original configuration is among the branches (mod 2π)
  int all_eight = 0;  ///< samples with 8 branches
  int singular = 0;   ///< samples with a branch flagged singular
  long branches = 0;  ///< branches returned in all
  long within_limits = 0;
  long dropped = 0;                    ///< branches dropped by the solver's own check
  double max_position_error = 0.0;     ///< by MuJoCo's FK, over every branch [m]
  double max_orientation_error = 0.0;  ///< [rad]
  double median_us = 0.0, p95_us = 0.0, mean_us = 0.0, max_us = 0.0;
  /// The same solves with the branches unchecked (`AnalyticIkOptions::check_branches` off).
  double unchecked_median_us = 0.0, unchecked_p95_us = 0.0;
};

AnalyticIkFigures run_protocol(const Chain& chain, int samples, std::uint64_t seed) {
  const AnalyticIk ik(chain);
  AnalyticIkOptions unchecked_options;
  unchecked_options.check_branches = false;
  const AnalyticIk unchecked(chain, unchecked_options);
  ChainKinematics kin(chain);
  Random rng(seed);
  constexpr double pi = std::numbers::pi;
  AnalyticIkFigures f;
  std::vector<double> times_us, unchecked_us;
  times_us.reserve(static_cast<std::size_t>(samples));
  unchecked_us.reserve(static_cast<std::size_t>(samples));
  AnalyticIkSolution solution, unchecked_solution;
  using Clock = std::chrono::steady_clock;
  for (int k = 0; k < samples; ++k) {
    Vector6d q;  // uniform in the limits, within one turn
    for (int i = 0; i < 6; ++i) {
      const double lo = std::max(chain.lower()[i], -pi), hi = std::min(chain.upper()[i], pi);
      q[i] = uniform(rng, lo, hi);
    }
    const Pose target = kin.update(q);
    const auto start = Clock::now();
    ik.solve(target, solution);
    const auto stop = Clock::now();
    times_us.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    const auto unchecked_start = Clock::now();
    unchecked.solve(target, unchecked_solution);
    const auto unchecked_stop = Clock::now();
    unchecked_us.push_back(
        std::chrono::duration<double, std::micro>(unchecked_stop - unchecked_start).count());
    ++f.samples;
    f.solved += solution.status == AnalyticIkStatus::solved;
    f.all_eight += solution.count == 8;
    f.branches += solution.count;
    f.dropped += solution.dropped;
    bool found = false, singular = false;
    for (int b = 0; b < solution.count; ++b) {
      const AnalyticIkBranch& branch = solution.branches[b];
      const Pose& X = kin.update(branch.q);
      f.max_position_error = std::max(f.max_position_error, (X.p - target.p).norm());
      const Eigen::AngleAxisd rel(X.R.transpose() * target.R);
      f.max_orientation_error = std::max(f.max_orientation_error, std::abs(rel.angle()));
      double gap = 0.0;
      for (int i = 0; i < 6; ++i) {
        gap = std::max(gap, std::abs(std::remainder(branch.q[i] - q[i], 2.0 * pi)));
      }
      found = found || gap < 1e-6;
      singular = singular || branch.singular;
      f.within_limits += branch.within_limits;
    }
    f.recovered += found;
    f.singular += singular;
  }
  double total = 0.0;
  for (const double t : times_us) total += t;
  f.mean_us = total / samples;
  f.max_us = *std::max_element(times_us.begin(), times_us.end());
  std::sort(times_us.begin(), times_us.end());
  std::sort(unchecked_us.begin(), unchecked_us.end());
  f.median_us = nearest_rank(times_us, 0.5);
  f.p95_us = nearest_rank(times_us, 0.95);
  f.unchecked_median_us = nearest_rank(unchecked_us, 0.5);
  f.unchecked_p95_us = nearest_rank(unchecked_us, 0.95);
  return f;
}

}  // namespace

Command add_bench_analytic_ik_subcommand(CLI::App& bench) {
  struct Options {
    std::string model = "ur5e";
    std::string site;
    int samples = 100000;
    std::uint64_t seed = 0;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "analytic-ik",
      "closed-form 6R IK (spherical wrist or UR family): N random configurations → MuJoCo FK → "
      "every branch → MuJoCo FK again; the worst branch error, how often the original "
      "configuration is among the branches, and the time per solve (all branches)");
  app->add_option("model", options->model, "bundled model name or MJCF file (default ur5e)");
  add_site_option(*app, options->site);
  app->add_option("--samples", options->samples, "number of random configurations N")
      ->check(count_in(1, 10000000));
  app->add_option("--seed", options->seed, "seed of the configurations")
      ->check(non_negative_integer());
  add_json_flag(*app, options->json);

  return {app, [options] {
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            const AnalyticIk ik(chain);  // refused here, with the reason, before any sampling
            const AnalyticIkFigures f = run_protocol(chain, options->samples, options->seed);
            const double n = f.samples;
            if (options->json) {
              print_json({{"model", robot.name()},
                          {"frame", chain.frame().name},
                          {"family", std::string(to_string(ik.family()))},
                          {"samples", f.samples},
                          {"seed", options->seed},
                          {"solved_fraction", f.solved / n},
                          {"recovered_fraction", f.recovered / n},
                          {"eight_branch_fraction", f.all_eight / n},
                          {"singular_samples", f.singular},
                          {"mean_branches", static_cast<double>(f.branches) / n},
                          {"within_limits_branches", f.within_limits},
                          {"dropped_branches", f.dropped},
                          {"max_position_error_m", f.max_position_error},
                          {"max_orientation_error_rad", f.max_orientation_error},
                          {"time_us",
                           {{"median", f.median_us},
                            {"p95", f.p95_us},
                            {"mean", f.mean_us},
                            {"max", f.max_us}}},
                          {"unchecked_time_us",
                           {{"median", f.unchecked_median_us}, {"p95", f.unchecked_p95_us}}},
                          {"target_median_us", 2.0}});
              return;
            }
            print_fields(
                std::cout,
                {{"model", robot.name()},
                 {"frame", chain.frame().name},
                 {"family", std::string(to_string(ik.family()))},
                 {"samples",
                  std::to_string(f.samples) + " (seed " + std::to_string(options->seed) + ")"},
                 {"solved", fixed(100.0 * f.solved / n, 3) + " %"},
                 {"original recovered", fixed(100.0 * f.recovered / n, 3) + " %"},
                 {"8 branches", fixed(100.0 * f.all_eight / n, 3) + " %"},
                 {"branches per solve", fixed(static_cast<double>(f.branches) / n, 3) + " (" +
                                            std::to_string(f.within_limits) + " within limits, " +
                                            std::to_string(f.dropped) + " dropped)"},
                 {"samples with a singular branch", std::to_string(f.singular)},
                 {"max FK error", compact(f.max_position_error) + " m, " +
                                      compact(f.max_orientation_error) + " rad"},
                 {"time per solve [µs]",
                  "median " + fixed(f.median_us, 3) + ", p95 " + fixed(f.p95_us, 3) + ", mean " +
                      fixed(f.mean_us, 3) + ", max " + fixed(f.max_us, 1) + " (target median ≤ 2)"},
                 {"unchecked [µs]", "median " + fixed(f.unchecked_median_us, 3) + ", p95 " +
                                        fixed(f.unchecked_p95_us, 3) +
                                        " (check_branches off: no forward kinematics)"}});
          }};
}

}  // namespace mjarm::cli
