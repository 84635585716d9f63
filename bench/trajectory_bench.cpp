// Evaluation cost per call of the motion profiles (what a control tick pays): trapezoid, synced
// trapezoid and quintic for 7 joints, SE(3) interpolation, smootherstep; and, for reference, the
// one-off costs of building them, including the exact shortest quintic duration.
// Run: build/bench_trajectory (built with -DMJARM_BUILD_BENCH=ON --target bench_trajectory).

#include <benchmark/benchmark.h>

#include <array>
#include <random>

#include "mjarm/lie/so3.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace {

constexpr int kJoints = 7;

// 256 seeded instants spread over [0, T] (and a little beyond, where profiles clamp)
std::array<double, 256> instants(double T) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.05 * T, 1.05 * T);
  std::array<double, 256> t{};
  for (double& x : t) x = u(rng);
  return t;
}

Eigen::VectorXd seeded_vector(unsigned seed, double scale) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(kJoints);
  for (int i = 0; i < kJoints; ++i) v[i] = u(rng);
  return v;
}

void BM_TrapezoidAt(benchmark::State& state) {
  const mjarm::TrapezoidProfile profile = mjarm::trap_profile(0.5);
  const auto t = instants(profile.duration());
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(profile.at(t[i++ & 255]));
}
BENCHMARK(BM_TrapezoidAt);

void BM_SyncedTrapezoidAt7(benchmark::State& state) {
  const mjarm::SyncedTrapezoid move(seeded_vector(1, 2.0), seeded_vector(2, 2.0),
                                    Eigen::VectorXd::Constant(kJoints, 1.5),
                                    Eigen::VectorXd::Constant(kJoints, 4.0));
  const auto t = instants(move.duration());
  Eigen::VectorXd q(kJoints), qd(kJoints), qdd(kJoints);
  std::size_t i = 0;
  for (auto _ : state) {
    move.at(t[i++ & 255], q, qd, qdd);
    benchmark::DoNotOptimize(q.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SyncedTrapezoidAt7);

mjarm::QuinticTrajectory blend7() {
  return mjarm::QuinticTrajectory::to_rest(
      {seeded_vector(1, 2.0), seeded_vector(3, 0.5), seeded_vector(4, 2.0)}, seeded_vector(2, 2.0),
      1.3);
}

void BM_QuinticAt7(benchmark::State& state) {
  const mjarm::QuinticTrajectory traj = blend7();
  const auto t = instants(traj.duration());
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
  const mjarm::QuinticTrajectory traj = blend7();
  const auto t = instants(traj.duration());
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
  mjarm::Pose X0, X1;
  X0.R = mjarm::so3::exp(Eigen::Vector3d(0.3, -0.8, 0.2));
  X0.p << 0.4, -0.1, 0.6;
  X1.R = mjarm::so3::exp(Eigen::Vector3d(-1.2, 0.4, 1.9));
  X1.p << 0.1, 0.3, 0.5;
  mjarm::Vector6d V0, A0;
  V0 << 0.2, -0.1, 0.05, 1.5, 0.7, -2.0;
  A0 << -1.0, 0.5, 2.0, 3.0, -4.0, 1.0;
  const mjarm::Se3Interpolation interpolation(X0, V0, A0, X1, 0.8);
  const auto t = instants(0.8);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(interpolation.at(t[i++ & 255]));
}
BENCHMARK(BM_Se3InterpolationAt);

void BM_SmootherstepAt(benchmark::State& state) {
  const mjarm::SmoothRamp ramp(mjarm::SmoothRamp::Kind::smootherstep, 0.4);
  const auto t = instants(0.4);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ramp.at(t[i++ & 255]));
}
BENCHMARK(BM_SmootherstepAt);

// one-off costs (not per tick)
void BM_QuinticBuild7(benchmark::State& state) {
  const mjarm::QuinticTrajectory::State start{seeded_vector(1, 2.0), seeded_vector(3, 0.5),
                                              seeded_vector(4, 2.0)};
  const Eigen::VectorXd goal = seeded_vector(2, 2.0);
  for (auto _ : state)
    benchmark::DoNotOptimize(mjarm::QuinticTrajectory::to_rest(start, goal, 1.3));
}
BENCHMARK(BM_QuinticBuild7);

void BM_QuinticShortestDuration7(benchmark::State& state) {
  const mjarm::QuinticTrajectory::State start{seeded_vector(1, 2.0), seeded_vector(3, 0.5),
                                              seeded_vector(4, 2.0)};
  const mjarm::QuinticTrajectory::State end{seeded_vector(2, 2.0), Eigen::VectorXd::Zero(kJoints),
                                            Eigen::VectorXd::Zero(kJoints)};
  const Eigen::VectorXd v_max = Eigen::VectorXd::Constant(kJoints, 1.5);
  const Eigen::VectorXd a_max = Eigen::VectorXd::Constant(kJoints, 4.0);
  for (auto _ : state)
    benchmark::DoNotOptimize(mjarm::shortest_quintic_duration(start, end, v_max, a_max));
}
BENCHMARK(BM_QuinticShortestDuration7)->Unit(benchmark::kMicrosecond);

}  // namespace
