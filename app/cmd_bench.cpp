// `mjarm bench ik MODEL --site S --samples N --timeout-ms T --seed K [--clock wall|cpu]`: the
// TRAC-IK protocol.

// `mjarm bench control MODEL [--site S] [--steps N] [--warmup W] [--json]`: time per controller
// step, allocations per step, and the real-time factor of closed-loop OSC + mj_step.

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/address_sanitizer.hpp"
#include "mjarm/control/control_benchmark.hpp"
#include "mjarm/error.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/ik/ik_benchmark.hpp"
#include "mjarm/interrupt.hpp"
#include "output.hpp"

// ---- allocation counter for `bench control` ----
// Every heap allocation of the process goes through one of these (operator new and Eigen call
// malloc), so counting them here is what "allocations per controller step" means. Under
// AddressSanitizer, whose allocator must stay in charge, the sanitizer's malloc hook counts
// instead.
namespace {
std::atomic<std::uint64_t> g_heap_allocations{0};
void count_heap_allocation() noexcept {
  g_heap_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

#if defined(MJARM_ADDRESS_SANITIZER)
// from the sanitizer runtime's allocator interface (GCC does not install its header)
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));
namespace {
void sanitizer_malloc_hook(const volatile void*, std::size_t) { count_heap_allocation(); }
void sanitizer_free_hook(const volatile void*) {}  // the runtime wants both hooks
[[maybe_unused]] const int g_hooks_installed =
    __sanitizer_install_malloc_and_free_hooks(sanitizer_malloc_hook, sanitizer_free_hook);
}  // namespace
#else
// glibc's own entry points; ours count, then forward
extern "C" void* __libc_malloc(std::size_t size) noexcept;
extern "C" void* __libc_calloc(std::size_t count, std::size_t size) noexcept;
extern "C" void* __libc_realloc(void* pointer, std::size_t size) noexcept;
extern "C" void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
extern "C" void* malloc(std::size_t size) noexcept {
  count_heap_allocation();
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t count, std::size_t size) noexcept {
  count_heap_allocation();
  return __libc_calloc(count, size);
}
extern "C" void* realloc(void* pointer, std::size_t size) noexcept {
  count_heap_allocation();
  return __libc_realloc(pointer, size);
}
extern "C" void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  count_heap_allocation();
  return __libc_memalign(alignment, size);
}
extern "C" void* memalign(std::size_t alignment, std::size_t size) noexcept {
  count_heap_allocation();
  return __libc_memalign(alignment, size);
}
extern "C" int posix_memalign(void** pointer, std::size_t alignment, std::size_t size) noexcept {
  if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) return EINVAL;
  count_heap_allocation();
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return ENOMEM;
  *pointer = p;
  return 0;
}
#endif

