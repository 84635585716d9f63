#include "mjarm/soak/soak.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>

#include "mjarm/env/environment.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/env/vector_environment.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/mujoco_library.hpp"
#include "mjarm/random.hpp"
#include "mjarm/tasks/pick_place/trials.hpp"
#include "mjarm/teleop/bimanual_lift.hpp"
#include "mjarm/teleop/session_log.hpp"

namespace mjarm {
namespace {

constexpr std::size_t kMaxNotes = 20;

// 64-bit FNV-1a over the bytes of the values added: equal fingerprints, equal bits
struct Fingerprint {
  std::uint64_t hash = 1469598103934665603ull;
  void bytes(const void* data, std::size_t size) noexcept {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ b[i]) * 1099511628211ull;
  }
  void add(double v) noexcept { bytes(&v, sizeof v); }
  void add(std::int64_t v) noexcept { bytes(&v, sizeof v); }
  void add(std::span<const double> v) noexcept { bytes(v.data(), v.size_bytes()); }
};

std::int64_t warning_total(const mjData& d) noexcept {
  std::int64_t n = 0;
  for (int w = 0; w < mjNWARNING; ++w) n += d.warning[w].number;
  return n;
}

void note(std::vector<std::string>& notes, std::string text) {
  if (notes.size() < kMaxNotes) notes.push_back(std::move(text));
}

// the wall clock since the soak started, progress and the stop request
struct SoakPace {
  const SoakOptions& options;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  int round = 0;
  bool stopped = false;

  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  /// Reports progress; true when the soak is to stop now.
  bool tick() {
    if (options.progress) options.progress(round, elapsed());
    stopped = stopped || (options.stop && options.stop());
    return stopped;
  }
};

// the faults injected on purpose (SoakInjection), released when the soak ends
struct InjectedFaults {
  std::vector<std::unique_ptr<char[]>> blocks;
  std::vector<int> fds;
  ~InjectedFaults() {
    for (const int fd : fds) ::close(fd);
  }
  void add(const SoakInjection& inject) {
    if (inject.leak_kib_per_round > 0) {
      const std::size_t size = static_cast<std::size_t>(inject.leak_kib_per_round) * 1024;
      blocks.emplace_back(new char[size]);
      // written, so that every page is resident
      std::memset(blocks.back().get(), 0x5a, size);
      volatile char sink = blocks.back()[size - 1];
      (void)sink;
    }
    for (int k = 0; k < inject.fds_per_round; ++k) {
      const int fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
      if (fd < 0) throw Error("soak: cannot open /dev/null for the injected descriptor");
      fds.push_back(fd);
    }
  }
};

// what the parts of one round compare with round 1
struct RoundPrints {
  std::vector<std::uint64_t> env;  // one per environment run, in run order
  std::vector<double> replay_state;
  std::vector<PickPlaceReport> trials;
};

class SoakRunner {
 public:
  SoakRunner(const SoakOptions& options, SoakResult& result, SoakPace& pace)
      : options_(options), result_(result), pace_(pace) {}

  void record_session() {
    const Robot robot = Robot::bundled("dual_arm_box");
    TeleopSession session(robot, TeleopOptions{});
    SessionRecorder recorder(session);
    const BimanualLiftResult lift = run_bimanual_lift(recorder);
    if (!lift.success) throw Error("soak: the bimanual lift to replay failed: " + lift.failure);
    log_ = recorder.log();
    result_.recorded_ticks = static_cast<int>(log_.ticks);
    warnings(session.simulation().data(), "recording the bimanual lift");
  }

  /// One round; false when the stop request cut it short.
  bool round() {
    RoundPrints prints;
    const bool drift = options_.inject.drift_from_round > 0 &&
                       pace_.round >= options_.inject.drift_from_round;
    if (!environments(prints, drift) || !vector_environment(prints, drift) ||
        !replay(prints, drift) || !trials(prints, drift))
      return false;
    if (pace_.round == 1) first_ = std::move(prints);
    return true;
  }

 private:
  const SoakOptions& options_;
  SoakResult& result_;
  SoakPace& pace_;
  SessionLog log_;
  RoundPrints first_;

  bool first_round() const { return pace_.round == 1; }

  void warnings(const mjData& d, const std::string& where) {
    const std::int64_t n = warning_total(d);
    if (n == 0) return;
    result_.mujoco_warnings += n;
    std::string kinds;
    for (int w = 0; w < mjNWARNING; ++w)
      if (d.warning[w].number > 0)
        kinds += (kinds.empty() ? "" : ", ") + std::string(mju_warningText(w, d.warning[w].lastinfo)) +
                 " ×" + std::to_string(d.warning[w].number);
    note(result_.warning_notes, "round " + std::to_string(pace_.round) + ", " + where + ": " + kinds);
  }

