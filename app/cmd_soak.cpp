// `mjarm soak [--minutes M] [--rounds N] [--seed S] [--json]`: the environments, the replay of a
// recorded session and a batch of pick-and-place trials, round after round, with memory, file
// descriptors and threads sampled; fails on growth, drift, a MuJoCo warning or a divergence
// (protocol in soak/soak.hpp; docs/hardening.md, "The soak").

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/soak/soak.hpp"
#include "output.hpp"

namespace mjarm::cli {

namespace {

Json memory_json(const GrowthReport& g, const MemoryGrowth& m, double bound, double margin) {
  return {{"first_kib", m.first},
          {"min_kib", m.min},
          {"max_kib", m.max},
          {"last_kib", m.last},
          {"warmup_max_kib", m.warmup_max},
          {"slope_kib_per_hour", g.judged ? Json(m.slope) : Json(nullptr)},
          {"max_slope_kib_per_hour", bound},
          {"margin_kib", margin},
          {"growth", m.growth}};
}

Json soak_json(const SoakOptions& o, const SoakResult& r) {
  const GrowthReport& g = r.growth;
  Json rounds = Json::array();
  for (const SoakSample& s : r.samples) {
    Json row = {{"round", s.round}, {"elapsed_s", s.elapsed_s}};
    row.update(fields_to_json(s.process));
    rounds.push_back(std::move(row));
  }
  return {{"status", to_string(r.status)},
          {"seed", o.seed},
          {"rounds", r.rounds},
          {"elapsed_s", r.elapsed_s},
          {"setup_s", r.setup_s},
          {"counts", fields_to_json(r.counts)},
          {"start", fields_to_json(r.start)},
          {"growth",
           {{"warmup_rounds", g.warmup_rounds},
            {"judged", g.judged},
            {"heap", memory_json(g, g.heap, o.limits.max_heap_slope_kib_per_hour,
                                 o.limits.heap_margin_kib)},
            {"rss", memory_json(g, g.rss, o.limits.max_rss_slope_kib_per_hour,
                                o.limits.rss_margin_kib)},
            {"fds_first", g.fds_first},
            {"fds_warmup_max", g.fds_warmup_max},
            {"fds_max", g.fds_max},
            {"fds_last", g.fds_last},
            {"fd_growth", g.fd_growth},
            {"threads_first", g.threads_first},
            {"threads_warmup_max", g.threads_warmup_max},
            {"threads_max", g.threads_max},
            {"threads_last", g.threads_last},
            {"thread_growth", g.thread_growth}}},
          {"mujoco_warnings", r.mujoco_warnings},
          {"logged_warnings", r.logged_warnings},
          {"divergences", r.divergences},
          {"drifts", r.drifts},
          {"replay_digest", r.replay_digest},
          {"recorded_ticks", r.recorded_ticks},
          {"drift_notes", r.drift_notes},
          {"warning_notes", r.warning_notes},
          {"failures", r.failures},
          {"samples", rounds}};
}

void print_soak(std::ostream& os, const SoakOptions& o, const SoakResult& r) {
  const GrowthReport& g = r.growth;
  const SoakCounts& c = r.counts;
  const auto mib = [](double v) { return fixed(v / 1024.0, 1) + " MiB"; };
  const auto slope = [&](const MemoryGrowth& m, double bound, double margin) {
    if (!g.judged)
      return "not judged (" + std::to_string(g.samples - g.warmup_rounds) +
             " rounds after the warm-up, " + std::to_string(kMinJudgedRounds) + " needed)";
    return fixed(m.slope, 0) + " KiB/h after the warm-up (bound " + fixed(bound, 0) +
           "); last − warm-up max " + fixed(m.last - m.warmup_max, 0) + " KiB (margin " +
           fixed(margin, 0) + ")";
  };
  // the heap in KiB (under a MiB), the RSS in MiB
  const auto figures = [&](const MemoryGrowth& m, double start, bool in_kib) {
    const auto f = [&](double v) { return in_kib ? fixed(v, 0) + " KiB" : mib(v); };
    return f(m.first) + " first, " + f(m.min) + " min, " + f(m.max) + " max, " + f(m.last) +
           " last (" + f(start) + " at start)";
  };
  print_fields(
      os,
      {{"soak", std::string(to_string(r.status)) + " (seed " + std::to_string(o.seed) + ")"},
       {"rounds", std::to_string(r.rounds) + " in " + fixed(r.elapsed_s / 60.0, 2) +
                      " min (warm-up " + std::to_string(g.warmup_rounds) + "; set-up " +
                      fixed(r.setup_s, 1) + " s)"},
       {"environments", std::to_string(c.env_runs) + " runs, " + std::to_string(c.env_episodes) +
                            " episodes, " + std::to_string(c.env_steps) + " steps; " +
                            std::to_string(c.vector_steps) + " vectorized steps"},
       {"replays", std::to_string(c.replays) + " of the bimanual lift (" +
                       std::to_string(r.recorded_ticks) + " ticks), " +
                       std::to_string(c.replay_ticks) + " ticks; final state " + r.replay_digest},
       {"trials", std::to_string(c.trials) + " pick-and-place, " +
                      std::to_string(c.trial_successes) + " successes"},
       {"heap in use", figures(g.heap, r.start.heap_kib, true)},
       {"heap slope", slope(g.heap, o.limits.max_heap_slope_kib_per_hour,
                            o.limits.heap_margin_kib)},
       {"resident memory", figures(g.rss, r.start.rss_kib, false)},
       {"RSS slope",
        slope(g.rss, o.limits.max_rss_slope_kib_per_hour, o.limits.rss_margin_kib)},
       {"file descriptors", std::to_string(g.fds_first) + " first, " +
                                std::to_string(g.fds_warmup_max) + " warm-up max, " +
                                std::to_string(g.fds_max) + " max, " +
                                std::to_string(g.fds_last) + " last (" +
                                std::to_string(r.start.fds) + " at start)"},
       {"threads", std::to_string(g.threads_first) + " first, " + std::to_string(g.threads_max) +
                       " max, " + std::to_string(g.threads_last) + " last"},
       {"MuJoCo warnings", std::to_string(r.mujoco_warnings) + " counted, " +
                               std::to_string(r.logged_warnings) + " logged"},
       {"divergences", std::to_string(r.divergences)},
       {"drift", std::to_string(r.drifts) + " results differing from round 1's"}});
  for (const std::string& n : r.drift_notes) os << "drift: " << n << '\n';
  for (const std::string& n : r.warning_notes) os << "warning: " << n << '\n';
  for (const std::string& f : r.failures) os << "failed: " << f << '\n';
}

}  // namespace

Command add_soak_command(CLI::App& root) {
  struct Options {
    SoakOptions soak;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "soak",
      "run the learning environments, the replay of a recorded bimanual session and a batch of "
      "seeded pick-and-place trials round after round, sampling resident memory, file "
      "descriptors and threads after each round; fails on growth, on a result that drifts from "
      "the first round's, and on any MuJoCo warning or divergence");
  SoakOptions& s = o->soak;
  app->add_option("--minutes", s.minutes, "wall-clock length: no round starts after it [min]")
      ->check(number_in(1e-3, 7.0 * 24 * 60))
      ->capture_default_str();
  app->add_option("--rounds", s.rounds, "stop after this many rounds (0: --minutes alone)")
      ->check(count_in(0, 1000000))
      ->capture_default_str();
  app->add_option("--seed", s.seed, "seed of the actions, episodes and trials")
      ->check(non_negative_integer())
      ->capture_default_str();
  app->add_option("--tasks", s.tasks, "environment tasks to run (default: every task)")
      ->check(CLI::IsMember(env_task_names()));
  app->add_option("--episodes", s.episodes, "episodes per task and action space per round")
      ->check(count_in(1, 1000))
      ->capture_default_str();
  app->add_option("--trials", s.trials, "pick-and-place trials per round")
      ->check(count_in(1, 1000))
      ->capture_default_str();
  app->add_option("--vector-task", s.vector_task, "task of the vectorized batch")
      ->check(CLI::IsMember(env_task_names()))
      ->capture_default_str();
  app->add_option("--warmup", s.limits.warmup_rounds, "rounds before growth is judged")
      ->check(count_in(1, 1000000))
      ->capture_default_str();
  app->add_option("--max-heap-slope", s.limits.max_heap_slope_kib_per_hour,
                  "heap-in-use growth bound after the warm-up [KiB/h]")
      ->check(number_in(0.0, 1e12))
      ->capture_default_str();
  app->add_option("--heap-margin", s.limits.heap_margin_kib,
                  "heap in use the last round may hold above the warm-up's largest [KiB]")
      ->check(number_in(0.0, 1e12))
      ->capture_default_str();
  app->add_option("--max-rss-slope", s.limits.max_rss_slope_kib_per_hour,
                  "memory growth bound after the warm-up [KiB/h]")
      ->check(number_in(0.0, 1e12))
      ->capture_default_str();
  app->add_option("--rss-margin", s.limits.rss_margin_kib,
                  "memory the last round may hold above the warm-up's largest [KiB]")
      ->check(number_in(0.0, 1e12))
      ->capture_default_str();
  // faults made on purpose, for the tests of the checks: not in --help
  app->add_option("--inject-leak-kib", s.inject.leak_kib_per_round)
      ->check(count_in(0, 1 << 20))
      ->group("");
  app->add_option("--inject-fds", s.inject.fds_per_round)->check(count_in(0, 100))->group("");
  app->add_option("--inject-drift-from", s.inject.drift_from_round)
      ->check(count_in(0, 1000000))
      ->group("");
  add_json_flag(*app, o->json);

  return {app, [o] {
            SoakOptions options = o->soak;
            const bool by_rounds = options.rounds > 0;
            Progress progress(by_rounds ? "soak (rounds)" : "soak (seconds)",
                              by_rounds ? options.rounds
                                        : std::max<std::int64_t>(
                                              1, std::llround(60.0 * options.minutes)),
                              stderr_is_terminal());  // on stderr: --json too
            options.progress = [&progress, by_rounds](int round, double elapsed_s) {
              progress.update(by_rounds ? std::max(0, round - 1)
                                        : static_cast<std::int64_t>(elapsed_s));
            };
            const InterruptGuard interrupts;  // Ctrl-C / SIGTERM: the figures of the rounds done
            options.stop = [] { return interrupt_requested(); };
            const SoakResult r = run_soak(options);
            progress.finish();
            if (o->json)
              print_json(soak_json(options, r));
            else
              print_soak(std::cout, options, r);
            if (r.status == SoakStatus::interrupted)
              throw InterruptedError("soak: interrupted in round " +
                                         std::to_string(r.rounds + 1) + " after " +
                                         std::to_string(r.rounds) + " whole rounds (" +
                                         fixed(r.elapsed_s, 1) + " s)",
                                     interrupt_signal());
            if (r.status == SoakStatus::failed) {
              std::string text = "soak failed:";
              for (const std::string& f : r.failures) text += " " + f + ";";
              text.pop_back();
              throw Error(text);
            }
          }};
}

}  // namespace mjarm::cli
