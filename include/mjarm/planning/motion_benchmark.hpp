#pragma once
/// @file
/// The motion benchmarks (`mjarm bench traj`, `mjarm bench plan`): what one evaluation of each
/// motion profile costs per call, what the viewer's target filter costs per tick, and what
/// planning the 5-waypoint path on the panda costs — each against a target.
///
/// Profiles. Each case is built once (seeded, 7 joints where it has joints), then evaluated at
/// 256 seeded instants spread over [−0.05·T, 1.05·T] (the clamped ends included), cycled. The
/// calls are timed in blocks of `block` calls (one clock read per block, so the ~20–40 ns of a
/// clock read do not swamp a 5 ns call); per-call figures are block time ÷ block: the median and
/// the 99th percentile (nearest rank) over the blocks, and the mean over all calls. The target
/// filter is measured twice: a tick along a motion under way (a jump of 0.4 m and 1.2 rad
/// followed at dt = 0.1 µs, restarted untimed whenever it settled), and a tick whose target moved
/// (two targets alternating, so the jerk-limited generator is recalculated for 6 DoF at every
/// call). The allocation hook, when given, is read around each case's timed calls.
///
/// Planning. `WaypointPlanner::plan` on the bundled `panda_torque` (tool frame
/// `attachment_site`) from its `home` keyframe through the positions of
/// `motion_benchmark_waypoints` with the tool's home orientation, default `PlanOptions`; each
/// plan timed alone.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {

/// The seeded profiles the profile benchmark evaluates (`mjarm bench traj` here, and the Google
/// Benchmark binary bench_trajectory): built once, the same in both.
struct MotionBenchmarkProfiles {
  static constexpr int kJoints = 7;  ///< joints of the multi-axis profiles
  /// Builds them (see each member).
  MotionBenchmarkProfiles();

  /// The classic trapezoid over 0.5 m (defaults v_max = 0.18 m/s, a_max = 0.9 m/s²).
  TrapezoidProfile trapezoid;
  Eigen::VectorXd v_max;  ///< 1.5 rad/s per joint (the synced trapezoid, the shortest quintic)
  Eigen::VectorXd a_max;  ///< 4 rad/s² per joint
  /// Seven axes between seeded positions in [−2, 2] rad, finishing together.
  SyncedTrapezoid synced;
  QuinticTrajectory::State quintic_start;  ///< seeded q, q̇, q̈ (7 joints)
  Eigen::VectorXd quintic_goal;            ///< seeded rest position (7 joints) [rad]
  QuinticTrajectory quintic;               ///< quintic_start → quintic_goal at rest, 1.3 s
  /// From a moving start (ω not parallel to the rotation axis) over 0.8 s.
  Se3Interpolation se3;
  SmoothRamp ramp;  ///< smootherstep over 0.4 s
};

/// 256 seeded instants spread over [−0.05·T, 1.05·T] for a profile of duration @p T [s] (the
/// clamped ends included), evaluated cycled.
std::array<double, 256> motion_benchmark_instants(double T);

/// Settings of `run_profile_benchmark`.
struct ProfileBenchmarkOptions {
  std::int64_t calls = 2000000;  ///< timed calls per evaluation case (≥ block)
  int block = 256;               ///< calls per clock read (≥ 1)
  /// Timed calls of the recalculating target-filter case (≥ 16; timed in blocks of 16: one
  /// call costs about as much as a few hundred evaluations).
  std::int64_t recalculations = 20000;
  bool thread_cpu_clock = false;  ///< the thread's CPU clock instead of the steady wall clock
  /// Allocation counter of the process (e.g. a replaced malloc's call count). Empty: not counted.
  std::function<std::uint64_t()> allocation_count;
  /// Called after each block with (timed calls done, timed calls of every case), untimed; may
  /// be empty.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
  /// Asked after each block whether to stop (e.g. after Ctrl-C); may be empty. The case under
  /// way is then kept with the blocks it timed, and no later case runs.
  std::function<bool()> stop;
};

/// The numeric fields of `ProfileBenchmarkOptions`; calls ≥ block is checked by hand.
constexpr auto declared_fields(const ProfileBenchmarkOptions*) {
  using S = ProfileBenchmarkOptions;
  return declare<S>(
      "profile benchmark",
      field("calls", &S::calls, "", Range::at_least(1), "timed calls per evaluation case"),
      field("block", &S::block, "", Range::at_least(1), "calls per clock read"),
      field("recalculations", &S::recalculations, "", Range::at_least(16),
            "timed calls of the recalculating target-filter case"),
      field("thread_cpu_clock", &S::thread_cpu_clock,
            "the thread's CPU clock instead of the steady wall clock"));
}