  void compare_env(RoundPrints& prints, std::uint64_t hash, const std::string& what) {
    const std::size_t k = prints.env.size();
    prints.env.push_back(hash);
    if (first_round() || k >= first_.env.size() || first_.env[k] == hash) return;
    ++result_.drifts;
    note(result_.drift_notes, "round " + std::to_string(pace_.round) + ", " + what +
                                  ": rewards or final observation differ from round 1's");
  }

  bool environments(RoundPrints& prints, bool drift) {
    for (const std::string& task : options_.tasks.empty() ? env_task_names() : options_.tasks) {
      for (const ActionSpace space : action_spaces()) {
        const std::string what = task + " (" + to_string(space) + ")";
        const std::uint64_t seed =
            splitmix64(options_.seed * 1000003u + prints.env.size());  // same each round
        EnvironmentOptions eo;
        eo.action_space = space;
        eo.seed = seed;
        Environment env(task, eo);
        ++result_.counts.env_runs;
        const ArraySpec& spec = env.action_spec();
        std::vector<double> action(static_cast<std::size_t>(spec.size()));
        Random rng(seed);
        Fingerprint print;
        for (int episode = 0; episode < options_.episodes; ++episode) {
          TimeStep ts = env.reset(splitmix64(seed + static_cast<std::uint64_t>(episode) + 1));
          bool first_action = true;
          while (!ts.last()) {
            for (std::size_t j = 0; j < action.size(); ++j) {
              const auto i = static_cast<Eigen::Index>(j);
              const double lo = std::isfinite(spec.minimum[i]) ? spec.minimum[i] : -1.0;
              const double hi = std::isfinite(spec.maximum[i]) ? spec.maximum[i] : 1.0;
              action[j] = uniform(rng, lo, hi);
              if (drift && first_action) action[j] = lo + hi - action[j];  // mirrored
            }
            first_action = false;
            ts = env.step(action);
            ++result_.counts.env_steps;
            print.add(*ts.reward);
            if (result_.counts.env_steps % 50 == 0 && pace_.tick()) return false;
          }
          ++result_.counts.env_episodes;
          print.add(ts.observation.values());
          print.add(static_cast<std::int64_t>(env.steps()));
          if (ts.end == EpisodeEnd::diverged) {
            ++result_.divergences;
            note(result_.warning_notes,
                 "round " + std::to_string(pace_.round) + ", " + what + ", episode " +
                     std::to_string(episode + 1) + ": diverged (" +
                     describe(env.simulation().model(), env.simulation().fault()) + ")");
          }
          // before the next reset, which zeroes the counters
          warnings(env.simulation().data(), what + ", episode " + std::to_string(episode + 1));
        }
        compare_env(prints, print.hash, what);
      }
    }
    return !pace_.tick();
  }

  bool vector_environment(RoundPrints& prints, bool drift) {
    EnvironmentOptions eo;
    eo.seed = splitmix64(options_.seed + 17);
    VectorEnvironment batch(options_.vector_task, eo, options_.vector_envs,
                            options_.vector_threads);
    const int n = batch.size();
    const std::string what = "vectorized " + options_.vector_task + " ×" + std::to_string(n);
    const ArraySpec& spec = batch.action_spec();
    const auto width = static_cast<std::size_t>(spec.size());
    std::vector<double> actions(width * static_cast<std::size_t>(n));
    std::vector<std::int64_t> seen(static_cast<std::size_t>(n), 0);
    Random rng(eo.seed);
    Fingerprint print;
    batch.reset();
    for (int i = 0; i < n; ++i) {
      seen[static_cast<std::size_t>(i)] = warning_total(batch.environment(i).simulation().data());
      result_.mujoco_warnings += seen[static_cast<std::size_t>(i)];
    }
    const int steps = batch.environment(0).step_limit();
    for (int k = 0; k < steps; ++k) {
      for (std::size_t j = 0; j < actions.size(); ++j) {
        const auto i = static_cast<Eigen::Index>(j % width);
        const double lo = std::isfinite(spec.minimum[i]) ? spec.minimum[i] : -1.0;
        const double hi = std::isfinite(spec.maximum[i]) ? spec.maximum[i] : 1.0;
        actions[j] = uniform(rng, lo, hi);
        if (drift && k == 0 && j < width) actions[j] = lo + hi - actions[j];  // row 0 mirrored
      }
      batch.step(actions);
      result_.counts.vector_steps += n;
      print.add(batch.rewards());
      for (int i = 0; i < n; ++i) {
        const auto u = static_cast<std::size_t>(i);
        const mjData& d = batch.environment(i).simulation().data();
        // a FIRST row was reset (counters zeroed) after its LAST row was read
        const std::int64_t total = warning_total(d);
        const std::int64_t added = batch.step_types()[u] == StepType::first ? total : total - seen[u];
        seen[u] = total;
        if (added > 0) {
          result_.mujoco_warnings += added;
          note(result_.warning_notes, "round " + std::to_string(pace_.round) + ", " + what +
                                          ", environment " + std::to_string(i) + ": " +
                                          std::to_string(added) + " MuJoCo warnings");
        }
        if (batch.step_types()[u] == StepType::last && batch.ends()[u] == EpisodeEnd::diverged) {
          ++result_.divergences;
          note(result_.warning_notes, "round " + std::to_string(pace_.round) + ", " + what +
                                          ", environment " + std::to_string(i) + ": diverged");
        }
      }
      if ((k + 1) % 50 == 0 && pace_.tick()) return false;
    }
    print.add(batch.observations());
    compare_env(prints, print.hash, what);
    return !pace_.tick();
  }

