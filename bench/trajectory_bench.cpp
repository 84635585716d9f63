// Evaluation cost per call of the motion profiles (what a control tick pays): trapezoid, synced
// trapezoid and quintic for 7 joints, SE(3) interpolation, smootherstep; and, for reference, the
// one-off costs of building them, including the exact shortest quintic duration. The profiles and
// instants are those of `mjarm bench traj` (MotionBenchmarkProfiles).
// Run: build/bench_trajectory (built with -DMJARM_BUILD_BENCH=ON --target bench_trajectory).

#include <benchmark/benchmark.h>

#include "mjarm/planning/motion_benchmark.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"

namespace {

using mjarm::motion_benchmark_instants;
using mjarm::MotionBenchmarkProfiles;
constexpr int kJoints = MotionBenchmarkProfiles::kJoints;

// the profiles and instants of `mjarm bench traj` (mjarm/planning/motion_benchmark.hpp)
const MotionBenchmarkProfiles& profiles() {
  static const MotionBenchmarkProfiles m;
  return m;
}

void BM_TrapezoidAt(benchmark::State& state) {
  const mjarm::TrapezoidProfile& profile = profiles().trapezoid;
  const auto t = motion_benchmark_instants(profile.duration());
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(profile.at(t[i++ & 255]));
}
BENCHMARK(BM_TrapezoidAt);

void BM_SyncedTrapezoidAt7(benchmark::State& state) {
  const mjarm::SyncedTrapezoid& move = profiles().synced;
  const auto t = motion_benchmark_instants(move.duration());
  Eigen::VectorXd q(kJoints), qd(kJoints), qdd(kJoints);
  std::size_t i = 0;
  for (auto _ : state) {
    move.at(t[i++ & 255], q, qd, qdd);
    benchmark::DoNotOptimize(q.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SyncedTrapezoidAt7);

void BM_QuinticAt7(benchmark::State& state) {
  const mjarm::QuinticTrajectory& traj = profiles().quintic;
  const auto t = motion_benchmark_instants(traj.duration());
  Eigen::VectorXd q(kJoints), qd(kJoints), qdd(kJoints);
  std::size_t i = 0;
  for (auto _ : state) {
    traj.at(t[i++ & 255], q, qd, qdd);
    benchmark::DoNotOptimize(q.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_QuinticAt7);

void BM_QuinticAt7WithJerk(benchmark::State& state) {
  const mjarm::QuinticTrajectory& traj = profiles().quintic;
  const auto t = motion_benchmark_instants(traj.duration());
  Eigen::VectorXd q(kJoints), qd(kJoints), qdd(kJoints), qddd(kJoints);
  std::size_t i = 0;
  for (auto _ : state) {
    traj.at(t[i++ & 255], q, qd, qdd, qddd);
    benchmark::DoNotOptimize(q.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_QuinticAt7WithJerk);

void BM_Se3InterpolationAt(benchmark::State& state) {
  const mjarm::Se3Interpolation& interpolation = profiles().se3;
  const auto t = motion_benchmark_instants(interpolation.duration());
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(interpolation.at(t[i++ & 255]));
}
BENCHMARK(BM_Se3InterpolationAt);

void BM_SmootherstepAt(benchmark::State& state) {
  const mjarm::SmoothRamp& ramp = profiles().ramp;
  const auto t = motion_benchmark_instants(ramp.duration());
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ramp.at(t[i++ & 255]));
}
BENCHMARK(BM_SmootherstepAt);

// one-off costs (not per tick)
void BM_QuinticBuild7(benchmark::State& state) {
  const MotionBenchmarkProfiles& m = profiles();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        mjarm::QuinticTrajectory::to_rest(m.quintic_start, m.quintic_goal, 1.3));
}
BENCHMARK(BM_QuinticBuild7);

void BM_QuinticShortestDuration7(benchmark::State& state) {
  const MotionBenchmarkProfiles& m = profiles();
  const mjarm::QuinticTrajectory::State end{m.quintic_goal, Eigen::VectorXd::Zero(kJoints),
                                            Eigen::VectorXd::Zero(kJoints)};
  for (auto _ : state)
    benchmark::DoNotOptimize(
        mjarm::shortest_quintic_duration(m.quintic_start, end, m.v_max, m.a_max));
}
BENCHMARK(BM_QuinticShortestDuration7)->Unit(benchmark::kMicrosecond);

}  // namespace
