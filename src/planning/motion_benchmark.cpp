#include "mjarm/planning/motion_benchmark.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/planning/waypoint_planner.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/target_filter.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {

namespace {

constexpr int kBenchJoints = 7;

/// Now in ns on the steady clock or, when @p cpu, the calling thread's CPU clock.
double motion_now_ns(bool cpu) noexcept { return 1e9 * benchmark_seconds(cpu); }

Eigen::VectorXd bench_vector(unsigned seed, double scale) {
  Random rng(seed);
  Eigen::VectorXd v(MotionBenchmarkProfiles::kJoints);
  for (double& x : v) x = uniform(rng, -scale, scale);
  return v;
}

Vector6d bench_twist(double v0, double v1, double v2, double w0, double w1, double w2) {
  Vector6d V;
  V << v0, v1, v2, w0, w1, w2;
  return V;
}

/// Calls of every case so far, for the progress callback.
struct ProfileProgress {
  const ProfileBenchmarkOptions& options;
  std::int64_t done = 0;
  std::int64_t total = 0;
};

/// Times @p call(k) for k = 0, 1, … in blocks (see the file comment) and fills @p out's
/// figures. @p between(k) runs untimed after each block, then the progress report and the stop
/// request. Returns false when stopped (the figures cover the blocks done).
template <class Call, class Between>
bool time_case(const ProfileBenchmarkOptions& o, ProfileBenchmarkCase& out, Call&& call,
               Between&& between, ProfileProgress& progress) {
  const std::int64_t blocks = o.calls / o.block;
  std::vector<double> per_call;
  per_call.reserve(static_cast<std::size_t>(blocks));
  double total = 0.0;
  std::int64_t k = 0;
  const std::uint64_t a0 = o.allocation_count ? o.allocation_count() : 0;
  bool stopped = false;
  for (std::int64_t b = 0; b < blocks; ++b) {
    const double t0 = motion_now_ns(o.thread_cpu_clock);
    for (int i = 0; i < o.block; ++i) call(k++);
    const double t1 = motion_now_ns(o.thread_cpu_clock);
    total += t1 - t0;
    per_call.push_back((t1 - t0) / o.block);
    between(k);
    progress.done += o.block;
    if (progress.options.progress) progress.options.progress(progress.done, progress.total);
    if (o.stop && o.stop()) {
      stopped = true;
      break;
    }
  }
  const std::uint64_t a1 = o.allocation_count ? o.allocation_count() : 0;
  out.calls = k;
  out.mean_ns = k > 0 ? total / static_cast<double>(k) : 0.0;
  std::vector<double> sorted = per_call;
  std::sort(sorted.begin(), sorted.end());
  out.median_ns = nearest_rank(sorted, 0.5);
  out.p99_ns = nearest_rank(sorted, 0.99);
  if (o.allocation_count && k > 0)
    out.allocations_per_call = static_cast<double>(a1 - a0) / static_cast<double>(k);
  return !stopped;
}

}  // namespace

MotionBenchmarkProfiles::MotionBenchmarkProfiles()
    : trapezoid(trap_profile(0.5)),
      v_max(Eigen::VectorXd::Constant(kJoints, 1.5)),
      a_max(Eigen::VectorXd::Constant(kJoints, 4.0)),
      synced(bench_vector(1, 2.0), bench_vector(2, 2.0), v_max, a_max),
      quintic_start{bench_vector(1, 2.0), bench_vector(3, 0.5), bench_vector(4, 2.0)},
      quintic_goal(bench_vector(2, 2.0)),
      quintic(QuinticTrajectory::to_rest(quintic_start, quintic_goal, 1.3)),
      se3(Pose::from_rotation_vector({0.4, -0.1, 0.6}, {0.3, -0.8, 0.2}),
          bench_twist(0.2, -0.1, 0.05, 1.5, 0.7, -2.0), bench_twist(-1.0, 0.5, 2.0, 3.0, -4.0, 1.0),
          Pose::from_rotation_vector({0.1, 0.3, 0.5}, {-1.2, 0.4, 1.9}), 0.8),
      ramp(SmoothRamp::Kind::smootherstep, 0.4) {}

