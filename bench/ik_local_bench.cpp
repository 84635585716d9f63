// Local IK solvers: position DLS on arm6 and pose IK (CLIK) on panda.
//
// Protocol: targets are the FK of 1024 configurations drawn uniformly inside the joint limits
// shrunk by 2 % of each range at both ends (std::mt19937 seed 7), cycled. Seeds: the middle of
// the joint ranges ("centre") or the target's own configuration plus N(0, 0.2 rad) per joint,
// clipped ("nearby"). Default options (position: λ 0.02, α 0.6, tol 1e-4 m; pose: tol 1e-5 m
// and 1e-5 rad). One iteration = one solve with the allocation-free in-place overload. The
// counters `success` (fraction converged) and `iters` (mean iterations) come from one untimed
// pass over all targets; failed solves are timed like any other.
// Run: build-<you>/bench_ik_local [--benchmark_min_time=1]

#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"

namespace {

using mjarm::Chain;
using mjarm::ChainKinematics;
using mjarm::IkResult;
using mjarm::Pose;

constexpr int kTargets = 1024;

/// Targets (FK poses) and seeds for one chain.
struct Problem {
  std::vector<Pose> targets;
  std::vector<Eigen::VectorXd> seeds;
};

Problem make_problem(const Chain& chain, bool nearby) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.2);
  ChainKinematics fk(chain);
  Problem problem;
  for (int t = 0; t < kTargets; ++t) {
    Eigen::VectorXd q(chain.size());
    for (int i = 0; i < chain.size(); ++i) {
      const double margin = 0.02 * (chain.upper()[i] - chain.lower()[i]);
      q[i] = std::uniform_real_distribution<double>(chain.lower()[i] + margin,
                                                    chain.upper()[i] - margin)(rng);
    }
    problem.targets.push_back(fk.update(q));
    Eigen::VectorXd seed = chain.center();
    if (nearby) {
      for (int i = 0; i < chain.size(); ++i) seed[i] = q[i] + noise(rng);
      seed = chain.clamp(seed);
    }
    problem.seeds.push_back(seed);
  }
  return problem;
}

template <class Solver, class Target>
void run(benchmark::State& state, Solver& solver, const Problem& problem, Target target_of) {
  IkResult result;
  // untimed pass: success rate and mean iterations
  int converged = 0;
  long iterations = 0;
  for (int t = 0; t < kTargets; ++t) {
    solver.solve(target_of(problem.targets[t]), problem.seeds[t], result);
    converged += result.ok() ? 1 : 0;
    iterations += result.iterations;
  }
  int t = 0;
  for (auto _ : state) {
    solver.solve(target_of(problem.targets[t]), problem.seeds[t], result);
    benchmark::DoNotOptimize(result.q.data());
    t = (t + 1) % kTargets;
  }
  state.counters["success"] = static_cast<double>(converged) / kTargets;
  state.counters["iters"] = static_cast<double>(iterations) / kTargets;
}

void position_dls_arm6(benchmark::State& state, bool nearby) {
  const Chain chain(mjarm::Robot::bundled("arm6"), "grip");
  mjarm::PositionIk ik(chain);
  const Problem problem = make_problem(chain, nearby);
  run(state, ik, problem, [](const Pose& X) -> Eigen::Vector3d { return X.p; });
}

void pose_ik_panda(benchmark::State& state, bool nearby) {
  const Chain chain(mjarm::Robot::bundled("panda"), "attachment_site");
  mjarm::PoseIk ik(chain);
  const Problem problem = make_problem(chain, nearby);
  run(state, ik, problem, [](const Pose& X) -> const Pose& { return X; });
}

BENCHMARK_CAPTURE(position_dls_arm6, centre, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(position_dls_arm6, nearby, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(pose_ik_panda, centre, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(pose_ik_panda, nearby, true)->Unit(benchmark::kMicrosecond);

}  // namespace
