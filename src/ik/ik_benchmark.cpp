#include "mjarm/ik/ik_benchmark.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

/// Uniform configurations inside the limits from a seeded generator (53-bit doubles).
class ConfigurationSampler {
 public:
  ConfigurationSampler(const Chain& chain, std::uint64_t seed)
      : rng_(seed), lower_(chain.lower()), upper_(chain.upper()) {
    const mjModel& m = chain.robot().model();
    for (int i = 0; i < chain.size(); ++i) {
      const double half = m.jnt_type[chain.joint_id(i)] == mjJNT_HINGE ? std::numbers::pi : 1.0;
      if (!std::isfinite(lower_[i])) lower_[i] = -half;
      if (!std::isfinite(upper_[i])) upper_[i] = half;
    }
  }

  void draw(Eigen::VectorXd& q) {
    for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = uniform(rng_, lower_[i], upper_[i]);
  }

 private:
  Random rng_;
  Eigen::VectorXd lower_, upper_;
};

/// CPU time consumed by the calling thread [ms].
double thread_cpu_ms() noexcept { return 1e3 * thread_cpu_seconds(); }

constexpr double kCpuModeWallFactor = 20.0;

}  // namespace

IkBenchmarkSolver global_ik_solver(const Chain& chain, const GlobalIkOptions& options) {
  auto solver = std::make_shared<GlobalIk>(chain, options);
  IkBenchmarkSolver s;
  s.name =
      std::string("global_ik(") + to_string(options.methods) + ", " + to_string(options.mode) + ")";
  // one result kept across calls: after the first solve no allocation happens in the solver
  auto result = std::make_shared<IkResult>();
  s.solve = [solver, result](const Pose& X_WT, const Eigen::VectorXd& q_seed) {
    solver->solve(X_WT, q_seed, *result);
    return *result;
  };
  return s;
}

IkBenchmarkResult run_ik_benchmark(const Chain& chain, const IkBenchmarkSolver& solver,
                                   const IkBenchmarkOptions& options) {
  check_fields(options);
  if (!solver.solve) throw Error("IK benchmark: solver '" + solver.name + "' has no function");
  check_tolerance(options.tolerance);
  if (!(options.timeout.count() > 0.0) || !std::isfinite(options.timeout.count())) {
    throw Error("IK benchmark: timeout must be finite and positive, got " +
                number_text(options.timeout.count()) + " s");
  }

  const int n = chain.size();
  ChainKinematics kin(chain);
  ConfigurationSampler targets(chain, options.seed);
  // the random seeds come from their own stream so that the targets match the mid-range run
  ConfigurationSampler seeds(chain, options.seed ^ 0x9E3779B97F4A7C15ull);
  const Eigen::VectorXd center = chain.center();
  Eigen::VectorXd q_target(n), q_seed(n);
  std::vector<double> times_ms(static_cast<std::size_t>(options.samples));

  IkBenchmarkResult out;
  out.solver = solver.name;
  out.robot = chain.robot().name();
  out.frame = chain.frame().name;
  out.seed_mode = options.seed_mode;
  out.clock = options.clock;
  const bool cpu_clock = options.clock == IkBenchmarkClock::thread_cpu;
  out.timeout_ms = std::chrono::duration<double, std::milli>(options.timeout).count();
  out.samples = options.samples;
  double iterations = 0.0;
  for (int s = 0; s < options.samples; ++s) {
    if (options.stop && options.stop()) {
      out.interrupted = true;
      out.samples = s;
      times_ms.resize(static_cast<std::size_t>(s));
      break;
    }
    targets.draw(q_target);
    const Pose X_WT = kin.update(q_target);
    if (options.seed_mode == IkSeedMode::random) {
      seeds.draw(q_seed);
    } else {
      q_seed = center;
    }

    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_clock ? thread_cpu_ms() : 0.0;
    const IkResult r = solver.solve(X_WT, q_seed);
    const double c1 = cpu_clock ? thread_cpu_ms() : 0.0;
    const auto t1 = std::chrono::steady_clock::now();
    double elapsed_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    bool in_budget = true;
    if (cpu_clock) {
      // over the CPU budget: the solve would have been stopped there, unsolved
      elapsed_ms = std::min(c1 - c0, out.timeout_ms);
      in_budget = c1 - c0 <= out.timeout_ms;
    }
    times_ms[static_cast<std::size_t>(s)] = elapsed_ms;

    // judge by our own forward kinematics, not by the solver's word
    bool ok = in_budget && r.q.size() == n && r.q.allFinite() && chain.within_limits(r.q);
    if (ok) ok = within_tolerance(target_frame_error(kin.update(r.q), X_WT), options.tolerance);
    out.successes += ok ? 1 : 0;
    out.solver_converged += r.status == IkStatus::converged ? 1 : 0;
    iterations += r.iterations;
    if (options.progress) options.progress(s + 1, options.samples);
  }

  if (out.samples == 0) return out;  // stopped before the first sample: no figures
  out.success_rate = static_cast<double>(out.successes) / out.samples;
  double total = 0.0;
  for (double t : times_ms) total += t;
  out.mean_time_ms = total / out.samples;
  out.mean_iterations = iterations / out.samples;
  std::sort(times_ms.begin(), times_ms.end());
  const std::size_t mid = times_ms.size() / 2;
  out.median_time_ms =
      times_ms.size() % 2 == 1 ? times_ms[mid] : 0.5 * (times_ms[mid - 1] + times_ms[mid]);
  out.p99_time_ms = nearest_rank(times_ms, 0.99);
  out.max_time_ms = times_ms.back();
  return out;
}

IkBenchmarkResult run_ik_benchmark(const Chain& chain, const IkBenchmarkOptions& options) {
  GlobalIkOptions global;
  global.timeout = options.timeout;
  if (options.clock == IkBenchmarkClock::thread_cpu) {
    // the wall-clock safety margin saturates instead of overflowing to inf
    global.timeout = std::min(global.timeout * kCpuModeWallFactor,
                              std::chrono::duration<double>(std::numeric_limits<double>::max()));
  }
  global.tolerance = options.tolerance;
  global.max_restarts = options.max_restarts;
  global.seed = options.seed;
  // the protocol measures the numeric search; the closed form has its own benchmark
  // (`mjarm bench analytic-ik`)
  global.analytic = false;
  return run_ik_benchmark(chain, global_ik_solver(chain, global), options);
}

}  // namespace mjarm