std::array<double, 256> motion_benchmark_instants(double T) {
  Random rng(3);
  std::array<double, 256> t{};
  for (double& x : t) x = uniform(rng, -0.05 * T, 1.05 * T);
  return t;
}

ProfileBenchmarkResult run_profile_benchmark(const ProfileBenchmarkOptions& o) {
  check_fields(o);
  if (o.calls < o.block)
    throw Error("profile benchmark: calls (" + std::to_string(o.calls) +
                ") must be at least one block of " + std::to_string(o.block));
  ProfileBenchmarkResult result;
  constexpr int kEvaluationCases = 6;  // and the recalculating one
  ProfileProgress progress{o};
  progress.total = kEvaluationCases * (o.calls / o.block * o.block) + o.recalculations / 16 * 16;
  double sink = 0.0;  // every result feeds it, so that nothing is optimized away
  const auto none = [](std::int64_t) {};
  const auto add = [&](ProfileBenchmarkCase c, auto&& call, auto&& between,
                       const ProfileBenchmarkOptions* protocol = nullptr) {
    const bool finished = time_case(protocol ? *protocol : o, c, call, between, progress);
    result.cases.push_back(c);
    if (!finished) result.interrupted = true;
    return finished;
  };

  const MotionBenchmarkProfiles m;
  constexpr int n = MotionBenchmarkProfiles::kJoints;

  // the classic trapezoid, one axis
  const auto t_trap = motion_benchmark_instants(m.trapezoid.duration());
  if (!add(
          {"trapezoid", "TrapezoidProfile::at", 0, 0, 0, 0, kProfileEvaluationTargetNs, -1},
          [&](std::int64_t k) { sink += m.trapezoid.at(t_trap[k & 255]).position; }, none))
    return result;

  // seven axes finishing together
  const auto t_synced = motion_benchmark_instants(m.synced.duration());
  Eigen::VectorXd q(n), qd(n), qdd(n);
  if (!add(
          {"synced trapezoid, 7 axes", "SyncedTrapezoid::at", 0, 0, 0, 0,
           kProfileEvaluationTargetNs, -1},
          [&](std::int64_t k) {
            m.synced.at(t_synced[k & 255], q, qd, qdd);
            sink += q[0];
          },
          none))
    return result;

  // the 7-joint quintic from a moving start to rest
  const auto t_quintic = motion_benchmark_instants(m.quintic.duration());
  if (!add(
          {"quintic, 7 joints (q, qd, qdd)", "QuinticTrajectory::at", 0, 0, 0, 0,
           kProfileEvaluationTargetNs, -1},
          [&](std::int64_t k) {
            m.quintic.at(t_quintic[k & 255], q, qd, qdd);
            sink += q[0];
          },
          none))
    return result;

  // the SE(3) interpolation from a moving start (ω not parallel to the rotation axis)
  const auto t_se3 = motion_benchmark_instants(m.se3.duration());
  if (!add(
          {"SE(3) interpolation (pose, twist, rate)", "Se3Interpolation::at", 0, 0, 0, 0,
           kProfileEvaluationTargetNs, -1},
          [&](std::int64_t k) { sink += m.se3.at(t_se3[k & 255]).X_WE.p[0]; }, none))
    return result;

  // smootherstep in time
  const auto t_ramp = motion_benchmark_instants(m.ramp.duration());
  if (!add(
          {"smootherstep ramp", "SmoothRamp::at", 0, 0, 0, 0, kProfileEvaluationTargetNs, -1},
          [&](std::int64_t k) { sink += m.ramp.at(t_ramp[k & 255]).s; }, none))
    return result;

  // the viewer's target filter: a tick along a motion under way
  const Pose start = Pose::from_rotation_vector({0.3, 0.0, 0.5}, {3.0, 0.0, 0.0});
  const Pose jump = Pose::from_rotation_vector({0.6, 0.2, 0.3}, {2.2, 0.5, 0.4});
  TargetFilter filter;
  const auto restart = [&] {
    filter.reset(start);
    filter.update(jump, 1e-7);  // the recalculation, untimed
  };
  restart();
  if (!add(
          {"target filter, tick in motion (6 DoF)", "TargetFilter::update", 0, 0, 0, 0,
           kProfileEvaluationTargetNs, -1},
          [&](std::int64_t) { sink += filter.update(jump, 1e-7).p[0]; },
          [&](std::int64_t) {
            if (filter.settled()) restart();
          }))
    return result;

  // …and a tick whose target moved: a 6-DoF recalculation every call
  restart();
  const Pose other = Pose::from_rotation_vector({0.5, -0.1, 0.4}, {2.8, -0.3, 0.1});
  ProfileBenchmarkOptions recalculating = o;
  recalculating.calls = o.recalculations;
  recalculating.block = 16;
  if (!add(
          {"target filter, target moved (6-DoF recalculation)", "TargetFilter::update", 0, 0, 0, 0,
           kFilterRecalculationTargetNs, -1},
          [&](std::int64_t k) { sink += filter.update((k & 1) ? jump : other, 1e-4).p[0]; }, none,
          &recalculating))
    return result;
  volatile double keep = sink;  // the calls' results are used: nothing is optimized away
  (void)keep;
  return result;
}

