// Joint-space dynamics: the cost of inverse dynamics and of the quantities a torque controller
// reads each tick, on a state MuJoCo has already computed.
//
// Protocol (also in every benchmark's label):
// - State: the bundled arm (position flavour; actuators do not matter here) at 256 random
//   configurations inside the joint limits with joint speeds uniform in ±2 rad/s (std::mt19937
//   seed 2024), each prepared once with mj_forward on its own mjData; the iterations cycle them.
//   q̈ on the chain's dofs uniform in ±5 rad/s².
// - MjInverse/<robot>: what a controller pays to get τ from MuJoCo's inverse dynamics: copy
//   qpos, qvel, qacc into a scratch mjData and run mj_inverse (position stage, velocity stage,
//   inverse constraint, RNE + armature).
// - ChainInverseDynamics/<robot>: mjarm's path on the up-to-date state: τ = M·q̈ + h with
//   MuJoCo's sparse mj_mulM on M plus qfrc_bias (ChainDynamics::inverse_dynamics). Never
//   writes the state.
// - MjRne/<robot>: mj_rne with accelerations on an up-to-date state (the Newton-Euler pass
//   inside mj_inverse, without armature), for reference.
// - ChainDynamicsUpdate/<robot>: ChainDynamics::update — M block, h, g, pose, J, velocity and
//   J̇·q̇ of the end effector.
// - TaskSpaceUpdate/<robot>: TaskSpaceDynamics::update on the full 6-row Jacobian — Cholesky
//   of M, Λ by the Cholesky fast path (the 6×6 eigendecomposition only for near-singular
//   states); J̄, M⁻¹ and N are computed on demand and not timed (J̄ since 2026-11-27).
// - ObserverUpdate/<method>: MomentumObserver::update on the iiwa14 (7 dofs) after its
//   ChainDynamics::update (not timed: a controller has it already) — p = M·q̇, Cᵀ·q̇ (0: exact
//   subtree momentum, 1: directional difference of M on a scratch mjData), both PI channels,
//   the friction model, the 6×6 LDLT of J·Jᵀ + εI and both wrench estimates.
// - ObserverTick/iiwa14: ChainDynamics::update plus ObserverUpdate/0, the whole per-tick cost of
//   a controller that needs nothing else.
// The figures quoted in docs/dynamics.md come from `bench_dynamics --benchmark_min_time=0.5`.

#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/momentum_observer.hpp"
#include "mjarm/dynamics/task_space.hpp"

namespace {

using namespace mjarm;

constexpr int kStates = 256;

struct Arm {
  Robot robot;
  Chain chain;
  std::vector<DataPtr> states;
  std::vector<Eigen::VectorXd> qdd;

  Arm(const char* name, const char* frame) : robot(Robot::bundled(name)), chain(robot, frame) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const mjModel& m = robot.model();
    for (int k = 0; k < kStates; ++k) {
      DataPtr d = robot.make_data();
      for (int i = 0; i < chain.size(); ++i) {
        d->qpos[chain.qpos_address(i)] =
            chain.lower()[i] + unit(rng) * (chain.upper()[i] - chain.lower()[i]);
      }
      for (int i = 0; i < m.nv; ++i) d->qvel[i] = 4.0 * unit(rng) - 2.0;
      mj_forward(&m, d.get());
      states.push_back(std::move(d));
      Eigen::VectorXd a(chain.size());
      for (int i = 0; i < chain.size(); ++i) a[i] = 10.0 * unit(rng) - 5.0;
      qdd.push_back(a);
    }
  }
};

Arm& arm(int index) {
  static Arm panda("panda", "attachment_site");
  static Arm iiwa("iiwa14", "attachment_site");
  static Arm ur5e("ur5e", "attachment_site");
  static Arm planar("planar2", "tip");
  Arm* arms[] = {&panda, &iiwa, &ur5e, &planar};
  return *arms[index];
}

void label(benchmark::State& state, const Arm& a) { state.SetLabel(a.robot.name()); }

void MjInverse(benchmark::State& state) {
  Arm& a = arm(static_cast<int>(state.range(0)));
  const mjModel& m = a.robot.model();
  DataPtr scratch = a.robot.make_data();
  std::vector<double> qacc(static_cast<std::size_t>(m.nv), 0.0);
  int k = 0;
  for (auto _ : state) {
    const mjData& d = *a.states[static_cast<std::size_t>(k)];
    for (int i = 0; i < a.chain.size(); ++i)
      qacc[static_cast<std::size_t>(a.chain.dof_address(i))] =
          a.qdd[static_cast<std::size_t>(k)][i];
    mju_copy(scratch->qpos, d.qpos, m.nq);
    mju_copy(scratch->qvel, d.qvel, m.nv);
    mju_copy(scratch->qacc, qacc.data(), m.nv);
    mj_inverse(&m, scratch.get());
    benchmark::DoNotOptimize(scratch->qfrc_inverse[0]);
    k = (k + 1) % kStates;
  }
  label(state, a);
}