  bool replay(RoundPrints& prints, bool drift) {
    const Robot robot = Robot::bundled("dual_arm_box");
    SessionLog log = log_;
    if (drift) {
      for (SessionEvent& e : log.events)
        if (e.kind == SessionEvent::Kind::targets && !e.targets.hands.empty())
          e.targets.hands.front().X_WT.p.x() += 1e-3;
    }
    SessionReplay replay(robot, log);
    while (replay.step()) {
      if (replay.ticks() % 100 == 0 && pace_.tick()) return false;
    }
    const ReplayResult r = replay.result();
    ++result_.counts.replays;
    result_.counts.replay_ticks += r.ticks;
    const Simulation& sim = replay.session().simulation();
    const mjModel& m = sim.model();
    const mjData& d = sim.data();
    const std::string where = "replay of the bimanual lift";
    warnings(d, where);
    if (r.stats.faulted) {
      ++result_.divergences;
      note(result_.warning_notes,
           "round " + std::to_string(pace_.round) + ", " + where + ": " + r.stats.fault);
    }
    std::vector<double>& state = prints.replay_state;
    state.push_back(d.time);
    state.insert(state.end(), d.qpos, d.qpos + m.nq);
    state.insert(state.end(), d.qvel, d.qvel + m.nv);
    state.insert(state.end(), d.act, d.act + m.na);
    if (first_round()) result_.replay_digest = r.digest;
    const std::string round = "round " + std::to_string(pace_.round) + ", " + where;
    if (!r.matches) {
      ++result_.drifts;
      note(result_.drift_notes,
           round + ": final state " + r.digest + ", recorded " + log_.digest);
    }
    if (!first_round() &&
        (state.size() != first_.replay_state.size() ||
         std::memcmp(state.data(), first_.replay_state.data(), sizeof(double) * state.size()) != 0)) {
      ++result_.drifts;
      note(result_.drift_notes, round + ": final state " + r.digest +
                                    " differs from the first replay's " + result_.replay_digest);
    }
    return !pace_.tick();
  }

