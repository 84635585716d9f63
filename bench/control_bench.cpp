// Controllers of the control room, their dynamics building blocks, and closed-loop stepping.
//
// Protocol (also in every benchmark's label):
// - Model: the bundled panda_torque (7 motors, gear 1), chain to attachment_site.
// - States: 64 drawn once (std::mt19937_64 seed 2024): joints uniform within 90 % of their ranges,
//   joint speeds uniform in [−1, 1] rad/s, states in contact with the floor redrawn; each kept in
//   its own mjData after mj_forward, cycled in order (one iteration = one state).
// - References: per state, a desired pose up to 0.1 m and 0.5 rad away, random desired twist,
//   acceleration and wrench, joint reference at mid-range.
// - Cases: ChainDynamics::update, TaskSpaceDynamics::update (6 and 3 rows), and
//   Controller::compute of every controller in `default_benchmark_controllers` (default options),
//   and the SE(3) impedance, HQP-AC and CIC controllers again on the bundled iiwa14_torque (same
//   protocol: issue 13's per-tick targets are on the iiwa14; the observer's is timed in
//   bench_dynamics, ObserverTick);
//   then one physics step from home: mj_step alone (constant torque = bias forces at home, so the
//   arm stays near home), and mj_step1 + OSC compute + mj_step2 with the torque applied (the
//   closed loop of `mjarm bench control`, here holding the home pose).
// Run: build-<you>/bench_control [--benchmark_min_time=0.5]
// `mjarm bench control panda` times the same controllers per call in closed loop on a moving
// reference and reports median/p99; docs/control.md keeps the figures.

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <memory>
#include <random>
#include <vector>

#include "mjarm/control/cartesian_impedance.hpp"
#include "mjarm/control/control_benchmark.hpp"
#include "mjarm/control/hqp_ac.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/control/se3_impedance.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/task_space.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace {

constexpr int kStates = 64;

/// 64 random contact-free states of a bundled torque model and a reference per state.
struct Scene {
  mjarm::Robot robot;
  mjarm::Chain chain;
  std::vector<mjarm::DataPtr> states;
  std::vector<mjarm::Reference> references;

  explicit Scene(const char* model)
      : robot(mjarm::Robot::bundled(model)), chain(robot, "attachment_site") {
    const mjModel& m = robot.model();
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    while (static_cast<int>(states.size()) < kStates) {
      mjarm::DataPtr d = robot.make_data();
      for (int i = 0; i < chain.size(); ++i) {
        const double lo = chain.lower()[i], hi = chain.upper()[i];
        d->qpos[chain.qpos_address(i)] = 0.5 * (lo + hi) + 0.45 * (hi - lo) * (2 * unit(rng) - 1);
        d->qvel[chain.dof_address(i)] = 2 * unit(rng) - 1;
      }
      mj_forward(&m, d.get());
      if (d->ncon > 0) continue;
      const int site = chain.frame().id;
      mjarm::Reference r;
      r.task.X_WE.p =
          Eigen::Map<const Eigen::Vector3d>(d->site_xpos + 3 * site) +
          0.1 * unit(rng) * Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
      r.task.X_WE.R =
          Eigen::AngleAxisd(0.5 * unit(rng), Eigen::Vector3d(unit(rng), unit(rng), 1).normalized())
              .toRotationMatrix() *
          Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * site);
      for (int k = 0; k < 6; ++k) {
        r.task.V_WE[k] = unit(rng) - 0.5;
        r.task.A_WE[k] = 2 * unit(rng) - 1;
        r.task.F_ext[k] = 5 * unit(rng);
      }
      r.joint.q = chain.center();
      r.joint.qd = Eigen::VectorXd::Zero(chain.size());
      r.joint.qdd = Eigen::VectorXd::Zero(chain.size());
      states.push_back(std::move(d));
      references.push_back(std::move(r));
    }
  }
};

Scene& scene() {
  static Scene s("panda_torque");
  return s;
}

Scene& iiwa_scene() {
  static Scene s("iiwa14_torque");
  return s;
}

void BM_ChainDynamicsUpdate(benchmark::State& state) {
  Scene& s = scene();
  mjarm::ChainDynamics dyn(s.chain);
  int k = 0;
  for (auto _ : state) {
    dyn.update(*s.states[k]);
    benchmark::DoNotOptimize(dyn.bias_acceleration().data());
    k = (k + 1) % kStates;
  }
  state.SetLabel("panda, 64 random states");
}
BENCHMARK(BM_ChainDynamicsUpdate);

void BM_TaskSpaceUpdate(benchmark::State& state) {
  Scene& s = scene();
  const int rows = static_cast<int>(state.range(0));
  mjarm::ChainDynamics dyn(s.chain);
  mjarm::TaskSpaceDynamics ts(s.chain.size(), rows);
  // the dynamics of every state read once, outside the timing
  std::vector<Eigen::MatrixXd> M, J;
  for (const auto& d : s.states) {
    dyn.update(*d);
    M.push_back(dyn.mass_matrix());
    J.push_back(dyn.jacobian().topRows(rows));
  }
  int eigen_path = 0;  // states whose Λ needed the eigendecomposition (not the Cholesky fast path)
  for (int k = 0; k < kStates; ++k) {
    ts.update(M[k], J[k]);
    eigen_path += ts.eigendecomposed() ? 1 : 0;
  }
  int k = 0;
  for (auto _ : state) {
    ts.update(M[k], J[k]);
    benchmark::DoNotOptimize(ts.nullspace().data());
    k = (k + 1) % kStates;
  }
  state.counters["eigen_path"] = eigen_path;
  state.SetLabel(rows == 6 ? "pose task, Λ, J̄, N" : "position task, Λ, J̄, N");
}
BENCHMARK(BM_TaskSpaceUpdate)->Arg(6)->Arg(3);

