// The jerk-limited online trajectory generator (trajectory/otg/).
//
// Protocol (also in every benchmark's label):
// - 256 cases drawn once (mjarm::Random seed 2024), 7 DoF each: limits log-uniform (v in
//   [0.2, 4], a in [0.3, 8], j in [0.5, 40]), start and target states uniform inside them
//   (positions in [−3, 3]), a fifth of the states at rest; cycled in order (one iteration =
//   one calculation of all 7 DoF).
// - Cases: JerkLimitedGenerator::calculate (position interface), calculate_velocity, and the
//   one-DoF step 1 (min_time_profile) alone.
// Run: build-<you>/bench_jerk_limited [--benchmark_min_time=0.5]
// `mjarm bench otg` times the same calculation per call (mean, p99) on freshly drawn cases and
// validates every result; docs/trajectory_otg.md keeps the figures.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "mjarm/random.hpp"
#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"

namespace {

constexpr int kCases = 256;
constexpr int kDofs = 7;

struct OtgCases {
  std::vector<std::vector<mjarm::JerkLimits>> limits;
  std::vector<std::vector<mjarm::KinematicState>> start, target;

  OtgCases() {
    mjarm::Random rng(2024);
    const auto u = [](mjarm::Random& r) { return mjarm::uniform(r); };
    auto scale = [&](double lo, double hi) { return lo * std::pow(hi / lo, u(rng)); };
    auto state = [&](const mjarm::JerkLimits& l) {
      mjarm::KinematicState s{6.0 * u(rng) - 3.0, l.velocity * (2.0 * u(rng) - 1.0),
                              l.acceleration * (2.0 * u(rng) - 1.0)};
      if (u(rng) < 0.2) s.v = s.a = 0.0;
      return s;
    };
    for (int c = 0; c < kCases; ++c) {
      limits.emplace_back();
      start.emplace_back();
      target.emplace_back();
      for (int i = 0; i < kDofs; ++i) {
        const mjarm::JerkLimits l{scale(0.2, 4.0), scale(0.3, 8.0), scale(0.5, 40.0)};
        mjarm::KinematicState s, t;
        do s = state(l);
        while (!mjarm::is_startable(s, l));
        do t = state(l);
        while (!mjarm::is_reachable(t, l));
        limits.back().push_back(l);
        start.back().push_back(s);
        target.back().push_back(t);
      }
    }
  }
};

const OtgCases& cases() {
  static const OtgCases c;
  return c;
}

void BM_PositionInterface7Dof(benchmark::State& state) {
  const OtgCases& c = cases();
  std::vector<mjarm::JerkLimitedGenerator> otg;
  for (int k = 0; k < kCases; ++k) otg.emplace_back(c.limits[k]);
  int k = 0, failures = 0;
  for (auto _ : state) {
    const mjarm::OtgResult r = otg[k].calculate(c.start[k], c.target[k]);
    failures +=
        r.status == mjarm::OtgStatus::working || r.status == mjarm::OtgStatus::finished ? 0 : 1;
    benchmark::DoNotOptimize(r);
    k = (k + 1) % kCases;
  }
  state.counters["failures"] = failures;
  state.SetLabel("256 random 7-DoF cases, cycled");
}
BENCHMARK(BM_PositionInterface7Dof)->Unit(benchmark::kMicrosecond);

void BM_VelocityInterface7Dof(benchmark::State& state) {
  const OtgCases& c = cases();
  std::vector<mjarm::JerkLimitedGenerator> otg;
  for (int k = 0; k < kCases; ++k) otg.emplace_back(c.limits[k]);
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(otg[k].calculate_velocity(c.start[k], c.target[k]));
    k = (k + 1) % kCases;
  }
  state.SetLabel("256 random 7-DoF cases, cycled");
}
BENCHMARK(BM_VelocityInterface7Dof)->Unit(benchmark::kMicrosecond);

void BM_MinTimeOneDof(benchmark::State& state) {
  const OtgCases& c = cases();
  mjarm::JerkBlock block;
  int k = 0;
  for (auto _ : state) {
    const int i = k % kDofs, n = k / kDofs;
    benchmark::DoNotOptimize(
        mjarm::min_time_profile(c.start[n][i], c.target[n][i], c.limits[n][i], block));
    k = (k + 1) % (kCases * kDofs);
  }
  state.SetLabel("step 1 of one DoF, 1792 random cases, cycled");
}
BENCHMARK(BM_MinTimeOneDof)->Unit(benchmark::kMicrosecond);

}  // namespace
