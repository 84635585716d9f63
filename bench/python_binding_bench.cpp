// The C++ side of the Python binding-overhead benchmark: the same calls, on the same inputs, as
// `python3 -m mjarm.bench` makes from Python (it runs this program and prints both columns).
//
// Protocol (the Python side repeats it exactly):
// - Model: bundled panda (FK, IK) and panda_torque (controller, simulation), chain to
//   attachment_site.
// - Configurations: 64, no random generator: joint i of configuration k is
//   lo + (hi − lo)·(0.05 + 0.9·frac(0.6180339887·(k + 1) + 0.4142135624·(i + 1))).
// - Fk: ChainKinematics::update on configuration k (cycled).
// - PositionIk: PositionIk (default options) from the home keyframe to the frame position of
//   configuration k (cycled).
// - ControllerStep: OperationalSpaceController::compute (default options) at the home state of
//   panda_torque after mj_forward, reference = the home pose moved 5 cm along x.
// - TickLoop: Simulation in torque mode, control period = timestep (2 ms), JointPdController
//   (default options) holding the home keyframe with a fixed Reference; 5000 ticks per
//   iteration (10 s simulated). Counter rtf = simulated time / wall time.
// - EnvStep: Environment "reach" with joint_torques actions, control period = the physics
//   timestep (one physics step per call: the cheapest step there is, so that the binding's
//   share shows), time limit 2 s (1000 steps an episode), zero action; a LAST step is followed
//   by reset(0) (timed too, once per 1000 steps). The first step follows reset(0).
// - EnvStepReach: the same loop on the default reach environment (ee_pose_deltas, T = 20 ms,
//   10 physics steps, the QP and the operational-space controller), 500 steps an episode.
//   The environment figures compared are CPU times (Google Benchmark's cpu_time here, the
//   thread CPU clock in Python): the wall time of a 15–200 µs call on a shared machine varies
//   by more than the binding's cost.
// Run: build/bench_python_binding [--benchmark_min_time=0.5]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "mjarm/control/joint_pd.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/ik/position_ik.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/sim/simulation.hpp"

namespace {

std::vector<Eigen::VectorXd> configurations(const mjarm::Chain& chain) {
  std::vector<Eigen::VectorXd> qs;
  for (int k = 0; k < 64; ++k) {
    Eigen::VectorXd q(chain.size());
    for (int i = 0; i < chain.size(); ++i) {
      const double x = 0.6180339887 * (k + 1) + 0.4142135624 * (i + 1);
      const double lo = chain.lower()[i], hi = chain.upper()[i];
      q[i] = lo + (hi - lo) * (0.05 + 0.9 * (x - std::floor(x)));
    }
    qs.push_back(q);
  }
  return qs;
}

void BM_Fk(benchmark::State& state) {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  const mjarm::Chain chain(robot, "attachment_site");
  mjarm::ChainKinematics kin(chain);
  const auto qs = configurations(chain);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(kin.update(qs[k]).p.data());
    k = (k + 1) % qs.size();
  }
  state.SetLabel("ChainKinematics::update, panda");
}
BENCHMARK(BM_Fk);

void BM_PositionIk(benchmark::State& state) {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  const mjarm::Chain chain(robot, "attachment_site");
  mjarm::ChainKinematics kin(chain);
  std::vector<Eigen::Vector3d> targets;
  for (const auto& q : configurations(chain)) targets.push_back(kin.update(q).p);
  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd seed = chain.gather(home.data());
  mjarm::PositionIk ik(chain);
  mjarm::IkResult result;
  std::size_t k = 0;
  for (auto _ : state) {
    ik.solve(targets[k], seed, result);
    benchmark::DoNotOptimize(result.q.data());
    k = (k + 1) % targets.size();
  }
  state.SetLabel("PositionIk::solve from home, panda, 64 targets");
}
BENCHMARK(BM_PositionIk);

void BM_ControllerStep(benchmark::State& state) {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda_torque");
  const mjarm::Chain chain(robot, "attachment_site");
  mjarm::DataPtr d = robot.make_data();
  const std::vector<double> home = robot.keyframe_qpos("home");
  std::copy(home.begin(), home.end(), d->qpos);
  mj_forward(&robot.model(), d.get());
  mjarm::ChainKinematics kin(chain);
  mjarm::Reference ref;
  ref.task.X_WE = kin.update(chain.gather(home.data()));
  ref.task.X_WE.p.x() += 0.05;
  ref.joint.q = chain.gather(home.data());
  ref.joint.qd = ref.joint.qdd = Eigen::VectorXd::Zero(chain.size());
  mjarm::OperationalSpaceController osc(chain);
  mjarm::JointCommand command{mjarm::CommandKind::torque, Eigen::VectorXd::Zero(chain.size())};
  for (auto _ : state) {
    osc.compute(*d, ref, command);
    benchmark::DoNotOptimize(command.value.data());
  }
  state.SetLabel("OperationalSpaceController::compute, panda_torque at home");
}
BENCHMARK(BM_ControllerStep);

void BM_TickLoop(benchmark::State& state) {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda_torque");
  const mjarm::Chain chain(robot, "attachment_site");
  mjarm::SimulationOptions options;
  options.mode = mjarm::SimulationMode::torque;
  mjarm::Simulation sim(robot, options);
  mjarm::JointPdController pd(chain);
  sim.add_controller(pd);
  const std::vector<double> home = robot.keyframe_qpos("home");
  mjarm::Reference ref;
  ref.joint.q = chain.gather(home.data());
  ref.joint.qd = ref.joint.qdd = Eigen::VectorXd::Zero(chain.size());
  constexpr int kTicks = 5000;
  double simulated = 0.0, wall = 0.0;
  for (auto _ : state) {
    sim.reset("home");
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kTicks; ++i) benchmark::DoNotOptimize(sim.tick(ref).time);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    simulated += sim.time();
  }
  state.counters["rtf"] = simulated / wall;
  state.counters["tick_us"] = 1e6 * wall / (static_cast<double>(state.iterations()) * kTicks);
  state.SetLabel("Simulation::tick x5000, torque mode, JointPd, panda_torque, 2 ms");
}
BENCHMARK(BM_TickLoop)->Unit(benchmark::kMillisecond);

/// One environment step per iteration, reset(0) after LAST (the Python side's loop).
void env_loop(benchmark::State& state, mjarm::Environment& env) {
  const std::vector<double> action(static_cast<std::size_t>(env.action_spec().size()), 0.0);
  env.reset(0);
  for (auto _ : state) {
    if (env.step(action).last()) env.reset(0);
  }
}

void BM_EnvStep(benchmark::State& state) {
  mjarm::EnvironmentOptions options;
  options.action_space = mjarm::ActionSpace::joint_torques;
  options.control_period = 0.002;
  options.time_limit = 2.0;
  mjarm::Environment env("reach", options);
  env_loop(state, env);
  state.SetLabel("Environment::step, reach, joint_torques, T = h (1 physics step)");
}
BENCHMARK(BM_EnvStep);

void BM_EnvStepReach(benchmark::State& state) {
  mjarm::EnvironmentOptions options;
  mjarm::Environment env("reach", options);
  env_loop(state, env);
  state.SetLabel("Environment::step, reach defaults (ee_pose_deltas, T = 20 ms, 10 physics steps)");
}
BENCHMARK(BM_EnvStepReach);

}  // namespace