  bool trials(RoundPrints& prints, bool drift) {
    PickPlaceBatchOptions batch;
    batch.base.seed = options_.seed;
    if (drift) batch.base.ranges.mass[1] += 1e-6;
    batch.trials = options_.trials;
    batch.threads = options_.trial_threads;
    // from the worker that finished a trial, one call at a time
    batch.on_progress = [this](int) {
      if (options_.progress) options_.progress(pace_.round, pace_.elapsed());
    };
    const std::uint64_t logged = mujoco_warning_count();
    PickPlaceBatch done = run_pick_place_trials(batch);
    result_.counts.trials += static_cast<std::int64_t>(done.reports.size());
    result_.counts.trial_successes += done.summary.successes;
    if (done.interrupted || pace_.tick()) return false;
    // the trials' simulations are their own: their first warning of a kind is logged
    if (mujoco_warning_count() > logged)
      note(result_.warning_notes, "round " + std::to_string(pace_.round) +
                                      ", pick-and-place trials: " +
                                      std::to_string(mujoco_warning_count() - logged) +
                                      " MuJoCo warnings logged");
    for (std::size_t k = 0; k < done.reports.size(); ++k) {
      const PickPlaceReport& t = done.reports[k];
      const std::string what = "round " + std::to_string(pace_.round) +
                               ", pick-and-place seed " + std::to_string(t.trial.seed);
      if (t.failure == PickPlaceFailure::diverged || t.failure == PickPlaceFailure::bad_command) {
        ++result_.divergences;
        note(result_.warning_notes, what + ": " + t.reason);
      }
      if (first_round() || k >= first_.trials.size()) continue;
      const PickPlaceReport& f = first_.trials[k];
      const auto same = [](double a, double b) {
        return std::memcmp(&a, &b, sizeof a) == 0;
      };
      if (t.success != f.success || t.failure != f.failure || t.run.ticks != f.run.ticks ||
          !same(t.run.end_time, f.run.end_time) || !same(t.placement_error, f.placement_error) ||
          !same(t.cycle_time, f.cycle_time)) {
        ++result_.drifts;
        note(result_.drift_notes,
             what + ": " + (t.success ? "success" : to_string(t.failure)) + ", placement error " +
                 std::to_string(t.placement_error) + " m after " + std::to_string(t.run.ticks) +
                 " ticks; round 1: " + (f.success ? "success" : to_string(f.failure)) + ", " +
                 std::to_string(f.placement_error) + " m after " + std::to_string(f.run.ticks));
      }
    }
    prints.trials = std::move(done.reports);
    return true;
  }
};

void judge(const SoakOptions& options, SoakResult& r) {
  const GrowthReport& g = r.growth;
  const auto memory = [&](const MemoryGrowth& m, const char* what, double bound, double margin) {
    if (!m.growth) return;
    char text[320];
    std::snprintf(text, sizeof text,
                  "%s grows: %.0f KiB/h after the %d-round warm-up (bound %.0f) and the last "
                  "round's %.0f KiB is %.0f KiB above the warm-up's largest (margin %.0f)",
                  what, m.slope, g.warmup_rounds, bound, m.last, m.last - m.warmup_max, margin);
    r.failures.emplace_back(text);
  };
  memory(g.heap, "heap in use", options.limits.max_heap_slope_kib_per_hour,
         options.limits.heap_margin_kib);
  memory(g.rss, "resident memory", options.limits.max_rss_slope_kib_per_hour,
         options.limits.rss_margin_kib);
  if (g.fd_growth)
    r.failures.push_back("open file descriptors grow: " + std::to_string(g.fds_max) +
                         " after the warm-up, at most " + std::to_string(g.fds_warmup_max) +
                         " during it");
  if (g.thread_growth)
    r.failures.push_back("threads grow: " + std::to_string(g.threads_max) +
                         " after the warm-up, at most " + std::to_string(g.threads_warmup_max) +
                         " during it");
  if (r.drifts > 0)
    r.failures.push_back(std::to_string(r.drifts) + " results drifted from round 1's (" +
                         (r.drift_notes.empty() ? std::string("?") : r.drift_notes.front()) + ")");
  if (r.mujoco_warnings > 0 || r.logged_warnings > 0)
    r.failures.push_back(std::to_string(r.mujoco_warnings) + " MuJoCo warnings counted, " +
                         std::to_string(r.logged_warnings) + " logged (" +
                         (r.warning_notes.empty() ? std::string("see stderr")
                                                  : r.warning_notes.front()) +
                         ")");
  if (r.divergences > 0)
    r.failures.push_back(std::to_string(r.divergences) + " divergences");
}

}  // namespace

void SoakOptions::check() const { check_fields(*this); }

SoakResult run_soak(const SoakOptions& options) {
  options.check();
  // an unknown name is an error before any work
  (void)make_env_task(options.vector_task);
  for (const std::string& task : options.tasks) (void)make_env_task(task);
  SoakResult result;
  result.start = sample_process();
  SoakPace pace{options};
  const std::uint64_t logged = mujoco_warning_count();
  InjectedFaults injected;
  SoakRunner runner(options, result, pace);
  runner.record_session();
  result.setup_s = pace.elapsed();
  bool interrupted = pace.tick();
  for (int round = 1; !interrupted; ++round) {
    if (options.rounds > 0 && round > options.rounds) break;
    if (round > 1 && pace.elapsed() >= 60.0 * options.minutes) break;
    pace.round = round;
    if (!runner.round()) {
      interrupted = true;
      break;
    }
    injected.add(options.inject);
    result.rounds = round;
    result.samples.push_back({round, pace.elapsed(), sample_process()});
  }
  result.elapsed_s = pace.elapsed();
  result.logged_warnings = static_cast<std::int64_t>(mujoco_warning_count() - logged);
  result.growth = check_growth(result.samples, options.limits);
  judge(options, result);
  result.status = interrupted             ? SoakStatus::interrupted
                  : result.failures.empty() ? SoakStatus::ok
                                            : SoakStatus::failed;
  return result;
}

}  // namespace mjarm
