// Inverse kinematics: one differential-IK QP step, and the global solver on the TRAC-IK protocol.
//
// Protocol (also in every benchmark's label):
// - DiffIkStep/<robot>_<case>: DiffIk on the bundled arm's attachment_site with a pose task
//   (gain 0.5) and a posture task (weight 1e-3), velocity limits 2 rad/s, dt = 0.01 s; q
//   follows the steps. One iteration = set_target + step (FK, Jacobians, QP build, dense dual
//   active-set solve, integration). Cases:
//     tracking:  the target moves on a 10 cm circle (period 3 s) around the home pose — the
//                ordinary control-loop use, few or no active bounds;
//     saturated: the target jumps every step to one of 1024 poses (FK of uniform
//                configurations, std::mt19937_64 seed 2024) — velocity limits bind on most
//                joints, the worst case for the active-set QP.
//   Goal for 7 DoF: ≤ 10 µs per step.
// - GlobalIkSolve/<robot>_<seeds>: GlobalIk (alternate LM/SQP, speed mode, 5 ms timeout,
//   tolerance 1e-5 on each of x, y, z, roll, pitch, yaw in the target frame). Targets: FK of
//   1024 uniform configurations inside the limits (seed 2024), cycled; seeds: the middle of the
//   joint ranges ("mid") or independent uniform configurations ("random", seed 2025). One
//   iteration = one solve. The counters `success` (fraction of solves meeting the tolerance
//   within the limits, checked by our own FK) and `iters` (mean local iterations) come from one
//   untimed pass over all 1024 targets. Failed solves run to the timeout and are timed like any
//   other, as in TRAC-IK's published figures (TRAC-IK 1.6.6 measured on this machine: panda
//   99.87 % / 0.38 ms, UR5 99.92 % / 0.28 ms).
// The full 10 000-sample protocol with per-robot figures is `mjarm bench ik` (ik_benchmark.hpp).
// Run: build-<you>/bench_ik [--benchmark_min_time=1]

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/ik/global_ik.hpp"

namespace {

using namespace mjarm;

constexpr int kPoses = 1024;
constexpr std::uint64_t kSeed = 2024;

std::vector<Eigen::VectorXd> uniform_configurations(const Chain& chain, int count,
                                                    std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::VectorXd> out;
  for (int k = 0; k < count; ++k) {
    Eigen::VectorXd q(chain.size());
    for (int i = 0; i < chain.size(); ++i) {
      const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
      q[i] = chain.lower()[i] + u * (chain.upper()[i] - chain.lower()[i]);
    }
    out.push_back(q);
  }
  return out;
}

std::vector<Pose> poses_of(const Chain& chain, const std::vector<Eigen::VectorXd>& qs) {
  ChainKinematics kin(chain);
  std::vector<Pose> poses;
  for (const Eigen::VectorXd& q : qs) poses.push_back(kin.update(q));
  return poses;
}

void DiffIkStep(benchmark::State& state, const std::string& robot, bool saturated) {
  const Robot model = Robot::bundled(robot);
  const Chain chain(model, "attachment_site");
  DiffIkOptions options;
  options.dt = 0.01;
  options.velocity_limit = Eigen::VectorXd::Constant(chain.size(), 2.0);
  DiffIk ik(chain, options);
  const int pose = ik.add_pose_task({}, 1.0, 1.0, 0.5);
  ik.add_posture_task(chain.center(), 1e-3);
  const std::vector<Pose> jumps = poses_of(chain, uniform_configurations(chain, kPoses, kSeed));
  const std::vector<double> home = model.keyframe_qpos("home");
  Eigen::VectorXd q = chain.gather(home.data());
  ChainKinematics kin(chain);
  Pose target = kin.update(q);
  const Eigen::Vector3d center = target.p;
  std::size_t k = 0;
  for (auto _ : state) {
    if (saturated) {
      target = jumps[k % jumps.size()];
    } else {
      const double phase = 2.0 * 3.141592653589793 * static_cast<double>(k) * options.dt / 3.0;
      target.p = center + 0.1 * Eigen::Vector3d(0.0, std::sin(phase), 1.0 - std::cos(phase));
    }
    ++k;
    ik.set_target(pose, target);
    q = ik.step(q).q_next;
    benchmark::DoNotOptimize(q.data());
  }
  state.SetLabel(robot + " diff-IK QP step, pose + posture tasks, velocity limits, " +
                 (saturated ? "target jumping (limits bind)" : "target on a circle"));
}

void GlobalIkSolve(benchmark::State& state, const std::string& robot, bool random_seeds) {
  const Chain chain(Robot::bundled(robot), "attachment_site");
  GlobalIkOptions options;  // speed mode, alternate methods, 5 ms, 1e-5 per component
  GlobalIk ik(chain, options);
  ChainKinematics kin(chain);
  const std::vector<Pose> targets = poses_of(chain, uniform_configurations(chain, kPoses, kSeed));
  const std::vector<Eigen::VectorXd> seeds = uniform_configurations(chain, kPoses, kSeed + 1);
  const Eigen::VectorXd mid = chain.center();
  IkResult result;
  // success and iterations from one untimed pass over all targets (the solver is deterministic)
  double solved = 0.0, iterations = 0.0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    ik.solve(targets[i], random_seeds ? seeds[i] : mid, result);
    solved +=
        chain.within_limits(result.q) &&
        within_tolerance(target_frame_error(kin.update(result.q), targets[i]), options.tolerance);
    iterations += result.iterations;
  }
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t i = k++ % targets.size();
    ik.solve(targets[i], random_seeds ? seeds[i] : mid, result);
    benchmark::DoNotOptimize(result.q.data());
  }
  state.counters["success"] = solved / static_cast<double>(targets.size());
  state.counters["iters"] = iterations / static_cast<double>(targets.size());
  state.SetLabel(robot + " TRAC-IK protocol, " + (random_seeds ? "random" : "mid-range") +
                 " seeds, 5 ms timeout, speed mode");
}

BENCHMARK_CAPTURE(DiffIkStep, panda_tracking, std::string("panda"), false);
BENCHMARK_CAPTURE(DiffIkStep, panda_saturated, std::string("panda"), true);
BENCHMARK_CAPTURE(DiffIkStep, iiwa14_tracking, std::string("iiwa14"), false);
BENCHMARK_CAPTURE(DiffIkStep, ur5e_tracking, std::string("ur5e"), false);
BENCHMARK_CAPTURE(GlobalIkSolve, panda_mid, std::string("panda"), false)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(GlobalIkSolve, panda_random, std::string("panda"), true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(GlobalIkSolve, iiwa14_mid, std::string("iiwa14"), false)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(GlobalIkSolve, ur5e_mid, std::string("ur5e"), false)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
