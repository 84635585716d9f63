// Timings of the SE(3) maps used in every IK iteration and control tick: exp, log, dexp⁻¹ and
// its time derivative. Run: build/bench_lie (built with -DMJARM_BUILD_BENCH=ON).

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/se3_jacobian.hpp"

namespace {

// a fixed, seeded set of twists with ‖ω‖ < π so every call takes the general branch
std::vector<mjarm::Vector6d> make_twists() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<mjarm::Vector6d> twists(256);
  for (auto& xi : twists) {
    for (int i = 0; i < 6; ++i) xi(i) = u(rng);
  }
  return twists;
}

void BM_Se3Exp(benchmark::State& state) {
  const auto twists = make_twists();
  std::size_t i = 0;
  for (auto _ : state) {
    mjarm::Pose X = mjarm::se3::exp(twists[i++ & 255]);
    benchmark::DoNotOptimize(X);
  }
}
BENCHMARK(BM_Se3Exp);

void BM_Se3Log(benchmark::State& state) {
  std::vector<mjarm::Pose> poses;
  for (const auto& xi : make_twists()) poses.push_back(mjarm::se3::exp(xi));
  std::size_t i = 0;
  for (auto _ : state) {
    mjarm::Vector6d xi = mjarm::se3::log(poses[i++ & 255]);
    benchmark::DoNotOptimize(xi);
  }
}
BENCHMARK(BM_Se3Log);

void BM_Se3LeftJacobianInverse(benchmark::State& state) {
  const auto twists = make_twists();
  std::size_t i = 0;
  for (auto _ : state) {
    mjarm::Matrix6d J = mjarm::se3::left_jacobian_inverse(twists[i++ & 255]);
    benchmark::DoNotOptimize(J);
  }
}
BENCHMARK(BM_Se3LeftJacobianInverse);

void BM_Se3LeftJacobianInverseDerivative(benchmark::State& state) {
  const auto twists = make_twists();
  std::size_t i = 0;
  for (auto _ : state) {
    mjarm::Matrix6d J =
        mjarm::se3::left_jacobian_inverse_derivative(twists[i & 255], twists[(i + 1) & 255]);
    ++i;
    benchmark::DoNotOptimize(J);
  }
}
BENCHMARK(BM_Se3LeftJacobianInverseDerivative);

}  // namespace