std::vector<Pose> motion_benchmark_waypoints(const Eigen::Matrix3d& R_WE) {
  std::vector<Pose> path;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.45, 0.0, 0.50), Eigen::Vector3d(0.45, 0.20, 0.40),
        Eigen::Vector3d(0.35, 0.25, 0.35), Eigen::Vector3d(0.30, 0.10, 0.45),
        Eigen::Vector3d(0.40, -0.15, 0.50)}) {
    Pose X;
    X.R = R_WE;
    X.p = p;
    path.push_back(X);
  }
  return path;
}

MotionBenchmarkPath motion_benchmark_path(const Robot& robot) {
  Chain chain(robot, "attachment_site");
  const std::vector<double> home = robot.keyframe_qpos("home");
  Eigen::VectorXd q_home = chain.gather(home.data());
  ChainKinematics fk(chain);
  std::vector<Pose> waypoints = motion_benchmark_waypoints(fk.update(q_home).R);
  return {std::move(chain), std::move(q_home), std::move(waypoints)};
}

PlanBenchmarkResult run_plan_benchmark(const PlanBenchmarkOptions& o) {
  check_fields(o);
  PlanBenchmarkResult out;
  const Robot robot = Robot::bundled("panda_torque");
  const MotionBenchmarkPath problem = motion_benchmark_path(robot);
  const Eigen::VectorXd& q_home = problem.q_home;
  const std::vector<Pose>& path = problem.waypoints;
  WaypointPlanner planner(problem.chain);
  out.model = robot.name();
  out.waypoints = static_cast<int>(path.size());
  PlanResult plan = planner.plan(q_home, path);  // untimed: warms caches, checks the path
  out.ok = plan.ok();
  out.message = plan.message;
  out.duration = plan.trajectory.duration();
  out.samples = plan.samples;
  if (!out.ok) return out;
  std::vector<double> ms;
  for (int k = 0; k < o.plans; ++k) {
    const double t0 = motion_now_ns(o.thread_cpu_clock);
    plan = planner.plan(q_home, path);
    const double t1 = motion_now_ns(o.thread_cpu_clock);
    ms.push_back((t1 - t0) * 1e-6);
    if (!plan.ok()) {
      out.ok = false;
      out.message = plan.message;
      break;
    }
    if (o.progress) o.progress(k + 1, o.plans);
    if (o.stop && o.stop()) {
      out.interrupted = true;
      break;
    }
  }
  out.plans = static_cast<int>(ms.size());
  double total = 0.0;
  for (double v : ms) total += v;
  out.mean_ms = ms.empty() ? 0.0 : total / static_cast<double>(ms.size());
  std::sort(ms.begin(), ms.end());
  out.median_ms = nearest_rank(ms, 0.5);
  out.p99_ms = nearest_rank(ms, 0.99);
  out.max_ms = ms.empty() ? 0.0 : ms.back();
  return out;
}

}  // namespace mjarm