/// Figures of one case.
struct ProfileBenchmarkCase {
  std::string name;                    ///< "trapezoid", "quintic, 7 joints", …
  std::string call;                    ///< the function timed ("TrapezoidProfile::at")
  std::int64_t calls = 0;              ///< timed calls
  double median_ns = 0.0;              ///< median per-call time over the blocks [ns]
  double p99_ns = 0.0;                 ///< 99th percentile over the blocks [ns]
  double mean_ns = 0.0;                ///< mean per-call time [ns]
  double target_ns = 0.0;              ///< the target for the median [ns]
  double allocations_per_call = -1.0;  ///< −1: not counted
};

/// Figures of the profile benchmark.
struct ProfileBenchmarkResult {
  /// the stop request ended it: the cases are those begun, the last with the calls it timed
  bool interrupted = false;
  std::vector<ProfileBenchmarkCase> cases;  ///< in the order of the file comment
};

/// The per-call target of profile evaluation: 1 µs, a thousandth of a 1 kHz control tick.
inline constexpr double kProfileEvaluationTargetNs = 1000.0;
/// The per-tick target of the target filter when its target moved (a 6-DoF recalculation of the
/// jerk-limited generator): 10 µs, a hundredth of a 1 kHz control tick.
inline constexpr double kFilterRecalculationTargetNs = 10000.0;
/// The target for planning the 5-waypoint path on the panda: 100 ms (a replan in interactive
/// time).
inline constexpr double kPlanTargetMs = 100.0;

/// Runs the profile cases (see the file comment).
/// @throws Error when calls < block, block < 1 or recalculations < 16.
ProfileBenchmarkResult run_profile_benchmark(const ProfileBenchmarkOptions& options);

/// Settings of `run_plan_benchmark`.
struct PlanBenchmarkOptions {
  int plans = 50;                 ///< timed plans (≥ 1), after one untimed
  bool thread_cpu_clock = false;  ///< the thread's CPU clock instead of the steady wall clock
  /// Called after each plan with (done, total); may be empty.
  std::function<void(int done, int total)> progress;
  /// Asked after each plan whether to stop; may be empty.
  std::function<bool()> stop;
};

constexpr auto declared_fields(const PlanBenchmarkOptions*) {
  using S = PlanBenchmarkOptions;
  return declare<S>("plan benchmark",
                    field("plans", &S::plans, "", Range::at_least(1), "timed plans"),
                    field("thread_cpu_clock", &S::thread_cpu_clock,
                          "the thread's CPU clock instead of the steady wall clock"));
}

/// Figures of the planning benchmark.
struct PlanBenchmarkResult {
  bool ok = false;                   ///< every plan succeeded (else `message` says why)
  bool interrupted = false;          ///< the stop request ended it
  std::string message;               ///< the plan's status message
  std::string model;                 ///< "panda_torque"
  int waypoints = 0;                 ///< 5
  int plans = 0;                     ///< timed plans
  double median_ms = 0.0;            ///< per plan [ms]
  double p99_ms = 0.0;               ///< 99th percentile (nearest rank) [ms]
  double mean_ms = 0.0;              ///< [ms]
  double max_ms = 0.0;               ///< [ms]
  double target_ms = kPlanTargetMs;  ///< the target for the median [ms]
  double duration = 0.0;             ///< the planned trajectory's duration [s]
  int samples = 0;                   ///< states checked per plan
};

/// Runs the planning benchmark (see the file comment).
/// @throws Error when plans < 1.
PlanBenchmarkResult run_plan_benchmark(const PlanBenchmarkOptions& options);

/// The planning benchmark's problem on one robot: its chain to `attachment_site`, the `home`
/// keyframe and the waypoints of `motion_benchmark_waypoints` with the tool's home rotation.
struct MotionBenchmarkPath {
  Chain chain;                  ///< the robot's joints to `attachment_site`
  Eigen::VectorXd q_home;       ///< the `home` keyframe on the chain [rad]
  std::vector<Pose> waypoints;  ///< the five waypoints
};

/// The planning benchmark's problem on @p robot (a panda: `mjarm bench plan` uses the bundled
/// `panda_torque`; bench_planning also a panda with a box in the way).
/// @throws Error when the robot has no `attachment_site` or `home` keyframe.
MotionBenchmarkPath motion_benchmark_path(const Robot& robot);

/// The 5 waypoints of the planning benchmark on the panda: positions [m] in the world frame
/// (0.45, 0, 0.5), (0.45, 0.2, 0.4), (0.35, 0.25, 0.35), (0.3, 0.1, 0.45), (0.4, −0.15, 0.5),
/// each with the tool rotation @p R_WE (its rotation at home in the benchmark).
std::vector<Pose> motion_benchmark_waypoints(const Eigen::Matrix3d& R_WE);

}  // namespace mjarm