void BM_ControllerCompute(benchmark::State& state) {
  Scene& s = scene();
  auto controllers = mjarm::default_benchmark_controllers(s.chain);
  mjarm::Controller& c = *controllers[static_cast<std::size_t>(state.range(0))];
  mjarm::JointCommand command{mjarm::CommandKind::torque, Eigen::VectorXd::Zero(s.chain.size())};
  int k = 0;
  for (auto _ : state) {
    c.compute(*s.states[k], s.references[k], command);
    benchmark::DoNotOptimize(command.value.data());
    k = (k + 1) % kStates;
  }
  state.SetLabel(std::string(c.name()) + ", panda, 64 random states");
}
BENCHMARK(BM_ControllerCompute)->DenseRange(0, 8);

/// Runs @p c over the iiwa14 scene's states (issue 13's per-tick targets are on the iiwa14).
void run_iiwa14(benchmark::State& state, mjarm::Controller& c, const char* label) {
  Scene& s = iiwa_scene();
  mjarm::JointCommand command{mjarm::CommandKind::torque, Eigen::VectorXd::Zero(s.chain.size())};
  int k = 0;
  for (auto _ : state) {
    c.compute(*s.states[k], s.references[k], command);
    benchmark::DoNotOptimize(command.value.data());
    k = (k + 1) % kStates;
  }
  state.SetLabel(label);
}

/// The SE(3) impedance controller on the iiwa14 (issue 13's target: ≤ 5 µs per tick), same
/// protocol as the panda cases (64 random states, seed 2024, targets up to 0.1 m and 0.5 rad
/// away), with a measured wrench set so that the γ and −J_bᵀ·F_E terms run too.
void BM_Se3ImpedanceIiwa14(benchmark::State& state) {
  mjarm::Se3ImpedanceController c(iiwa_scene().chain);
  c.set_measured_wrench((mjarm::Vector6d() << 0.5, -0.3, 1.0, 0.02, 0.0, -0.01).finished());
  run_iiwa14(state, c, "se3, iiwa14, 64 random states, measured wrench");
}
BENCHMARK(BM_Se3ImpedanceIiwa14);

/// HQP-AC on the iiwa14 (target ≤ 25 µs per tick: both QPs, the adaptive compliance and the
/// manipulability gradient), default options, no force source; the states jump from one to the
/// next, so every warm start starts from another state's working set.
void BM_HqpAcIiwa14(benchmark::State& state) {
  mjarm::HqpAcController c(iiwa_scene().chain);

  run_iiwa14(state, c, "hqp-ac, iiwa14, 64 random states");

  state.counters["least_squares"] = static_cast<double>(c.counters().least_squares);
  state.counters["null_dropped"] = static_cast<double>(c.counters().null_space_dropped);
}
BENCHMARK(BM_HqpAcIiwa14);

/// CIC on the iiwa14, default options (natural inertia; no friction in the model, so no integral
/// and no feed-forward), no force source.
void BM_CicIiwa14(benchmark::State& state) {
  mjarm::CartesianImpedanceController c(iiwa_scene().chain);
  run_iiwa14(state, c, "cic, iiwa14, 64 random states");
}
BENCHMARK(BM_CicIiwa14);

/// One physics step from home, alone or with OSC in the loop (fixed target: home pose).
void BM_Step(benchmark::State& state) {
  Scene& s = scene();
  const bool with_osc = state.range(0) != 0;
  const mjModel& m = s.robot.model();
  mjarm::DataPtr d = s.robot.make_data();
  mj_resetDataKeyframe(&m, d.get(), s.robot.keyframe("home"));
  mj_forward(&m, d.get());
  mjarm::OperationalSpaceController osc(s.chain);
  mjarm::Reference ref;
  const int site = s.chain.frame().id;
  ref.task.X_WE.p = Eigen::Map<const Eigen::Vector3d>(d->site_xpos + 3 * site);
  ref.task.X_WE.R =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * site);
  mjarm::JointCommand command{mjarm::CommandKind::torque, Eigen::VectorXd::Zero(s.chain.size())};
  // without the controller, a constant torque equal to the bias forces at home keeps the arm near
  // home (no falling onto the floor, no contacts that would change the cost of a step)
  for (int i = 0; i < s.chain.size(); ++i)
    d->ctrl[*s.chain.actuator(i)] = d->qfrc_bias[s.chain.dof_address(i)];
  for (auto _ : state) {
    if (with_osc) {
      mj_step1(&m, d.get());
      osc.compute(*d, ref, command);
      for (int i = 0; i < s.chain.size(); ++i) d->ctrl[*s.chain.actuator(i)] = command.value[i];
      mj_step2(&m, d.get());
    } else {
      mj_step(&m, d.get());
    }
  }
  state.SetLabel(with_osc ? "mj_step1 + OSC + mj_step2, panda holding home"
                          : "mj_step alone, panda from home, constant home bias torque");
}
BENCHMARK(BM_Step)->Arg(0)->Arg(1);

}  // namespace