void ChainInverseDynamics(benchmark::State& state) {
  Arm& a = arm(static_cast<int>(state.range(0)));
  ChainDynamics dyn(a.chain);
  Eigen::VectorXd tau(a.chain.size());
  int k = 0;
  for (auto _ : state) {
    dyn.inverse_dynamics(*a.states[static_cast<std::size_t>(k)], a.qdd[static_cast<std::size_t>(k)],
                         tau);
    benchmark::DoNotOptimize(tau.data());
    k = (k + 1) % kStates;
  }
  label(state, a);
}

void MjRne(benchmark::State& state) {
  Arm& a = arm(static_cast<int>(state.range(0)));
  const mjModel& m = a.robot.model();
  std::vector<double> out(static_cast<std::size_t>(m.nv));
  int k = 0;
  for (auto _ : state) {
    mjData* d = a.states[static_cast<std::size_t>(k)].get();
    mj_rne(&m, d, 1, out.data());
    benchmark::DoNotOptimize(out.data());
    k = (k + 1) % kStates;
  }
  label(state, a);
}

void ChainDynamicsUpdate(benchmark::State& state) {
  Arm& a = arm(static_cast<int>(state.range(0)));
  ChainDynamics dyn(a.chain);
  int k = 0;
  for (auto _ : state) {
    dyn.update(*a.states[static_cast<std::size_t>(k)]);
    benchmark::DoNotOptimize(dyn.bias_acceleration().data());
    k = (k + 1) % kStates;
  }
  label(state, a);
}

void TaskSpaceUpdate(benchmark::State& state) {
  Arm& a = arm(static_cast<int>(state.range(0)));
  // one ChainDynamics per state, updated beforehand: only Λ, J̄, N are timed
  std::vector<ChainDynamics> dyn(kStates, ChainDynamics(a.chain));
  for (int k = 0; k < kStates; ++k)
    dyn[static_cast<std::size_t>(k)].update(*a.states[static_cast<std::size_t>(k)]);
  TaskSpaceDynamics ts(a.chain.size(), 6);
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ts.update(dyn[static_cast<std::size_t>(k)]));
    k = (k + 1) % kStates;
  }
  label(state, a);
}

void ObserverUpdate(benchmark::State& state) {
  Arm& a = arm(1);
  MomentumObserverOptions options;
  options.coriolis = state.range(0) == 0 ? CoriolisMethod::subtree_momentum
                                         : CoriolisMethod::directional_difference;
  std::vector<ChainDynamics> dyn(kStates, ChainDynamics(a.chain));
  for (int k = 0; k < kStates; ++k)
    dyn[static_cast<std::size_t>(k)].update(*a.states[static_cast<std::size_t>(k)]);
  MomentumObserver observer(a.chain, options);
  int k = 0;
  for (auto _ : state) {
    const auto i = static_cast<std::size_t>(k);
    benchmark::DoNotOptimize(observer.update(*a.states[i], dyn[i], a.qdd[i], 0.002));
    k = (k + 1) % kStates;
  }
  state.SetLabel(options.coriolis == CoriolisMethod::subtree_momentum
                     ? "iiwa14 subtree momentum"
                     : "iiwa14 directional difference");
}

void ObserverTick(benchmark::State& state) {
  Arm& a = arm(1);
  ChainDynamics dyn(a.chain);
  MomentumObserver observer(a.chain);
  int k = 0;
  for (auto _ : state) {
    const auto i = static_cast<std::size_t>(k);
    dyn.update(*a.states[i]);
    benchmark::DoNotOptimize(observer.update(*a.states[i], dyn, a.qdd[i], 0.002));
    k = (k + 1) % kStates;
  }
  label(state, a);
}

}  // namespace

BENCHMARK(ObserverUpdate)->DenseRange(0, 1);
BENCHMARK(ObserverTick);
BENCHMARK(MjInverse)->DenseRange(0, 3);
BENCHMARK(ChainInverseDynamics)->DenseRange(0, 3);
BENCHMARK(MjRne)->DenseRange(0, 3);
BENCHMARK(ChainDynamicsUpdate)->DenseRange(0, 3);
BENCHMARK(TaskSpaceUpdate)->DenseRange(0, 3);
