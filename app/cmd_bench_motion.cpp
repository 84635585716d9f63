// `mjarm bench traj [--calls N] [--block B] [--clock wall|cpu] [--json]`: evaluation cost per
// call of the motion profiles and of the viewer's target filter, against their targets.
// `mjarm bench plan [--plans N] [--clock wall|cpu] [--json]`: planning the 5-waypoint path on
// the panda, against its target (planning/motion_benchmark.hpp).

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/planning/motion_benchmark.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

std::string motion_verdict(double value, double target) { return value <= target ? "yes" : "NO"; }

}  // namespace

Command add_bench_traj_subcommand(CLI::App& bench, std::function<std::uint64_t()> allocations) {
  struct Options {
    std::int64_t calls = 2000000;
    int block = 256;
    std::int64_t recalculations = 20000;
    std::string clock = "wall";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "traj",
      "cost per call of evaluating the motion profiles (trapezoid, synced trapezoid, 7-joint "
      "quintic, SE(3) interpolation, smootherstep) and of the viewer's target filter (a tick in "
      "motion; a tick whose target moved: a 6-DoF jerk-limited recalculation), against targets");
  app->add_option("--calls", options->calls, "timed calls per case")
      ->check(count_in(1, 1000000000));  // of each evaluation case
  app->add_option("--block", options->block, "calls per clock read")->check(count_in(1, 100000));
  app->add_option("--recalculations", options->recalculations,
                  "timed calls of the recalculating target-filter case (blocks of 16)")
      ->check(count_in(16, 100000000));
  app->add_option("--clock", options->clock,
                  "wall: steady clock; cpu: the thread's CPU time (for a shared machine)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  add_json_flag(*app, options->json);
  return {
      app, [options, allocations] {
        if (options->calls < options->block)
          throw UsageError("--calls (" + std::to_string(options->calls) +
                           ") must be at least --block (" + std::to_string(options->block) + ")");
        ProfileBenchmarkOptions protocol;
        protocol.calls = options->calls;
        protocol.block = options->block;
        protocol.recalculations = options->recalculations;
        protocol.thread_cpu_clock = options->clock == "cpu";
        protocol.allocation_count = allocations;
        Progress progress("timing profiles (calls)", 1);
        protocol.progress = [&progress](std::int64_t done, std::int64_t total) {
          progress.update(done, total);
        };
        const InterruptGuard interrupts;  // Ctrl-C: the figures of the calls timed so far
        protocol.stop = [] { return interrupt_requested(); };
        const ProfileBenchmarkResult r = run_profile_benchmark(protocol);
        progress.finish();
        // printed first, the figures measured so far; then the interrupt
        const auto stopped = [&] {
          if (!r.interrupted) return;
          const ProfileBenchmarkCase& last = r.cases.back();
          const std::int64_t asked = r.cases.size() == 7 ? options->recalculations : options->calls;
          throw InterruptedError("bench traj: interrupted in case " +
                                     std::to_string(r.cases.size()) + " of 7 ('" + last.name +
                                     "') after " + std::to_string(last.calls) + " of " +
                                     std::to_string(asked) + " calls",
                                 interrupt_signal());
        };
        if (options->json) {
          Json cases = Json::array();
          for (const auto& c : r.cases)
            cases.push_back({{"case", c.name},
                             {"call", c.call},
                             {"calls", c.calls},
                             {"median_ns", c.median_ns},
                             {"p99_ns", c.p99_ns},
                             {"mean_ns", c.mean_ns},
                             {"target_ns", c.target_ns},
                             {"within_target", c.median_ns <= c.target_ns},
                             {"allocations_per_call", c.allocations_per_call}});
          print_json({{"interrupted", r.interrupted},
                      {"clock", options->clock},
                      {"block", options->block},
                      {"cases", cases}});
          return stopped();
        }
        print_fields(std::cout,
                     {{"protocol",
                       "each case built once, then evaluated at 256 seeded "
                       "instants over [−0.05T, 1.05T], cycled"},
                      {"timing", std::to_string(options->block) + " calls per clock read (" +
                                     options->clock + " clock); median and p99 over the blocks"}});
        std::cout << '\n';
        Table table({{"case", Table::Align::left},
                     {"call", Table::Align::left},
                     {"median [ns]"},
                     {"p99 [ns]"},
                     {"mean [ns]"},
                     {"target [ns]"},
                     {"met"},
                     {"alloc/call"}});
        for (const auto& c : r.cases)
          table.add_row({c.name, c.call, fixed(c.median_ns, 1), fixed(c.p99_ns, 1),
                         fixed(c.mean_ns, 1), "≤ " + compact(c.target_ns),
                         motion_verdict(c.median_ns, c.target_ns),
                         c.allocations_per_call < 0 ? "-" : compact(c.allocations_per_call)});
        table.print(std::cout);
        if (r.interrupted)
          std::cout << "\ninterrupted: the last case timed " << r.cases.back().calls
                    << " calls; the cases after it did not run\n";
        stopped();
      }};
}

Command add_bench_plan_subcommand(CLI::App& bench) {
  struct Options {
    int plans = 50;
    std::string clock = "wall";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "plan",
      "planning the 5-waypoint path on the panda (panda_torque, attachment_site, from home, "
      "default plan options), each plan timed, against the target");
  app->add_option("--plans", options->plans, "timed plans")->check(count_in(1, 100000));
  app->add_option("--clock", options->clock,
                  "wall: steady clock; cpu: the thread's CPU time (for a shared machine)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  add_json_flag(*app, options->json);
  return {
      app, [options] {
        PlanBenchmarkOptions protocol;
        protocol.plans = options->plans;
        protocol.thread_cpu_clock = options->clock == "cpu";
        Progress progress("planning", options->plans);
        protocol.progress = [&progress](int done, int) { progress.update(done); };
        const InterruptGuard interrupts;
        protocol.stop = [] { return interrupt_requested(); };
        const PlanBenchmarkResult r = run_plan_benchmark(protocol);
        progress.finish();
        if (!r.ok) throw Error("bench plan: the 5-waypoint plan failed: " + r.message);
        // printed first, the figures of the plans timed so far; then the interrupt
        const auto stopped = [&] {
          if (!r.interrupted) return;
          throw InterruptedError("bench plan: interrupted after " + std::to_string(r.plans) +
                                     " of " + std::to_string(options->plans) + " plans",
                                 interrupt_signal());
        };
        if (options->json) {
          print_json({{"interrupted", r.interrupted},
                      {"model", r.model},
                      {"waypoints", r.waypoints},
                      {"plans", r.plans},
                      {"clock", options->clock},
                      {"median_ms", r.median_ms},
                      {"p99_ms", r.p99_ms},
                      {"mean_ms", r.mean_ms},
                      {"max_ms", r.max_ms},
                      {"target_ms", r.target_ms},
                      {"within_target", r.median_ms <= r.target_ms},
                      {"plan_duration", r.duration},
                      {"samples", r.samples}});
          return stopped();
        }
        print_fields(
            std::cout,
            {{"model", r.model + ", frame attachment_site, from keyframe 'home'"},
             {"path", std::to_string(r.waypoints) + " waypoints, the tool pointing down"},
             {"plan", compact(r.duration) + " s of motion, " + std::to_string(r.samples) +
                          " states checked"},
             {"plans timed",
              std::to_string(r.plans) +
                  (r.interrupted ? " of " + std::to_string(options->plans) + ", interrupted" : "") +
                  " (" + options->clock + " clock)"}});
        std::cout << '\n';
        Table table(
            {{"median [ms]"}, {"p99 [ms]"}, {"mean [ms]"}, {"max [ms]"}, {"target [ms]"}, {"met"}});
        table.add_row({fixed(r.median_ms, 2), fixed(r.p99_ms, 2), fixed(r.mean_ms, 2),
                       fixed(r.max_ms, 2), "≤ " + compact(r.target_ms),
                       motion_verdict(r.median_ms, r.target_ms)});
        table.print(std::cout);
        stopped();
      }};
}

}  // namespace mjarm::cli