namespace mjarm::cli {
namespace {

/// MODEL, or its torque-driven variant when MODEL is a bundled name that has one ("panda" →
/// "panda_torque"): the control benchmark drives motors.
Robot load_torque_model(const std::string& model) {
  if (model.find('/') == std::string::npos && model.find('.') == std::string::npos) {
    const auto names = Robot::bundled_names();
    const std::string torque = model + "_torque";
    if (std::find(names.begin(), names.end(), torque) != names.end()) return Robot::bundled(torque);
  }
  return load_model(model);
}

/// The median target of a row of `mjarm bench control` [µs], 0 when it has none: issue 13's on
/// the iiwa14 (se3 ≤ 5, hqp-ac ≤ 25, observer ≤ 2) and the earlier ones of docs/control.md.
double control_target_us(const std::string& name) {
  if (name == "joint-pd" || name == "gravity") return 1.0;
  if (name == "ct") return 3.0;
  if (name == "osc") return 4.0;
  if (name == "se3") return 5.0;
  if (name == "hqp-ac") return 25.0;
  if (name == "observer") return 2.0;
  return 0.0;
}

Json controller_json(const ControllerBenchmark& c) {
  const double target = control_target_us(c.name);
  Json row{{"name", c.name},
           {"target_median_us", target > 0.0 ? Json(target) : Json(nullptr)},
           {"meets_target", target > 0.0 ? Json(c.median_us <= target) : Json(nullptr)}};
  row.update(fields_to_json(c));
  return row;
}

/// `mjarm bench control`: registers the subcommand on @p bench.
Command add_control_subcommand(CLI::App& bench) {
  struct Options {
    std::string model;
    std::string site;
    int steps = 20000;
    int warmup = 200;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand(
      "control",
      "every torque controller (joint PD, gravity hold, computed torque, task PD, acceleration "
      "control, operational space, SE(3) impedance, CIC, HQP-AC) and the momentum observer in "
      "closed loop with MuJoCo on a periodic reference: median and p99 time per controller step "
      "against the targets, heap allocations per step, and the real-time factor of "
      "operational-space control + mj_step beside mj_step alone");
  add_model_argument(*app, options->model)->required();
  add_site_option(*app, options->site);
  app->add_option("--steps", options->steps,
                  "timed control steps per controller (one per physics step)")
      ->check(count_in(1, 1000000));
  app->add_option("--warmup", options->warmup, "untimed steps before each timed run")
      ->check(count_in(0, 1000000));
  add_json_flag(*app, options->json);

  return {
      app, [options] {
        const Robot robot = load_torque_model(options->model);
        const Chain chain(robot, resolve_site(robot, options->site));
        ControlBenchmarkOptions protocol;
        protocol.steps = options->steps;
        protocol.warmup = options->warmup;
        protocol.allocation_count = [] {
          return g_heap_allocations.load(std::memory_order_relaxed);
        };
        Progress progress("benchmarking controllers", 12);
        protocol.progress = [&progress](int done, int) { progress.update(done); };
        const InterruptGuard interrupts;  // Ctrl-C: the figures of the controllers done
        protocol.stop = [] { return interrupt_requested(); };
        const ControlBenchmarkResult r = run_control_benchmark(chain, protocol);
        progress.finish();
        // a faulted run's numbers mean nothing: no figures, a failed command
        const std::string failed = "bench control on model '" + r.robot + "': " + r.message;
        const bool interrupted = r.status == ControlBenchmarkStatus::interrupted;
        if (r.status != ControlBenchmarkStatus::ok && !interrupted) throw Error(failed);
        // printed first, the controllers measured before the interrupt; then the interrupt
        const bool timed_loop = r.osc_real_time_factor > 0.0 && r.passive_real_time_factor > 0.0;
        const auto stopped = [&] {
          if (!interrupted) return;
          throw InterruptedError("bench control on model '" + r.robot + "': interrupted after " +
                                     std::to_string(r.controllers.size()) +
                                     " controller runs; the real-time factor was not measured",
                                 interrupt_signal());
        };

        if (options->json) {
          Json controllers = Json::array();
          for (const auto& c : r.controllers) controllers.push_back(controller_json(c));
          print_json(
              {{"interrupted", interrupted},
               {"model", r.robot},
               {"frame", r.frame},
               {"joints", r.joints},
               {"timestep", r.timestep},
               {"steps", r.steps},
               {"warmup", options->warmup},
               {"reference_frequency_hz", r.frequency},
               {"reference_amplitude", protocol.amplitude},
               {"controllers", controllers},
               {"real_time_factor", timed_loop ? Json{{"osc_mj_step", r.osc_real_time_factor},
                                                      {"mj_step_only", r.passive_real_time_factor}}
                                               : Json(nullptr)},
               {"step_us", timed_loop ? Json{{"osc_mj_step", r.osc_step_us},
                                             {"mj_step_only", r.passive_step_us}}
                                      : Json(nullptr)},
               {"loop_allocations", timed_loop ? Json(r.loop_allocations) : Json(nullptr)}});
          return stopped();
        }
        print_fields(
            std::cout,
            {{"model", r.robot},
             {"frame", r.frame},
             {"joints", std::to_string(r.joints)},
             {"timestep [s]", compact(r.timestep) + " (one control step per physics step)"},
             {"steps", std::to_string(r.steps) + " per controller, after " +
                           std::to_string(options->warmup) + " untimed"},
             {"reference", "joint sinusoids of " + compact(protocol.amplitude) + " rad at " +
                               compact(r.frequency) + " Hz and their task-space image"}});
        std::cout << '\n';
        Table table({{"controller", Table::Align::left},
                     {"median [µs]"},
                     {"target [µs]"},
                     {"met", Table::Align::left},
                     {"p99 [µs]"},
                     {"mean [µs]"},
                     {"max [µs]"},
                     {"alloc/step"},
                     {"rms error [mm]"}});
        for (const auto& c : r.controllers) {
          const double target = control_target_us(c.name);
          const bool has = target > 0.0;
          table.add_row({c.name, fixed(c.median_us, 3), has ? "≤ " + compact(target) : "—",
                         has ? (c.median_us <= target ? "yes" : "NO") : "", fixed(c.p99_us, 3),
                         fixed(c.mean_us, 3), fixed(c.max_us, 1), compact(c.allocations_per_step),
                         fixed(1e3 * c.rms_position_error, 3)});
        }
        table.print(std::cout);
        std::cout << '\n';
        if (!timed_loop) {
          std::cout << "real-time factor: not measured (interrupted)\n";
          return stopped();
        }
        Table rtf({{"one thread", Table::Align::left}, {"real-time factor"}, {"per step [µs]"}});
        rtf.add_row({"osc + mj_step", fixed(r.osc_real_time_factor, 1), fixed(r.osc_step_us, 3)});
        rtf.add_row(
            {"mj_step only", fixed(r.passive_real_time_factor, 1), fixed(r.passive_step_us, 3)});
        rtf.print(std::cout);
        std::cout << "\nheap allocations in the closed OSC loop (controller + physics): "
                  << r.loop_allocations << '\n';
      }};
}

}  // namespace

Command add_bench_command(CLI::App& root) {
  struct Options {
    std::string model;
    std::string site;
    int samples = 10000;
    double timeout_ms = 5.0;
    int max_restarts = -1;  // unbounded (the protocol)
    std::uint64_t seed = 0;
    std::string clock = "wall";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* bench = root.add_subcommand(
      "bench",
      "benchmarks of the library: ik, control, otg (jerk-limited generator), topp (time-optimal "
      "path parameterization), traj (motion "
      "profiles), plan (5-waypoint panda path), env (learning environment), diffik (collision "
      "rows), analytic-ik (closed-form 6R IK); see `mjarm bench NAME "
      "--help`");
  bench->require_subcommand(1);
  CLI::App* app = bench->add_subcommand(
      "ik",
      "TRAC-IK protocol: N random configurations inside the limits → forward kinematics → solve "
      "that 6-D pose from the mid-range configuration, then again from random configurations; "
      "success = x, y, z, roll, pitch, yaw each within 1e-5 and joints within limits");
  add_model_argument(*app, options->model)->required();
  add_site_option(*app, options->site);
  app->add_option("--samples", options->samples, "number of random targets N")
      ->check(count_in(1, 10000000));
  app->add_option("--timeout-ms", options->timeout_ms, "time budget per solve [ms]; default 5")
      ->check(timeout_ms());
  app->add_option("--seed", options->seed, "seed of the targets (and of the random starts)")
      ->check(non_negative_integer());
  app->add_option("--max-restarts", options->max_restarts,
                  "restarts the global solver may make per solve; default unbounded (the "
                  "protocol: the budget decides). With a cap and a roomy --timeout-ms every "
                  "sample's outcome is the same on any machine")
      ->check(count_in(0, 1000000));
  app->add_option("--clock", options->clock,
                  "wall: the published protocol (steady clock); cpu: the solving thread's CPU "
                  "time, for a shared machine (a solve over budget counts as failed)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  add_json_flag(*app, options->json);
  const Command control = add_control_subcommand(*bench);
  const Command otg = add_bench_otg_subcommand(
      *bench, [] { return g_heap_allocations.load(std::memory_order_relaxed); });
  const Command otg_brake = add_bench_otg_brake_subcommand(*bench);
  const Command topp = add_bench_topp_subcommand(
      *bench, [] { return g_heap_allocations.load(std::memory_order_relaxed); });
  const Command traj = add_bench_traj_subcommand(
      *bench, [] { return g_heap_allocations.load(std::memory_order_relaxed); });
  const Command plan = add_bench_plan_subcommand(*bench);
  const Command ompl = add_bench_ompl_subcommand(*bench);
  const Command env = add_bench_env_subcommand(*bench);
  const Command diffik = add_bench_diffik_subcommand(*bench);
  const Command analytic = add_bench_analytic_ik_subcommand(*bench);

  return {bench,
          [options, app, control, otg, otg_brake, topp, traj, plan, ompl, env, diffik, analytic] {
            if (control.app->parsed()) return control.run();
            if (otg.app->parsed()) return otg.run();
            if (otg_brake.app->parsed()) return otg_brake.run();
            if (topp.app->parsed()) return topp.run();
            if (traj.app->parsed()) return traj.run();
            if (plan.app->parsed()) return plan.run();
            if (ompl.app->parsed()) return ompl.run();
            if (env.app->parsed()) return env.run();
            if (diffik.app->parsed()) return diffik.run();
            if (analytic.app->parsed()) return analytic.run();
            if (!app->parsed()) return;
            const Robot robot = load_model(options->model);
            const Chain chain(robot, resolve_site(robot, options->site));
            std::vector<IkBenchmarkResult> results;
            const InterruptGuard interrupts;  // Ctrl-C: the figures of the samples done
            for (const IkSeedMode mode : {IkSeedMode::mid_range, IkSeedMode::random}) {
              if (!results.empty() && results.back().interrupted) break;
              IkBenchmarkOptions protocol;
              protocol.samples = options->samples;
              protocol.seed = options->seed;
              protocol.seed_mode = mode;
              protocol.timeout = std::chrono::duration<double, std::milli>(options->timeout_ms);
              if (options->max_restarts >= 0) protocol.max_restarts = options->max_restarts;
              protocol.clock =
                  options->clock == "cpu" ? IkBenchmarkClock::thread_cpu : IkBenchmarkClock::wall;
              Progress progress(std::string("solving (") + to_string(mode) + " seeds)",
                                options->samples);
              protocol.progress = [&progress](int done, int) { progress.update(done); };
              protocol.stop = [] { return interrupt_requested(); };
              results.push_back(run_ik_benchmark(chain, protocol));
              progress.finish();
            }
            const auto stopped = [&] {
              if (!results.back().interrupted) return;
              throw InterruptedError("bench ik: interrupted after " +
                                         std::to_string(results.back().samples) + " of " +
                                         std::to_string(options->samples) + " samples (" +
                                         to_string(results.back().seed_mode) + " seeds)",
                                     interrupt_signal());
            };
            if (options->json) {
              Json runs = Json::array();
              for (const auto& r : results) runs.push_back(fields_to_json(r));
              print_json({{"model", robot.name()},
                          {"frame", chain.frame().name},
                          {"joints", chain.size()},
                          {"samples", options->samples},
                          {"timeout_ms", options->timeout_ms},
                          {"max_restarts", options->max_restarts >= 0
                                               ? Json(options->max_restarts)
                                               : Json(nullptr)},
                          {"seed", options->seed},
                          {"clock", to_string(results.front().clock)},
                          {"interrupted", results.back().interrupted},
                          {"runs", runs}});
              return stopped();
            }
            print_fields(std::cout, {{"model", robot.name()},
                                     {"frame", chain.frame().name},
                                     {"solver", results.front().solver},
                                     {"samples", std::to_string(options->samples)},
                                     {"timeout [ms]", compact(options->timeout_ms)},
                                     {"restarts", options->max_restarts >= 0
                                                      ? "at most " +
                                                            std::to_string(options->max_restarts)
                                                      : "unbounded"},
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
              table.add_row({to_string(r.seed_mode) +
                                 (r.interrupted ? " (" + std::to_string(r.samples) + " done)" : ""),
                             fixed(100.0 * r.success_rate, 2), fixed(r.mean_time_ms, 4),
                             fixed(r.median_time_ms, 4), fixed(r.p99_time_ms, 4),
                             fixed(r.max_time_ms, 3), fixed(r.mean_iterations, 1)});
            }
            table.print(std::cout);
            stopped();
          }};
}

}  // namespace mjarm::cli
